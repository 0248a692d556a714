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
      {"BoxROI", "engine",
       "Selects the points and elements inside axis-aligned and oriented boxes, bounds included; outputs indices, "
       "pointsInROI, nbIndices, indicesOut, pointsOutROI, and per element kind its indices, the elements in (and "
       "out: edges, triangles, tetrahedra) of the region (edgeIndices, edgesInROI, edgeOutIndices, edgesOutROI, "
       "triangle..., quadIndices, quadsInROI, tetrahedron..., hexahedronIndices, hexahedraInROI).",
       {{"box", "reals", "0 0 0 1 1 1", "xmin ymin zmin xmax ymax zmax, 6 numbers per box (no default with orientedBox)"},
        {"orientedBox", "reals", "", "p0 p1 p2 depth, 10 numbers per box: the parallelogram p0 p1 p2 (p0 + p2 - p1), depth thick"},
        {"position", "vec3s", "", "points to test (default: the node's rest positions)"},
        {"strict", "bool", "true", "an element is inside when all its points are (else its centre)"},
        {"edges", "indices", "", "edges to test (default: the node's topology's)"},
        {"triangles", "indices", "", "triangles to test (default: the node's triangle container's, else its topology's)"},
        {"quads", "indices", "", "quads to test (default: the node's topology's); also quad"},
        {"quad", "indices", "", "quads (SOFA's other name)"},
        {"tetrahedra", "indices", "", "tetrahedra to test (default: the node's topology's)"},
        {"hexahedra", "indices", "", "hexahedra to test (default: the node's topology's)"},
        {"computeEdges", "bool", "true", "select edges"},
        {"computeTriangles", "bool", "true", "select triangles"},
        {"computeQuads", "bool", "true", "select quads; also computeQuad"},
        {"computeQuad", "bool", "true", "computeQuads (SOFA's other name)"},
        {"computeTetrahedra", "bool", "true", "select tetrahedra"},
        {"computeHexahedra", "bool", "true", "select hexahedra"},
        {"doUpdate", "bool", "true", "accepted; the selection is made at init"}}},
      {"PlaneROI", "engine",
       "Selects the points inside slabs over parallelograms, bounds included, and the edges, triangles and "
       "tetrahedra with all their points in one slab; outputs indices, pointsInROI, edgeIndices, edgesInROI, "
       "triangleIndices, trianglesInROI, tetrahedronIndices, tetrahedraInROI.",
       {{"plane", "reals", "0 0 0 0 0 0 0 0 0 0", "p0 p1 p2 depth, 10 numbers per slab: the parallelogram p0 p1 p2 (p0 + p2 - p1), depth thick"},
        {"position", "vec3s", "", "points to test (default: the node's rest positions)"},
        {"edges", "indices", "", "edges to test (default: the node's topology's)"},
        {"triangles", "indices", "", "triangles to test (default: the node's triangle container's, else its topology's)"},
        {"tetrahedra", "indices", "", "tetrahedra to test (default: the node's topology's)"},
        {"computeEdges", "bool", "true", "select edges"},
        {"computeTriangles", "bool", "true", "select triangles"},
        {"computeTetrahedra", "bool", "true", "select tetrahedra"}}}
  };
}

}  // namespace fastcorot::scene_detail
