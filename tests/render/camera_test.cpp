// The camera's matrices against hand-made cases, the automatic framing's promises (every corner
// in the picture, up against gravity, broadside to the long axis) and orbit/pan/zoom.
#include "fastcorot/render/camera.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace fastcorot {
namespace {

Eigen::AlignedBox3d box(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return Eigen::AlignedBox3d(a, b);
}

TEST(Camera, ViewAndProjectionFollowOpenGL) {
  Camera camera;
  camera.eye = {0, 0, 10};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  const Eigen::Matrix4d view = camera.view_matrix();
  EXPECT_TRUE((view * Eigen::Vector4d(0, 0, 10, 1)).isApprox(Eigen::Vector4d(0, 0, 0, 1)));
  EXPECT_TRUE((view * Eigen::Vector4d(0, 0, 0, 1)).isApprox(Eigen::Vector4d(0, 0, -10, 1)));
  // Near and far planes map to clip depths -1 and 1.
  const Eigen::Matrix4d projection = camera.projection_matrix(2.0, 1.0, 100.0);
  const Eigen::Vector4d near = projection * Eigen::Vector4d(0, 0, -1, 1);
  const Eigen::Vector4d far = projection * Eigen::Vector4d(0, 0, -100, 1);
  EXPECT_NEAR(near.z() / near.w(), -1, 1e-12);
  EXPECT_NEAR(far.z() / far.w(), 1, 1e-12);
  // The target is the picture's centre; +x is to the right and +y up (smaller row).
  const auto centre = camera.project({0, 0, 0}, 200, 100);
  ASSERT_TRUE(centre);
  EXPECT_TRUE(centre->isApprox(Eigen::Vector2d(100, 50)));
  EXPECT_GT(camera.project({1, 0, 0}, 200, 100)->x(), 100);
  EXPECT_LT(camera.project({0, 1, 0}, 200, 100)->y(), 50);
  // A point at the top of the field of view lands on the top edge.
  const double top = 10 * std::tan(15.0 * std::numbers::pi / 180);
  EXPECT_NEAR(camera.project({0, top, 0}, 200, 100)->y(), 0, 1e-9);
  EXPECT_FALSE(camera.project({0, 0, 20}, 200, 100));  // behind the eye
}

TEST(Camera, FramingShowsEveryCornerWithAMargin) {
  const Eigen::AlignedBox3d beam = box({0, 6, -2}, {16, 10, 2});
  CameraOptions options;
  options.room_below = 0;
  for (double aspect : {16.0 / 9.0, 1.0, 0.5}) {
    const Camera camera = frame_camera(beam, {0, -9.81, 0}, aspect, options);
    const int height = 400, width = static_cast<int>(height * aspect);
    double left = width, right = 0, top = height, bottom = 0;
    for (int c = 0; c < 8; ++c) {
      const auto p = camera.project(beam.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)),
                                    width, height);
      ASSERT_TRUE(p);
      left = std::min(left, p->x());
      right = std::max(right, p->x());
      top = std::min(top, p->y());
      bottom = std::max(bottom, p->y());
    }
    EXPECT_GE(left, 0);
    EXPECT_LE(right, width);
    EXPECT_GE(top, 0);
    EXPECT_LE(bottom, height);
    // Tight in one direction at least, and centred.
    EXPECT_TRUE(left < 0.1 * width || top < 0.1 * height) << "aspect " << aspect;
    EXPECT_NEAR(left + right, width, 1e-3 * width);
    EXPECT_NEAR(top + bottom, height, 1e-3 * height);
  }
}

TEST(Camera, FramingStandsUpAgainstGravityAndLooksBroadside) {
  const Eigen::AlignedBox3d beam = box({0, 0, 0}, {16, 4, 4});
  CameraOptions options;
  options.azimuth_degrees = 0;
  options.elevation_degrees = 0;
  options.room_below = 0;
  const Camera camera = frame_camera(beam, {0, 0, -9.81}, 1.5, options);
  EXPECT_TRUE(camera.up.isApprox(Eigen::Vector3d(0, 0, 1)));
  // Broadside to the long x axis: the view direction has no x component.
  const Eigen::Vector3d direction = (camera.target - camera.eye).normalized();
  EXPECT_NEAR(direction.x(), 0, 1e-12);
  EXPECT_NEAR(direction.z(), 0, 1e-12);
  // No gravity: +y is up.
  EXPECT_TRUE(
      frame_camera(beam, Eigen::Vector3d::Zero(), 1.5).up.isApprox(Eigen::Vector3d::UnitY()));
}

TEST(Camera, RoomBelowExtendsTheFrameAlongGravity) {
  const Eigen::AlignedBox3d beam = box({0, 0, 0}, {10, 1, 1});
  CameraOptions options;
  options.room_below = 0.5;  // 5 below the beam
  const Camera camera = frame_camera(beam, {0, -1, 0}, 16.0 / 9.0, options);
  const auto low = camera.project({10, -5, 0}, 1600, 900);
  ASSERT_TRUE(low);
  EXPECT_GE(low->y(), 0);
  EXPECT_LE(low->y(), 900);
}

TEST(Camera, GivenEyeTargetAndUpAreKept) {
  CameraOptions options;
  options.eye = Eigen::Vector3d(1, 2, 30);
  options.target = Eigen::Vector3d(1, 2, 3);
  options.up = Eigen::Vector3d(0, 2, 0);
  options.fov_y_degrees = 45;
  const Camera camera = frame_camera(box({0, 0, 0}, {1, 1, 1}), {0, -9.81, 0}, 1, options);
  EXPECT_EQ(camera.eye, *options.eye);
  EXPECT_EQ(camera.target, *options.target);
  EXPECT_TRUE(camera.up.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(camera.fov_y_degrees, 45);
}

TEST(Camera, BadFramingRequestsAreErrors) {
  const Eigen::AlignedBox3d unit = box({0, 0, 0}, {1, 1, 1});
  const Eigen::Vector3d g(0, -1, 0);
  auto fails = [&](const Eigen::AlignedBox3d& b, double aspect, const CameraOptions& o) {
    try {
      frame_camera(b, g, aspect, o);
    } catch (const Error&) {
      return true;
    }
    return false;
  };
  EXPECT_TRUE(fails(Eigen::AlignedBox3d(), 1, {}));
  EXPECT_TRUE(fails(unit, 0, {}));
  CameraOptions o;
  o.fov_y_degrees = 180;
  EXPECT_TRUE(fails(unit, 1, o));
  o = {};
  o.margin = 0.5;
  EXPECT_TRUE(fails(unit, 1, o));
  o = {};
  o.up = Eigen::Vector3d::Zero();
  EXPECT_TRUE(fails(unit, 1, o));
  o = {};
  o.eye = Eigen::Vector3d(0.5, 0.5, 0.5);
  o.target = Eigen::Vector3d(0.5, 0.5, 0.5);
  EXPECT_TRUE(fails(unit, 1, o));
  o.eye = Eigen::Vector3d(0.5, 5, 0.5);  // straight above: parallel to up
  EXPECT_TRUE(fails(unit, 1, o));
  // A single point is framed at some distance.
  const Camera point = frame_camera(box({1, 1, 1}, {1, 1, 1}), g, 1);
  EXPECT_GT((point.eye - point.target).norm(), 0);
}

TEST(Camera, OrbitPanAndZoom) {
  Camera camera;
  camera.eye = {0, 0, 10};
  camera.target = {1, 0, 0};
  const double distance = (camera.eye - camera.target).norm();
  camera.orbit(0.7, 0.3);
  EXPECT_NEAR((camera.eye - camera.target).norm(), distance, 1e-12);
  EXPECT_GT(camera.eye.y(), 0);  // a positive pitch raises the eye
  camera.orbit(0, 10);           // far past the pole: stops 1 degree short of it
  const double elevation =
      std::asin((camera.eye - camera.target).normalized().y()) * 180 / std::numbers::pi;
  EXPECT_NEAR(elevation, 89, 1e-9);
  const Eigen::Vector3d offset = camera.eye - camera.target;
  camera.pan(0.5, 0.25);
  EXPECT_TRUE((camera.eye - camera.target).isApprox(offset));
  EXPECT_GT((camera.target - Eigen::Vector3d(1, 0, 0)).norm(), 0);
  camera.zoom(0.5);
  EXPECT_NEAR((camera.eye - camera.target).norm(), distance / 2, 1e-9);
  camera.zoom(-1);  // ignored
  EXPECT_NEAR((camera.eye - camera.target).norm(), distance / 2, 1e-9);
}

}  // namespace
}  // namespace fastcorot
