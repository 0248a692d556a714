// CylinderGridTopology's points, worked out by hand from SOFA's getPointInGrid for a 3 x 3 x 2
// grid along y: square coordinates in {-r, 0, r}, corners pulled onto the circle, the frame
// X = (1, 0, 0), Y = (0, 0, -1), Z = (0, 1, 0).
#include "fastcorot/topology/cylinder_grid.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fastcorot {
namespace {

TEST(CylinderGrid, SofasPointsAlongY) {
  CylinderGrid grid;
  grid.n = {3, 3, 2};
  grid.axis = {0, 5, 0};
  grid.radius = 2;
  grid.length = 10;
  grid.center = {1, 0, 0};
  const auto x = cylinder_grid_points(grid);
  ASSERT_EQ(x.size(), 18u);
  const double s = std::sqrt(2.0);
  // Point (i, j, k) is i + 3 j + 9 k; the square point (a, b) goes to (a, k l, -b) + centre.
  EXPECT_LT((x[0] - Vec3<double>(1 - s, 0, s)).norm(), 1e-15);    // corner (-2, -2)
  EXPECT_LT((x[1] - Vec3<double>(1, 0, 2)).norm(), 1e-15);        // edge (0, -2): on the circle already
  EXPECT_LT((x[4] - Vec3<double>(1, 0, 0)).norm(), 1e-15);        // the centre
  EXPECT_LT((x[17] - Vec3<double>(1 + s, 10, -s)).norm(), 1e-14);  // corner (2, 2) of the top disc
  for (int k : {0, 1, 2, 3, 5, 6, 7, 8}) {
    const Vec3<double> p = x[static_cast<std::size_t>(k)];
    EXPECT_NEAR(std::hypot(p.x() - 1, p.z()), 2, 1e-14) << k;  // the ring is on the circle
  }
}

TEST(CylinderGrid, BadGridsAreRefused) {
  CylinderGrid grid;
  grid.n = {1, 3, 3};
  EXPECT_THROW(cylinder_grid_points(grid), Error);
  grid.n = {3, 3, 3};
  grid.axis = {0, 0, 0};
  EXPECT_THROW(cylinder_grid_points(grid), Error);
  grid.axis = {0, 0, 1};
  grid.radius = std::nan("");
  EXPECT_THROW(cylinder_grid_points(grid), Error);
}

}  // namespace
}  // namespace fastcorot
