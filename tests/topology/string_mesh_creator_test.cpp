// StringMeshCreator's mesh, from SOFA's StringMeshCreator::doLoad (commit 2a278d891f): point x at
// (x / (resolution - 1), 0, 0), edges (x - 1, x).
#include "fastcorot/topology/string_mesh_creator.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

TEST(StringMeshCreator, EvenlySpacedPointsJoinedInOrder) {
  const StringMesh mesh = string_mesh(5);
  ASSERT_EQ(mesh.points.size(), 5u);
  for (int x = 0; x < 5; ++x) EXPECT_EQ(mesh.points[static_cast<std::size_t>(x)], Vec3<double>(0.25 * x, 0, 0));
  ASSERT_EQ(mesh.edges.size(), 4u);
  EXPECT_EQ(mesh.edges[0], (Edge{0, 1}));
  EXPECT_EQ(mesh.edges[3], (Edge{3, 4}));
  EXPECT_EQ(string_mesh(2).points[1], Vec3<double>(1, 0, 0));  // SOFA's default resolution
  EXPECT_TRUE(string_mesh(0).points.empty());
}

TEST(StringMeshCreator, OneOrNegativeResolutionIsRefused) {
  EXPECT_THROW(string_mesh(1), Error);  // SOFA divides by zero there
  EXPECT_THROW(string_mesh(-3), Error);
}

}  // namespace
}  // namespace fastcorot
