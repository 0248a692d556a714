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
      {"GenerateGrid", "engine", "SOFA's grid of resolution = (L, W, H) cells over [min, max]: output_position (alias position), hexahedra and tetrahedra (6 per hexahedron), or for H = 0 quads and triangles (2 per quad), in SOFA's order (cells x slowest, z fastest).",
       {{"min", "vec3", "0 0 0", "minimum corner"},
        {"max", "vec3", "0 0 0", "maximum corner"},
        {"resolution", "int3", "3 3 3", "cells along x, y, z (x, y >= 1; z = 0: a flat grid of quads)"}}},
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
      {"SphereROI", "engine",
       "Selects the points and elements inside balls (|p - c| <= r), with BoxROI's outputs and rules (indices, also "
       "pointIndices; pointsInROI, nbIndices, indicesOut, pointsOutROI, and per element kind its indices and the elements in "
       "and out); edges within edgeAngle of direction and triangles within triAngle of normal are left out when those "
       "angles are set.",
       {{"centers", "vec3s", "", "the balls' centres"},
        {"radii", "reals", "", "their radii (one for all, or one each)"},
        {"direction", "vec3", "0 0 0", "with edgeAngle: the edges' direction to leave out"},
        {"normal", "vec3", "0 0 0", "with triAngle: the triangles' normal to leave out"},
        {"edgeAngle", "real", "0", "degrees (0: no filter)"},
        {"triAngle", "real", "0", "degrees (0: no filter); also angle"},
        {"angle", "real", "0", "triAngle (SOFA's other name)"},
        {"position", "vec3s", "", "points to test (default: the node's rest positions); also rest_position"},
        {"rest_position", "vec3s", "", "position (SOFA's other name)"},
        {"strict", "bool", "true", "an element is inside when all its points are (else its centre)"},
        {"edges", "indices", "", "edges to test (default: the node's topology's)"},
        {"triangles", "indices", "", "triangles to test (default: the node's triangle container's, else its topology's)"},
        {"quads", "indices", "", "quads to test (default: the node's topology's)"},
        {"tetrahedra", "indices", "", "tetrahedra to test (default: the node's topology's)"},
        {"hexahedra", "indices", "", "hexahedra to test (default: the node's topology's)"},
        {"computeEdges", "bool", "true", "select edges"},
        {"computeTriangles", "bool", "true", "select triangles"},
        {"computeQuads", "bool", "true", "select quads"},
        {"computeTetrahedra", "bool", "true", "select tetrahedra"},
        {"computeHexahedra", "bool", "true", "select hexahedra"},
        {"drawSphere", "bool", "false", "accepted (display); also isVisible"},
        {"isVisible", "bool", "false", "accepted (display)"},
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
        {"computeTetrahedra", "bool", "true", "select tetrahedra"}}},
      {"SubsetTopology", "engine",
       "Selects the points and elements (all their points in one same region) inside boxes or, when centers is "
       "given, spheres (bounds included); outputs indices, pointsInROI, pointsOutROI, nbrborder and per element "
       "kind its indices and the elements in and out (edgeIndices, edgesInROI, edgesOutROI, triangle..., quad..., "
       "tetrahedron... (tetrahedraInROI, tetrahedraOutROI), hexahedron...). With localIndices the elements are "
       "renumbered for the two sub-meshes, the border points (in the first region, on an element crossing it) first "
       "in both point lists; Vec3 only.",
       {{"box", "reals", "0 0 0 1 1 1", "xmin ymin zmin xmax ymax zmax, 6 numbers per box"},
        {"centers", "vec3s", "", "sphere centres (given: spheres replace the boxes)"},
        {"radii", "reals", "", "one radius per centre"},
        {"rest_position", "vec3s", "", "points to select (default: the position of the MechanicalObject at or above the node)"},
        {"edges", "indices", "", "edges (default: src's, else the node's topology's)"},
        {"triangles", "indices", "", "triangles (default: src's, else the node's topology's)"},
        {"quads", "indices", "", "quads (default: src's)"},
        {"tetrahedra", "indices", "", "tetrahedra (default: src's, else the node's topology's)"},
        {"hexahedra", "indices", "", "hexahedra (default: src's)"},
        {"tetrahedraInput", "indices", "", "the tetrahedra to keep, whatever the regions (point lists made from the tetrahedra)"},
        {"localIndices", "bool", "false", "renumber the output elements for the sub-meshes, border points first"},
        {"direction", "vec3", "", "accepted (SOFA does not use it)"},
        {"normal", "vec3", "", "accepted (SOFA does not use it)"},
        {"edgeAngle", "real", "0", "accepted (SOFA does not use it)"},
        {"triAngle", "real", "0", "accepted (SOFA does not use it)"},
        {"indices", "indices", "", "an output; accepted when written (SOFA replaces the value at init; here links read the value written)"}}},
      {"MeshTetraStuffing", "engine",
       "Fills a closed triangle surface with tetrahedra by isosurface stuffing (Labelle and Shewchuk 2007) as SOFA "
       "does: a body-centred cubic lattice over vbbox, points classed inside by the surface crossings along the "
       "lattice lines, snapped to the surface and tetrahedra cut at it on request; outputs outputPoints, "
       "outputTetrahedra (also outputTetras) and vbbox.",
       {{"inputPoints", "vec3s", "", "surface points"},
        {"inputTriangles", "indices", "", "surface triangles (outward normals)"},
        {"inputQuads", "indices", "", "surface quads (each a b c d counts as a b c and a c d)"},
        {"vbbox", "reals", "0 0 0 0 0 0", "xmin ymin zmin xmax ymax zmax; used when xmin < xmax, else the surface's box grown by 1%"},
        {"size", "real", "-8", "cell size; negative: -(cells across the largest extent of the box)"},
        {"alphaLong", "real", "0.24999", "snapping threshold on the grids' edges, in edge lengths"},
        {"alphaShort", "real", "0.42978", "snapping threshold on the edges between the two grids"},
        {"snapPoints", "bool", "false", "move lattice points close to the surface onto it"},
        {"splitTetrahedra", "bool", "false", "cut the tetrahedra crossing the surface; also splitTetras"},
        {"splitTetras", "bool", "false", "splitTetrahedra (SOFA's other name)"}}},
      {"MeshSplittingEngine", "engine",
       "Shares a mesh's points among nbInputs sub-meshes (the points listed in indices<i> and those of the elements "
       "listed in edgeIndices<i>, triangleIndices<i>, quadIndices<i>, tetrahedronIndices<i>, hexahedronIndices<i>; "
       "the first sub-mesh that claims a point takes it) and a last one for the rest; outputs position1 .. "
       "position<nbInputs + 1> and indexPairs (sub-mesh from 0, index in it, per point).",
       {{"position", "vec3s", "", "input points (default: src's)"},
        {"edges", "indices", "", "input edges (default: src's)"},
        {"triangles", "indices", "", "input triangles (default: src's)"},
        {"quads", "indices", "", "input quads (default: src's)"},
        {"tetrahedra", "indices", "", "input tetrahedra (default: src's)"},
        {"hexahedra", "indices", "", "input hexahedra (default: src's)"},
        {"nbInputs", "int", "0", "number of sub-meshes given by lists"},
        {"indices<N>", "indices", "", "points of sub-mesh N (1 to nbInputs)"},
        {"edgeIndices<N>", "indices", "", "edges of sub-mesh N"},
        {"triangleIndices<N>", "indices", "", "triangles of sub-mesh N"},
        {"quadIndices<N>", "indices", "", "quads of sub-mesh N"},
        {"tetrahedronIndices<N>", "indices", "", "tetrahedra of sub-mesh N"},
        {"hexahedronIndices<N>", "indices", "", "hexahedra of sub-mesh N"}}},
      {"NearestPointROI", "engine",
       "For each point of object2 (or of inputIndices2), the nearest point of object1 (or of inputIndices1; the first "
       "of equals), kept when closer than radius: outputs indices1, indices2, edges (2k, 2k + 1 by object2's index, as "
       "SOFA), indexPairs (0 i1 1 i2 per pair, for a SubsetMultiMapping) and distances.",
       {{"object1", "link", "", "the first MechanicalObject"},
        {"object2", "link", "", "the second MechanicalObject"},
        {"inputIndices1", "indices", "", "candidates of object1 (default: all)"},
        {"inputIndices2", "indices", "", "points of object2 to pair (default: all)"},
        {"radius", "real", "1", "largest distance of a pair (> 0)"},
        {"useRestPosition", "bool", "true", "compare rest positions (else positions at init)"},
        {"indices1", "indices", "", "output"},
        {"indices2", "indices", "", "output"},
        {"edges", "indices", "", "output"},
        {"indexPairs", "indices", "", "output"},
        {"distances", "reals", "", "output"},
        {"drawPairs", "bool", "false", "accepted (display)"}}},
      {"IndexValueMapper", "engine",
       "outputValues = inputValues with `value` at each of `indices` (the list grows to the largest index, gaps "
       "filled with defaultValue): per-element values such as youngModulus, layer by layer.",
       {{"inputValues", "reals", "", "the values to start from"},
        {"indices", "indices", "", "where `value` goes"},
        {"value", "real", "0", "the value"},
        {"defaultValue", "real", "1", "for the gaps when the list grows"},
        {"outputValues", "reals", "", "the result (an output)"}}},
      {"TransformEngine", "engine",
       "output_position = input_position scaled, rotated by the Euler angles, rotated by the quaternion, translated "
       "(SOFA's order; each step only when it is not the identity); with inverse the inverse steps in the opposite "
       "order. Templates Vec1, Vec2, Vec3 (default) and Rigid3 (7 numbers per rigid: a rotation also turns the "
       "orientations).",
       {{"input_position", "vec3s", "", "the points (Rigid3: x y z qx qy qz qw per rigid)"},
        {"translation", "vec3", "0 0 0", "applied last"},
        {"rotation", "vec3", "0 0 0", "Euler angles in degrees, R = Rz Ry Rx (SOFA's createQuaterFromEuler), applied after the scale"},
        {"quaternion", "reals", "0 0 0 1", "qx qy qz qw, applied after rotation (not normalised, as SOFA)"},
        {"scale", "vec3", "1 1 1", "applied first"},
        {"inverse", "bool", "false", "apply the inverse transformation"},
        {"output_position", "vec3s", "", "the result (an output)"}}},
      {"PointsFromIndices", "engine",
       "indices_position = the points of position at indices, in that order, each distinct point once (SOFA's "
       "comparison: every coordinate within 1e-6); Vec3.",
       {{"position", "vec3s", "", "the points (default: the position of the node's state, or the nearest above)"},
        {"indices", "indices", "", "the points to take"},
        {"indices_position", "vec3s", "", "the result (an output)"}}}
  };
}

}  // namespace fastcorot::scene_detail
