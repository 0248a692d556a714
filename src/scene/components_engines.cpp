// Engines: generated meshes and regions of interest.
#include "component_families.h"

namespace fastcorot::scene_detail {

std::vector<ComponentSpec> engine_components() {
  return {
      {"GenerateCylinder", "engine", "A tetrahedral cylinder along z (data tetrahedra and output_TetrahedraPosition, alias output_position), SOFA's points and tetrahedra in SOFA's order; linear tetrahedra only.",
       {{"radius", "real", "0.2", "radius"},
        {"height", "real", "1", "height"},
        {"origin", "vec3", "0 0 0", "centre of the base"},
        {"resCircumferential", "int", "6", "points around each ring (>= 3)"},
        {"resRadial", "int", "3", "rings (>= 1)"},
        {"resHeight", "int", "5", "layers of points along z (>= 2)"},
        {"openSurface", "bool", "true", "accepted (its triangle output is not made)"},
        {"BezierTetrahedronDegree", "int", "0", "only 0 or 1 (linear)"},
        {"BezierTriangleDegree", "int", "0", "only 0 or 1 (linear)"}}},
      {"PairBoxROI", "engine", "Selects the points inside inclusiveBox and not inside includedBox (bounds included).",
       {{"inclusiveBox", "reals", "", "xmin ymin zmin xmax ymax zmax"},
        {"includedBox", "reals", "", "xmin ymin zmin xmax ymax zmax"},
        {"position", "vec3s", "", "points to test (default: the node's rest positions)"},
        {"meshPosition", "vec3s", "", "accepted"},
        {"drawSize", "real", "", "accepted (display)"}}},
      {"BoxROI", "engine", "Selects the points (and tetrahedra) inside axis-aligned boxes, bounds included.",
       {{"box", "reals", "0 0 0 1 1 1", "xmin ymin zmin xmax ymax zmax, 6 numbers per box"},
        {"position", "vec3s", "", "points to test (default: the node's rest positions)"},
        {"strict", "bool", "true", "a tetrahedron or triangle is inside when all its vertices are (else its barycentre)"},
        {"triangles", "indices", "", "triangles to test for triangleIndices (default: the node's triangle container's, else its topology's)"},
        {"doUpdate", "bool", "true", "accepted; the selection is made at init"}}}
  };
}

}  // namespace fastcorot::scene_detail
