// Lagrangian constraints in pictures: their points are magenta markers where they project (and
// none with the option off), bilateral pairs are joined, and each point's force is an arrow of
// scale × force from the point (geometry checked against the force worked out by hand).
#include "fastcorot/render/offscreen_renderer.h"

#include "render/render_scenes.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using testing::build_test_scene;

// A tetrahedron hanging from point 1 by a FixedLagrangianConstraint (point masses 0.5).
const std::string kHeld = R"(
  <FreeMotionAnimationLoop/>
  <BlockGaussSeidelConstraintSolver maxIterations="100000" tolerance="1e-14"/>
  <Node name="tet">
    <EulerImplicitSolver/>
    <SparseLDLSolver/>
    <MechanicalObject name="dofs" position="0 0 0  1 0 0  0 1 0  0 0 1"/>
    <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
    <UniformMass vertexMass="0.5"/>
    <TetrahedronFEMForceField youngModulus="1000" poissonRatio="0.3"/>
    <FixedLagrangianConstraint indices="1"/>
    <LinearSolverConstraintCorrection/>
  </Node>)";

RenderStyle flat_style() {
  RenderStyle style;
  style.background_top = style.background_bottom = {0.2f, 0.2f, 0.2f, 1.0f};
  style.lighting = false;
  return style;
}

bool magenta(const std::array<std::uint8_t, 3>& p) {
  return p[0] > 200 && p[1] < 80 && p[2] > 200;
}

int count_magenta(const Image& image) {
  int count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) count += magenta(image.pixel(x, y)) ? 1 : 0;
  }
  return count;
}

TEST(ConstraintPicture, ConstraintPointsAreMagentaMarkersUnlessSwitchedOff) {
  const LoadedScene scene = build_test_scene(kHeld);
  SceneDrawer drawer;
  DrawOptions on;
  on.fixed_points = on.boxes = false;
  DrawOptions off = on;
  off.constraints = false;
  const DrawGeometry with = drawer.draw(scene.simulation, on);
  ASSERT_EQ(with.markers.size(), 1u);
  EXPECT_TRUE(drawer.draw(scene.simulation, off).markers.positions.empty());

  OffscreenRenderer renderer(160, 90);
  const Camera camera = frame_camera(with.bounds(), scene.simulation.gravity, 160.0 / 90.0);
  const Image shown = renderer.render(with, camera, flat_style());
  const Image hidden = renderer.render(drawer.draw(scene.simulation, off), camera, flat_style());
  const auto p = camera.project({1, 0, 0}, shown.width, shown.height);
  ASSERT_TRUE(p);
  const auto at = shown.pixel(static_cast<int>(p->x()), static_cast<int>(p->y()));
  EXPECT_TRUE(magenta(at)) << int(at[0]) << " " << int(at[1]) << " " << int(at[2]);
  EXPECT_GT(count_magenta(shown), 20);  // a 10-pixel marker, less what the edge of the picture takes
  EXPECT_EQ(count_magenta(hidden), 0);
}

TEST(ConstraintPicture, ForcesAreArrowsFromTheirPointsAndPairsAreJoined) {
  LoadedScene scene = build_test_scene(kHeld);
  scene.simulation.step();
  SceneDrawer drawer;
  DrawOptions options;
  options.fixed_points = options.boxes = options.rigid_frames = false;
  options.constraint_force_scale = 0.1;
  const DrawGeometry geometry = drawer.draw(scene.simulation, options);
  ASSERT_EQ(geometry.markers.size(), 1u);
  const Eigen::Vector3f point = scene.simulation.objects[0].system.state.position[1].cast<float>();
  EXPECT_EQ(geometry.markers.positions[0], point);
  // The arrow: the shaft from the point to point + 0.1 f, f = λ / h from the stage's impulses (the
  // forces themselves are checked against λ by hand in tests/scene/constraint_drawing_test.cpp),
  // in the force colour, then the head's four strokes.
  const auto impulses = scene.simulation.constraints->constraint_forces();
  ASSERT_EQ(impulses.size(), 3u);
  const Eigen::Vector3f force = Eigen::Vector3f(static_cast<float>(impulses[0]), static_cast<float>(impulses[1]),
                                                static_cast<float>(impulses[2])) / 0.01f;
  ASSERT_GT(force.norm(), 1.0f);
  EXPECT_GT(force.y(), 0.0f) << "the point is held up";
  ASSERT_EQ(geometry.lines.size(), 5u);  // the shaft and four head strokes
  EXPECT_EQ(geometry.lines.colors[0], options.constraint_force_color);
  EXPECT_EQ(geometry.lines.positions[0], point);
  EXPECT_LT((geometry.lines.positions[1] - (point + 0.1f * force)).norm(), 1e-5f);

  // Automatic scale: the largest arrow is a tenth of the scene's size.
  options.constraint_force_scale = 0;
  const DrawGeometry automatic = drawer.draw(scene.simulation, options);
  EXPECT_NEAR((automatic.lines.positions[1] - automatic.lines.positions[0]).norm(), 0.1 * scene.simulation.scene_size(), 1e-5);
}

TEST(ConstraintPicture, BilateralPairsAreJoinedAndInactiveOnesAreGreen) {
  const std::string tet = R"(<MechanicalObject name="dofs" position="0 0 0  1 0 0  0 1 0  0 0 1"/>
      <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/><UniformMass vertexMass="0.5"/>
      <TetrahedronFEMForceField youngModulus="1000" poissonRatio="0.3"/><LinearSolverConstraintCorrection/>)";
  auto scene_text = [&](const std::string& activate) {
    return "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver/>"
           "<Node name=\"A\"><EulerImplicitSolver/><SparseLDLSolver/>" + tet + "<FixedProjectiveConstraint indices=\"0 1 2 3\"/></Node>"
           "<Node name=\"B\"><EulerImplicitSolver/><SparseLDLSolver/>" + tet + "</Node>"
           "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"@B/dofs\" first_point=\"2\" second_point=\"3\" activate=\"" +
           activate + "\"/>";
  };
  DrawOptions options;
  options.fixed_points = options.boxes = false;
  for (const std::string activate : {"true", "false"}) {
    const LoadedScene scene = build_test_scene(scene_text(activate));
    const DrawGeometry geometry = SceneDrawer().draw(scene.simulation, options);
    const Rgba color = activate == "true" ? options.constraint_color : options.inactive_constraint_color;
    ASSERT_EQ(geometry.markers.size(), 2u) << activate;
    EXPECT_EQ(geometry.markers.colors[0], color);
    EXPECT_EQ(geometry.markers.colors[1], color);
    ASSERT_EQ(geometry.lines.size(), 1u) << "the pair's segment, no force before a step";
    EXPECT_EQ(geometry.lines.positions[0], Eigen::Vector3f(0, 1, 0));
    EXPECT_EQ(geometry.lines.positions[1], Eigen::Vector3f(0, 0, 1));
    EXPECT_EQ(geometry.lines.colors[0], color);
  }
}

}  // namespace
}  // namespace fastcorot
