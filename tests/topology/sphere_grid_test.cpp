// SphereGridTopology's points, worked out by hand from SOFA's SphereGridTopology::getPointInGrid
// (commit 2a278d891f): cube coordinates in {-r, 0, r}, each pulled onto the sphere through it by
// max(|x|, |y|, |z|) / |p|, in the frame of grid_axes.
#include "fastcorot/topology/sphere_grid.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fastcorot {
namespace {

TEST(SphereGrid, SofasPointsAlongZ) {
  SphereGrid grid;
  grid.n = {3, 3, 3};
  grid.radius = 2;
  grid.center = {1, 2, 3};
  const auto x = sphere_grid_points(grid);
  ASSERT_EQ(x.size(), 27u);
  const Vec3<double> c = grid.center;
  const double a = 2 / std::sqrt(3.0), b = std::sqrt(2.0);
  // Point (i, j, k) is i + 3 j + 9 k; the frame is the world's for the z axis.
  EXPECT_LT((x[0] - (c + Vec3<double>(-a, -a, -a))).norm(), 1e-15);  // corner (-2, -2, -2)
  EXPECT_LT((x[13] - c).norm(), 1e-15);                               // the centre stays
  EXPECT_LT((x[14] - (c + Vec3<double>(2, 0, 0))).norm(), 1e-15);    // face centre: on the sphere already
  EXPECT_LT((x[17] - (c + Vec3<double>(b, b, 0))).norm(), 1e-15);    // edge middle (2, 2, 0)
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i != 13) EXPECT_NEAR((x[i] - c).norm(), 2, 1e-14) << i;  // every other point is on the sphere
  }
}

TEST(SphereGrid, AxisAlongYTurnsTheGrid) {
  // Z = (0, 1, 0), Y = Z x (1, 0, 0) = (0, 0, -1), X = Y x Z = (1, 0, 0): (a, b, c) -> (a, c, -b).
  SphereGrid grid;
  grid.n = {3, 3, 3};
  grid.axis = {0, 4, 0};
  grid.radius = 2;
  const auto x = sphere_grid_points(grid);
  EXPECT_LT((x[10] - Vec3<double>(0, 0, 2)).norm(), 1e-15);   // (1, 0, 1): cube (0, -2, 0)
  EXPECT_LT((x[22] - Vec3<double>(0, 2, 0)).norm(), 1e-15);   // (1, 1, 2): cube (0, 0, 2)
  EXPECT_LT((x[5] - Vec3<double>(std::sqrt(2.0), -std::sqrt(2.0), 0)).norm(), 1e-15);  // (2, 1, 0): cube (2, 0, -2)
}

TEST(SphereGrid, BadGridsAreRefused) {
  SphereGrid grid;
  grid.n = {3, 1, 3};
  EXPECT_THROW(sphere_grid_points(grid), Error);
  grid.n = {3, 3, 3};
  grid.axis = {0, 0, 0};
  EXPECT_THROW(sphere_grid_points(grid), Error);
  grid.axis = {0, 0, 1};
  grid.radius = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(sphere_grid_points(grid), Error);
}

}  // namespace
}  // namespace fastcorot
