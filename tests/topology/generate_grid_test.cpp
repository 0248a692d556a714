// GenerateGrid's points and elements, worked out by hand from SOFA's GenerateGrid::doUpdate (commit
// 2a278d891f): point (i, j, k) at i + (L+1) (j + (W+1) k), min + index x step; hexahedra with i
// slowest and k fastest, each split (0 5 1 6) (0 1 3 6) (1 3 6 2) (6 3 0 7) (6 7 0 5) (7 5 4 0); a
// flat grid's quads with i slowest, each split (0 1 3) (3 1 2).
#include "fastcorot/topology/generate_grid.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

TEST(GenerateGrid, PointsHexahedraAndTetrahedraInSofasOrder) {
  // 2 x 1 x 2 cells of size 1 from (1, 2, 3): points 3 x 2 x 3.
  const GeneratedGrid g = generate_grid({1, 2, 3}, {3, 3, 5}, {2, 1, 2});
  ASSERT_EQ(g.points.size(), 18u);
  EXPECT_EQ(g.points[0], Vec3<double>(1, 2, 3));
  EXPECT_EQ(g.points[4], Vec3<double>(2, 3, 3));   // (1, 1, 0)
  EXPECT_EQ(g.points[17], Vec3<double>(3, 3, 5));  // (2, 1, 2)
  ASSERT_EQ(g.hexahedra.size(), 4u);
  EXPECT_EQ(g.hexahedra[0], (Hexahedron{0, 1, 4, 3, 6, 7, 10, 9}));      // cell (0, 0, 0)
  EXPECT_EQ(g.hexahedra[1], (Hexahedron{6, 7, 10, 9, 12, 13, 16, 15}));  // cell (0, 0, 1): z runs fastest
  EXPECT_EQ(g.hexahedra[2], (Hexahedron{1, 2, 5, 4, 7, 8, 11, 10}));     // cell (1, 0, 0)
  ASSERT_EQ(g.tetrahedra.size(), 24u);
  EXPECT_EQ(g.tetrahedra[0], (Tetrahedron{0, 7, 1, 10}));
  EXPECT_EQ(g.tetrahedra[3], (Tetrahedron{10, 3, 0, 9}));
  EXPECT_EQ(g.tetrahedra[5], (Tetrahedron{9, 7, 6, 0}));
  EXPECT_EQ(g.tetrahedra[12], (Tetrahedron{1, 8, 2, 11}));  // first of cell (1, 0, 0)
  EXPECT_TRUE(g.quads.empty());
  EXPECT_TRUE(g.triangles.empty());
}

TEST(GenerateGrid, StepsAsSofaComputesThem) {
  // SOFA's GenerateGrid.scn: max (0.5, 1.5, 1), resolution 5 3 4; x = i (0.5 / 5) + 0.
  const GeneratedGrid g = generate_grid({0, 0, 0}, {0.5, 1.5, 1}, {5, 3, 4});
  ASSERT_EQ(g.points.size(), 6u * 4u * 5u);
  EXPECT_EQ(g.points[3].x(), 3 * (0.5 / 5));
  EXPECT_EQ(g.points[6 * 2].y(), 2 * (1.5 / 3));
  EXPECT_EQ(g.points[24 * 3].z(), 3 * (1.0 / 4));
  EXPECT_EQ(g.hexahedra.size(), 60u);
  EXPECT_EQ(g.tetrahedra.size(), 360u);
}

TEST(GenerateGrid, FlatGridGivesQuadsAndTriangles) {
  const GeneratedGrid g = generate_grid({0, 0, 7}, {2, 2, 9}, {2, 2, 0});
  ASSERT_EQ(g.points.size(), 9u);
  EXPECT_EQ(g.points[8], Vec3<double>(2, 2, 7));  // z stays at min.z
  EXPECT_TRUE(g.hexahedra.empty());
  EXPECT_TRUE(g.tetrahedra.empty());
  ASSERT_EQ(g.quads.size(), 4u);
  EXPECT_EQ(g.quads[0], (Quad{0, 1, 4, 3}));
  EXPECT_EQ(g.quads[1], (Quad{3, 4, 7, 6}));  // (0, 1): j runs fastest
  EXPECT_EQ(g.quads[2], (Quad{1, 2, 5, 4}));
  ASSERT_EQ(g.triangles.size(), 8u);
  EXPECT_EQ(g.triangles[0], (Triangle{0, 1, 3}));
  EXPECT_EQ(g.triangles[1], (Triangle{3, 1, 4}));
}

TEST(GenerateGrid, BadResolutionsAreRefused) {
  EXPECT_THROW(generate_grid({0, 0, 0}, {1, 1, 1}, {0, 1, 1}), Error);
  EXPECT_THROW(generate_grid({0, 0, 0}, {1, 1, 1}, {1, 0, 1}), Error);
  EXPECT_THROW(generate_grid({0, 0, 0}, {1, 1, 1}, {1, 1, -1}), Error);
  EXPECT_THROW(generate_grid({0, 0, 0}, {1, 1, 1}, {100000, 100000, 100000}), Error);
}

}  // namespace
}  // namespace fastcorot
