// Picking for cutting: the ray through a pixel undoes Camera::project; Möller–Trumbore hits both
// sides of a triangle and nothing behind the origin; the nearest boundary triangle names the
// tetrahedron (not the first in order), and after its removal the one behind is hit; the brush
// takes the tetrahedra whose centroid is within the radius. Expected values are derived by hand in
// the comments.
#include "fastcorot/render/picking.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fastcorot {
namespace {

// The unit corner tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1) lifted by `z`: points 4k..4k+3.
void add_corner_tetrahedron(std::vector<Vec3<double>>& points, std::vector<Tetrahedron>& tets,
                            double z) {
  const Index first = static_cast<Index>(points.size());
  points.insert(points.end(), {Vec3<double>(0, 0, z), Vec3<double>(1, 0, z), Vec3<double>(0, 1, z),
                               Vec3<double>(0, 0, z + 1)});
  tets.push_back({first, first + 1, first + 2, first + 3});
}

// Looks straight down −z at (0.2, 0.3) from z = 10: the centre (50.5, 50.5) of a 101 × 101 picture
// is that vertical line.
Camera camera_above() {
  Camera camera;
  camera.eye = {0.2, 0.3, 10};
  camera.target = {0.2, 0.3, 0};
  camera.up = {0, 1, 0};
  return camera;
}
const Eigen::Vector2d kCentre(50.5, 50.5);

TEST(Picking, PixelRayGoesThroughThePixel) {
  // 90 degrees of view: at depth 1 the picture spans [-1, 1] both ways (square picture). Pixel
  // (75, 50) of 100 × 100 is x = +0.5, y = 0 there; the eye's right is +x, so the direction is
  // (0.5, 0, -1) / |(0.5, 0, -1)|.
  Camera camera;
  camera.eye = {0, 0, 10};
  camera.target = {0, 0, 0};
  camera.fov_y_degrees = 90;
  const Ray ray = pixel_ray(camera, 100, 100, {75, 50});
  EXPECT_TRUE(ray.origin.isApprox(camera.eye));
  EXPECT_TRUE(ray.direction.isApprox(Eigen::Vector3d(0.5, 0, -1).normalized(), 1e-12));
  EXPECT_TRUE(pixel_ray(camera, 100, 100, {50, 50}).direction.isApprox(-Eigen::Vector3d::UnitZ()));
  // Pixel y grows downwards: the top row looks up.
  EXPECT_GT(pixel_ray(camera, 100, 100, {50, 0}).direction.y(), 0);

  // Any camera and aspect: projecting a point of the ray gives the pixel back.
  Camera oblique;
  oblique.eye = {3, -1, 2};
  oblique.target = {0.5, 0.2, -0.3};
  oblique.up = {0, 0, 1};
  oblique.fov_y_degrees = 40;
  for (const Eigen::Vector2d& pixel :
       {Eigen::Vector2d(10.5, 20.25), Eigen::Vector2d(600, 1), Eigen::Vector2d(320, 240)}) {
    const Ray r = pixel_ray(oblique, 640, 480, pixel);
    EXPECT_NEAR(r.direction.norm(), 1, 1e-12);
    const auto back = oblique.project(r.origin + 7 * r.direction, 640, 480);
    ASSERT_TRUE(back);
    EXPECT_LT((*back - pixel).norm(), 1e-9) << pixel.transpose();
  }
  EXPECT_THROW(pixel_ray(camera, 0, 100, {0, 0}), Error);
}

TEST(Picking, RayMeetsTriangleFromEitherSideAndOnlyAhead) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
  // From 2 above the plane z = 0, straight down inside the triangle: distance 2.
  const auto from_above = intersect_ray_triangle({{0.25, 0.25, 2}, down}, a, b, c);
  ASSERT_TRUE(from_above);
  EXPECT_NEAR(*from_above, 2, 1e-15);
  // From below, upwards: the back face is hit too (cut surfaces have either winding).
  const auto from_below = intersect_ray_triangle({{0.25, 0.25, -3}, -down}, a, b, c);
  ASSERT_TRUE(from_below);
  EXPECT_NEAR(*from_below, 3, 1e-15);
  // Outside: x + y = 1.6 > 1.
  EXPECT_FALSE(intersect_ray_triangle({{0.8, 0.8, 2}, down}, a, b, c));
  // Behind the origin: the ray starts below the triangle and points away from it.
  EXPECT_FALSE(intersect_ray_triangle({{0.25, 0.25, -1}, down}, a, b, c));
  // In the triangle's plane: parallel, never a hit.
  EXPECT_FALSE(intersect_ray_triangle({{-1, 0.25, 0}, Eigen::Vector3d::UnitX()}, a, b, c));
  // A degenerate (flat) triangle is never hit.
  EXPECT_FALSE(intersect_ray_triangle({{0.25, 0, 2}, down}, a, b, Eigen::Vector3d(2, 0, 0)));
  // Oblique: from (0.25, 0.25, 1) along (1, 0, -1)/√2 the plane is reached at (1.25, 0.25, 0),
  // outside; along (-0.1, 0, -1) at (0.15, 0.25, 0), inside, after √(0.01 + 1).
  EXPECT_FALSE(
      intersect_ray_triangle({{0.25, 0.25, 1}, Eigen::Vector3d(1, 0, -1).normalized()}, a, b, c));
  const auto oblique =
      intersect_ray_triangle({{0.25, 0.25, 1}, Eigen::Vector3d(-0.1, 0, -1).normalized()}, a, b, c);
  ASSERT_TRUE(oblique);
  EXPECT_NEAR(*oblique, std::sqrt(1.01), 1e-12);
}

TEST(Picking, TheNearestTetrahedronIsPickedAndTheOneBehindAfterItsRemoval) {
  // Tetrahedron 0 sits at z in [0, 1], tetrahedron 1 at z in [2, 3]: 1 is nearer the eye (z = 10)
  // but comes second, so taking the first hit in order would be wrong. The vertical line through
  // (0.2, 0.3) enters a corner tetrahedron lifted by z0 through its slanted face x + y + (z - z0)
  // = 1, at z = z0 + 0.5.
  std::vector<Vec3<double>> points;
  std::vector<Tetrahedron> tets;
  add_corner_tetrahedron(points, tets, 0);
  add_corner_tetrahedron(points, tets, 2);
  TetMesh mesh(static_cast<Index>(points.size()), tets);
  const Ray ray = pixel_ray(camera_above(), 101, 101, kCentre);

  const auto hit = pick_tetrahedron<double>(mesh, points, ray);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->tetrahedron, 1);
  EXPECT_NEAR(hit->distance, 10 - 2.5, 1e-12);
  EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(0.2, 0.3, 2.5), 1e-12));
  // Through the boundary triangles the answer is the same.
  const std::vector<BoundaryTriangle> boundary = mesh.boundary_triangles();
  const auto boundary_hit =
      pick_tetrahedron<double>(std::span<const BoundaryTriangle>(boundary), points, ray);
  ASSERT_TRUE(boundary_hit);
  EXPECT_EQ(boundary_hit->tetrahedron, 1);
  EXPECT_EQ(boundary_hit->distance, hit->distance);

  const Index nearest[] = {1};
  mesh.remove_tetrahedra(nearest);
  const auto behind = pick_tetrahedron<double>(mesh, points, ray);
  ASSERT_TRUE(behind);
  EXPECT_EQ(behind->tetrahedron, 0);
  EXPECT_NEAR(behind->distance, 10 - 0.5, 1e-12);

  const Index last[] = {0};
  mesh.remove_tetrahedra(last);
  EXPECT_FALSE(pick_tetrahedron<double>(mesh, points, ray));  // an empty mesh hides nothing
}

TEST(Picking, NearestWinsWhateverTheOrderAndPixelsBesideTheObjectHitNothing) {
  // The same pair listed the other way round: the nearer one (now 0) is still the answer.
  std::vector<Vec3<double>> points;
  std::vector<Tetrahedron> tets;
  add_corner_tetrahedron(points, tets, 2);
  add_corner_tetrahedron(points, tets, 0);
  const TetMesh mesh(static_cast<Index>(points.size()), tets);
  const Camera camera = camera_above();
  const auto hit = pick_tetrahedron<double>(mesh, points, pixel_ray(camera, 101, 101, kCentre));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->tetrahedron, 0);

  // The default 30 degrees of view shows ±10 tan 15° ≈ ±2.68 around (0.2, 0.3) at z = 0: the top
  // left corner pixel looks at about (-2.5, 3, 0) and beyond, far from the unit tetrahedra.
  EXPECT_FALSE(pick_tetrahedron<double>(mesh, points, pixel_ray(camera, 101, 101, {0.5, 0.5})));
  // Positions in float pick the same.
  std::vector<Vec3<float>> floats;
  for (const auto& p : points) floats.push_back(p.cast<float>());
  const auto float_hit =
      pick_tetrahedron<float>(mesh, floats, pixel_ray(camera, 101, 101, kCentre));
  ASSERT_TRUE(float_hit);
  EXPECT_EQ(float_hit->tetrahedron, 0);
}

TEST(Picking, GridColumnIsEnteredThroughItsTopAndCutDownwards) {
  // Three unit cubes stacked along z (points 2 × 2 × 4, cells 0, 1, 2 bottom to top, tetrahedra
  // 6c..6c+5). Looking down at (0.2, 0.3) the ray enters the top face z = 3 at distance 7 in a
  // tetrahedron of the top cell; removing what is hit goes down the column, never upwards.
  RegularGrid grid;
  grid.n = {2, 2, 4};
  grid.max = {1, 1, 3};
  const std::vector<Vec3<double>> points = grid_points<double>(grid);
  TetMesh mesh(grid.num_points(), grid_tetrahedra(grid, true));
  const Ray ray = pixel_ray(camera_above(), 101, 101, kCentre);
  const auto hit = pick_tetrahedron<double>(mesh, points, ray);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 7, 1e-12);
  EXPECT_GE(hit->tetrahedron, 12);  // top cell
  double depth = hit->distance;
  double highest_vertex_of_last = 0;
  int removed = 0;
  while (const auto next = pick_tetrahedron<double>(mesh, points, ray)) {
    // The faces inside the column never come first: the boundary alone gives the same answer.
    const std::vector<BoundaryTriangle> boundary = mesh.boundary_triangles();
    const auto on_boundary =
        pick_tetrahedron<double>(std::span<const BoundaryTriangle>(boundary), points, ray);
    ASSERT_TRUE(on_boundary);
    EXPECT_EQ(on_boundary->tetrahedron, next->tetrahedron);
    EXPECT_EQ(on_boundary->distance, next->distance);
    EXPECT_GE(next->distance, depth - 1e-12);
    depth = next->distance;
    highest_vertex_of_last = 0;
    for (Index v : mesh.tetrahedron(next->tetrahedron))
      highest_vertex_of_last =
          std::max(highest_vertex_of_last, points[static_cast<std::size_t>(v)].z());
    const Index picked[] = {next->tetrahedron};
    mesh.remove_tetrahedra(picked);
    ASSERT_LT(++removed, 18) << "more picks than tetrahedra";
  }
  // The last tetrahedron picked is in the bottom cell, entered between z = 1 and z = 0.
  EXPECT_EQ(highest_vertex_of_last, 1);
  EXPECT_GE(depth, 9 - 1e-12);
  EXPECT_LT(depth, 10);
  EXPECT_GT(mesh.num_tetrahedra(), 0);  // the vertical line misses some tetrahedra of each cube
}

TEST(Picking, BrushTakesTheTetrahedraWhoseCentroidIsWithinTheRadius) {
  // Centroids: tetrahedron 0 at (0.25, 0.25, 0.25), tetrahedron 1 at (0.25, 0.25, 2.25), 2 apart.
  std::vector<Vec3<double>> points;
  std::vector<Tetrahedron> tets;
  add_corner_tetrahedron(points, tets, 0);
  add_corner_tetrahedron(points, tets, 2);
  const TetMesh mesh(static_cast<Index>(points.size()), tets);
  const Eigen::Vector3d centre(0.25, 0.25, 2.25);
  EXPECT_EQ(tetrahedra_within<double>(mesh, points, centre, 0), (std::vector<Index>{1}));
  EXPECT_EQ(tetrahedra_within<double>(mesh, points, centre, 1.99), (std::vector<Index>{1}));
  EXPECT_EQ(tetrahedra_within<double>(mesh, points, centre, 2), (std::vector<Index>{0, 1}));
  EXPECT_TRUE(tetrahedra_within<double>(mesh, points, {5, 5, 5}, 1).empty());
  EXPECT_TRUE(tetrahedra_within<double>(mesh, points, centre, -1).empty());
  EXPECT_TRUE(
      tetrahedra_within<double>(mesh, points, centre, std::numeric_limits<double>::quiet_NaN())
          .empty());
}

}  // namespace
}  // namespace fastcorot
