// SOFA's triangle and edge arrays of a tetrahedral mesh and its boundary, worked out by hand for
// two tetrahedra sharing a face.
#include "fastcorot/topology/tetrahedron_faces.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

TEST(TetrahedronFaces, SofasOrderRotationAndSharing) {
  const std::vector<Tetrahedron> tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  // Tetrahedron 0's faces (1 2 3), (0 3 2), (1 3 0) -> (0 1 3), (0 2 1); tetrahedron 1 (0 2 1 4):
  // (2 1 4) -> (1 4 2), (0 4 1), (2 4 0) -> (0 2 4), and (0 1 2), the shared face seen the other way.
  const std::vector<Triangle> expected = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}, {1, 4, 2}, {0, 4, 1}, {0, 2, 4}};
  EXPECT_EQ(tetrahedron_set_triangles(tets), expected);
  const std::vector<Triangle> boundary = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {1, 4, 2}, {0, 4, 1}, {0, 2, 4}};
  EXPECT_EQ(boundary_triangles(tets), boundary);
  EXPECT_EQ(boundary_triangles(tets, true).front(), (Triangle{1, 3, 2}));
  EXPECT_TRUE(boundary_triangles(std::vector<Tetrahedron>{}).empty());
}

TEST(TetrahedronFaces, SofasEdgeArrayFromTheTetrahedra) {
  const std::vector<Tetrahedron> tets = {{3, 1, 2, 0}, {0, 2, 1, 4}};
  // Tetrahedron 0 (3 1 2 0): (3 1) (3 2) (3 0) (1 2) (1 0) (2 0), each smallest first; tetrahedron 1
  // (0 2 1 4): (0 2) (0 1) seen, (0 4), (2 1) seen, (2 4), (1 4).
  const std::vector<Edge> expected = {{1, 3}, {2, 3}, {0, 3}, {1, 2}, {0, 1}, {0, 2}, {0, 4}, {2, 4}, {1, 4}};
  EXPECT_EQ(tetrahedron_set_edges(tets), expected);
  EXPECT_TRUE(tetrahedron_set_edges(std::vector<Tetrahedron>{}).empty());
}

}  // namespace
}  // namespace fastcorot
