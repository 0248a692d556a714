// Pictures rendered headless with OSMesa (and GlRenderer, which draws them): each face of a drawn
// tetrahedron shows its drawColor where it is seen, with SOFA's face order; pictures are not blank;
// fixed points and boxes are marked; the same input gives the same pixels.
#include "fastcorot/render/offscreen_renderer.h"

#include "fastcorot/core/error.h"
#include "render/render_scenes.h"

#include <gtest/gtest.h>

#include <set>

namespace fastcorot {
namespace {

using testing::build_test_scene;

const Rgba kGrey{0.2f, 0.2f, 0.2f, 1.0f};

RenderStyle flat_style() {
  RenderStyle style;
  style.background_top = style.background_bottom = kGrey;
  style.lighting = false;
  return style;
}

std::array<std::uint8_t, 3> bytes(const Rgba& c) {
  auto byte = [](float v) { return static_cast<std::uint8_t>(v * 255.0f + 0.5f); };
  return {byte(c[0]), byte(c[1]), byte(c[2])};
}

// Fraction of pixels that differ from `background` by more than a few levels.
double coverage(const Image& image, const std::array<std::uint8_t, 3>& background) {
  long differing = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto p = image.pixel(x, y);
      int distance = 0;
      for (int c = 0; c < 3; ++c) distance += std::abs(p[c] - background[c]);
      if (distance > 6) ++differing;
    }
  }
  return static_cast<double>(differing) / (static_cast<double>(image.width) * image.height);
}

TEST(OffscreenRenderer, EachFaceShowsItsDrawColourInSofasOrder) {
  const LoadedScene scene = build_test_scene(testing::kDrawnTetrahedron);
  DrawOptions options;
  options.fixed_points = false;
  options.boxes = false;
  SceneDrawer drawer;
  const DrawGeometry geometry = drawer.draw(scene.simulation, options);
  const auto& x = scene.simulation.objects[0].system.state.position;
  const auto& colors = scene.simulation.objects[0].force_field_drawing[0].colors;
  // SOFA (FastTetrahedralCorotationalForceField::draw): the face opposite vertex 3 is drawColor1,
  // opposite 0 drawColor2, opposite 1 drawColor3, opposite 2 drawColor4.
  const std::array<int, 4> color_of_face_opposite = {1, 2, 3, 0};
  OffscreenRenderer renderer(64, 48);
  for (int opposite = 0; opposite < 4; ++opposite) {
    // Look at the face from outside, along its normal, through its centroid.
    Vec3<double> centroid = Vec3<double>::Zero();
    for (int j = 0; j < 4; ++j) {
      if (j != opposite) centroid += x[static_cast<std::size_t>(j)] / 3;
    }
    const Vec3<double> outward = (centroid - x[static_cast<std::size_t>(opposite)]).normalized();
    Camera camera;
    camera.target = centroid;
    camera.eye = centroid + 4 * outward;
    camera.up = std::abs(outward.y()) < 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    const Image image = renderer.render(geometry, camera, flat_style());
    const Rgba& expected = colors[static_cast<std::size_t>(
        color_of_face_opposite[static_cast<std::size_t>(opposite)])];
    EXPECT_EQ(image.pixel(32, 24), bytes(expected)) << "face opposite vertex " << opposite;
  }
}

TEST(OffscreenRenderer, SeenFromACornerThreeFacesShowAndTheFourthIsHidden) {
  const LoadedScene scene = build_test_scene(testing::kDrawnTetrahedron);
  SceneDrawer drawer;
  const DrawGeometry geometry = drawer.draw(scene.simulation, DrawOptions{});
  OffscreenRenderer renderer(120, 90);
  // From (-1, -1, -1) the faces x = 0, y = 0 and z = 0 (opposite vertices 1, 2, 3) face the eye and
  // the slanted face (opposite vertex 0) is behind them.
  CameraOptions options;
  options.eye = Eigen::Vector3d(-2, -2.5, -3);
  const Camera camera =
      frame_camera(geometry.bounds(), scene.simulation.gravity, 120.0 / 90.0, options);
  const Image image = renderer.render(geometry, camera, flat_style());
  std::set<std::array<std::uint8_t, 3>> seen;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) seen.insert(image.pixel(x, y));
  }
  const auto& colors = scene.simulation.objects[0].force_field_drawing[0].colors;
  EXPECT_TRUE(seen.count(bytes(colors[0])));   // drawColor1: opposite vertex 3, the face z = 0
  EXPECT_FALSE(seen.count(bytes(colors[1])));  // drawColor2: opposite vertex 0, hidden
  EXPECT_TRUE(seen.count(bytes(colors[2])));   // drawColor3: opposite vertex 1, the face x = 0
  EXPECT_TRUE(seen.count(bytes(colors[3])));   // drawColor4: opposite vertex 2, the face y = 0
  EXPECT_GT(coverage(image, bytes(kGrey)), 0.02);
}

TEST(OffscreenRenderer, SurfacePicturesAreNotBlankAndMarkFixedPointsAndBoxes) {
  const LoadedScene scene = build_test_scene(testing::small_beam("false"));
  SceneDrawer drawer;
  const DrawGeometry geometry = drawer.draw(scene.simulation, DrawOptions{});
  OffscreenRenderer renderer(160, 90);
  const Camera camera = frame_camera(geometry.bounds(), scene.simulation.gravity, 160.0 / 90.0);
  RenderStyle style;  // lit, gradient background
  const Image image = renderer.render(geometry, camera, style);
  EXPECT_GT(coverage(image, image.pixel(0, 45)), 0.1);  // the left edge is background
  // Lit surfaces: many shades, not one flat colour.
  std::set<std::array<std::uint8_t, 3>> shades;
  for (int x = 0; x < image.width; ++x) shades.insert(image.pixel(x, image.height / 2));
  EXPECT_GT(shades.size(), 3u);
  // A fixed point (point 6, corner (0, 0, 1), in front) is a red dot where it projects (drawn
  // without the box, whose nearer edge passes in front of it).
  DrawOptions no_box;
  no_box.boxes = false;
  const Image dots = renderer.render(drawer.draw(scene.simulation, no_box), camera, style);
  const auto p = camera.project({0, 0, 1}, image.width, image.height);
  ASSERT_TRUE(p);
  const auto red = dots.pixel(static_cast<int>(p->x()), static_cast<int>(p->y()));
  EXPECT_GT(red[0], 150) << int(red[0]) << " " << int(red[1]) << " " << int(red[2]);
  EXPECT_LT(red[1], 100);
  // The BoxROI's box is drawn in its colour (orange) somewhere.
  int orange = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto q = image.pixel(x, y);
      if (q[0] > 200 && q[1] > 120 && q[1] < 220 && q[2] < 90) ++orange;
    }
  }
  EXPECT_GT(orange, 5);
}

TEST(OffscreenRenderer, SameInputSamePixels) {
  const LoadedScene scene = build_test_scene(testing::small_beam("true"));
  SceneDrawer drawer;
  const DrawGeometry geometry = drawer.draw(scene.simulation, DrawOptions{});
  const Camera camera = frame_camera(geometry.bounds(), scene.simulation.gravity, 4.0 / 3.0);
  OffscreenRenderer first(80, 60), second(80, 60);
  const Image a = first.render(geometry, camera);
  const Image b = first.render(geometry, camera);
  const Image c = second.render(geometry, camera);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.rgb, c.rgb);
  EXPECT_GT(coverage(a, a.pixel(0, 0)), 0.05);
  EXPECT_NE(first.driver().find("Mesa"), std::string::npos) << first.driver();
}

TEST(OffscreenRenderer, SupersamplingAndSizeLimits) {
  EXPECT_EQ(OffscreenRenderer(32, 16, 2).supersample(), 2);
  EXPECT_EQ(OffscreenRenderer(8192, 16, 2).supersample(), 1);  // 16384 would exceed OSMesa's limit
  EXPECT_THROW(OffscreenRenderer(0, 16), Error);
  EXPECT_THROW(OffscreenRenderer(16, 9000), Error);
  // An empty geometry gives the background.
  OffscreenRenderer renderer(16, 16);
  const Image empty = renderer.render(DrawGeometry{}, Camera{}, flat_style());
  EXPECT_EQ(coverage(empty, bytes(kGrey)), 0.0);
}

}  // namespace
}  // namespace fastcorot
