// Mesh2PointTopologicalMapping's points, by hand from SOFA's Mesh2PointTopologicalMapping::init and
// addInput* (commit 2a278d891f): offsets on points, p0 (1-x) + p1 x on edges, p0 (1-x-y) + p1 x +
// p2 y on triangles, SOFA's quad formula (corners 0 1 2 3 weighted as a lexicographic square, so
// (0, 1) lands on corner 2), p0 (1-x-y-z) + p1 x + p2 y + p3 z on tetrahedra, trilinear on hexahedra.
#include "fastcorot/topology/mesh2point_mapping.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using V = Vec3<double>;

const std::vector<V> kCube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

TEST(Mesh2PointMapping, PointsThenEdgesInSofasOrder) {
  const std::vector<V> points = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
  const std::vector<Edge> edges = {{0, 1}, {2, 0}};
  Mesh2PointCoords coords;
  coords.point = {{0, 0, 0}, {0, 0, 1}};
  coords.edge = {{0.25, 0, 0}};
  const auto out = mesh2point_points({points, edges, {}, {}, {}, {}}, coords);
  ASSERT_EQ(out.size(), 8u);
  EXPECT_EQ(out[0], V(0, 0, 0));
  EXPECT_EQ(out[1], V(0, 0, 1));  // point 0 + the second offset
  EXPECT_EQ(out[5], V(0, 2, 1));
  EXPECT_EQ(out[6], V(0.25, 0, 0));
  EXPECT_EQ(out[7], V(0, 1.5, 0));  // 0.75 p2 + 0.25 p0
}

TEST(Mesh2PointMapping, TrianglesQuadsTetrahedraHexahedra) {
  const std::vector<Triangle> triangles = {{0, 1, 3}};
  const std::vector<std::array<Index, 4>> quads = {{0, 1, 2, 3}};
  const std::vector<Tetrahedron> tetrahedra = {{0, 1, 3, 4}};
  const std::vector<std::array<Index, 8>> hexahedra = {{0, 1, 2, 3, 4, 5, 6, 7}};
  Mesh2PointCoords coords;
  coords.triangle = {{0.2, 0.3, 0}};
  coords.quad = {{0.5, 0.5, 0}, {1, 0, 0}, {0, 1, 0}};
  coords.tetra = {{0.1, 0.2, 0.3}};
  coords.hexa = {{0.25, 0.5, 1}};
  const auto out = mesh2point_points({kCube, {}, triangles, quads, tetrahedra, hexahedra}, coords);
  ASSERT_EQ(out.size(), 6u);
  EXPECT_LT((out[0] - V(0.2, 0.3, 0)).norm(), 1e-15);
  EXPECT_LT((out[1] - V(0.5, 0.5, 0)).norm(), 1e-15);
  EXPECT_EQ(out[2], V(1, 0, 0));
  EXPECT_EQ(out[3], V(1, 1, 0));  // SOFA's formula puts (0, 1) on quad corner 2
  EXPECT_LT((out[4] - V(0.1, 0.2, 0.3)).norm(), 1e-15);
  EXPECT_LT((out[5] - V(0.25, 0.5, 1)).norm(), 1e-15);  // trilinear in the unit cube: the coordinates
}

TEST(Mesh2PointMapping, IndexBeyondThePointsIsRefused) {
  const std::vector<Edge> edges = {{0, 8}};
  Mesh2PointCoords coords;
  coords.edge = {{0.5, 0, 0}};
  try {
    mesh2point_points({kCube, edges, {}, {}, {}, {}}, coords);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("edge 0 names point 8"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fastcorot
