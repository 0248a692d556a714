// SOFA's SimpleTesselatedTetraTopologicalMapping: each tetrahedron cut into 8 at its edge
// midpoints. The points are the mesh's points, then one per mesh edge (in edge order, SOFA's); the
// tetrahedra are 8 per tetrahedron, 8t..8t+7 from tetrahedron t, in SOFA's order.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/topology/tet_mesh.h"

#include <span>
#include <vector>

namespace fastcorot {

struct Subdivision {
  std::vector<Vec3<double>> points;
  std::vector<Tetrahedron> tetrahedra;
};

// Throws fastcorot::Error when `points` does not have one position per mesh point.
Subdivision subdivide_tetrahedra(const TetMesh& mesh, std::span<const Vec3<double>> points);

}  // namespace fastcorot
