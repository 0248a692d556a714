// PointMapping: SOFA's trilinear regular-grid mapper (cell found from the grid's own geometry,
// clamped to the nearest cell outside), the tetrahedral one in weight form, the identity; and a
// VisualSurface following its object's points.
#include "fastcorot/sim/visual_surface.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <random>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

TEST(PointMapping, TrilinearReproducesTrilinearMotionsInsideAndAffineOnesOutside) {
  RegularGrid grid;
  grid.n = {4, 3, 5};
  grid.min = Vec3<double>(-1, 0, 2);
  grid.max = Vec3<double>(2, 1, 6);
  const auto rest = grid_points<double>(grid);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> inside_x(-1, 2), inside_y(0, 1), inside_z(2, 6), outside(-3, 8);
  Points points;
  for (int i = 0; i < 100; ++i) points.emplace_back(inside_x(rng), inside_y(rng), inside_z(rng));
  for (int i = 0; i < 50; ++i) points.emplace_back(outside(rng), outside(rng), outside(rng));
  points.push_back(grid.max);  // a corner: the last cell
  const auto map = PointMapping<double>::trilinear(grid, points);
  // Inside: weights in [0, 1] summing to 1 on the corners of the cell holding the point.
  for (std::size_t i = 0; i < 100; ++i) {
    double sum = 0;
    for (double w : map.weights[i]) {
      EXPECT_GE(w, -1e-12);
      sum += w;
    }
    EXPECT_NEAR(sum, 1, 1e-12);
  }
  // At rest every point maps to itself; under an affine motion to its image, outside too.
  Points out(points.size());
  map.apply(rest, out);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_LT((out[i] - points[i]).norm(), 1e-11) << i;
  Mat3<double> a;
  a << 0.9, 0.2, 0, -0.1, 1.1, 0.3, 0.05, 0, 1.2;
  Points moved;
  for (const auto& p : rest) moved.push_back(a * p + Vec3<double>(1, 2, 3));
  map.apply(moved, out);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_LT((out[i] - (a * points[i] + Vec3<double>(1, 2, 3))).norm(), 1e-10) << i;
  }
  // A trilinear (non-affine) field is reproduced inside: x y z is trilinear.
  Points bent;
  for (const auto& p : rest) bent.push_back(Vec3<double>(p.x() * p.y() * p.z(), 0, 0));
  map.apply(bent, out);
  for (std::size_t i = 0; i < 100; ++i) EXPECT_NEAR(out[i].x(), points[i].x() * points[i].y() * points[i].z(), 1e-10);
}

TEST(PointMapping, GridCellsComeFromTheGridNotFromTheState) {
  // SOFA locates points with the grid's geometry: the state may be elsewhere (a MechanicalObject's
  // translation), the weights stay those of the grid.
  RegularGrid grid;
  grid.n = {2, 2, 2};
  const Points points = {{0.25, 0.5, 0.75}};
  const auto map = PointMapping<double>::trilinear(grid, points);
  Points shifted = grid_points<double>(grid);
  for (auto& p : shifted) p += Vec3<double>(10, 0, 0);
  Points out(1);
  map.apply(shifted, out);
  EXPECT_LT((out[0] - Vec3<double>(10.25, 0.5, 0.75)).norm(), 1e-14);
}

TEST(PointMapping, IdentityAndBarycentricForms) {
  const Points rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const TetMesh mesh(4, {{0, 1, 2, 3}});
  const Points points = {{0.2, 0.3, 0.1}};
  const auto bary = PointMapping<double>::from_barycentric(mesh, map_onto_tetrahedra<double>(mesh, rest, points));
  Points out(1);
  bary.apply(rest, out);
  EXPECT_LT((out[0] - points[0]).norm(), 1e-15);
  const auto identity = PointMapping<double>::identity(4);
  Points same(4);
  identity.apply(rest, same);
  EXPECT_EQ(same, rest);
  Points wrong(3);
  EXPECT_THROW(identity.apply(rest, wrong), Error);
  VisualSurface surface;
  surface.map = bary;
  EXPECT_LT((surface.points(rest)[0] - points[0]).norm(), 1e-15);
}

}  // namespace
}  // namespace fastcorot
