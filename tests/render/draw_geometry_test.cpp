// What SceneDrawer draws for scenes built through the real parser: the drawn tetrahedra with the
// scene's colours, otherwise the boundary surface (which follows cuts), fixed points and BoxROI
// boxes; the contacts of the last collision detection; and the switches.
#include "fastcorot/render/draw_geometry.h"

#include "fastcorot/core/error.h"
#include "fastcorot/render/tetrahedron_drawing.h"
#include "fastcorot/scene/scene_builder.h"
#include "render/render_scenes.h"
#include "support/sofa_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

namespace fastcorot {
namespace {

using testing::build_test_scene;

TEST(DrawGeometry, DrawnTetrahedronHasFourFacesInItsColours) {
  const LoadedScene scene = build_test_scene(testing::kDrawnTetrahedron);
  SceneDrawer drawer;
  const DrawGeometry geometry = drawer.draw(scene.simulation, DrawOptions{});
  ASSERT_EQ(geometry.triangles.size(), 4u);
  const std::array<Rgba, 4> colors = {Rgba{1, 0, 0, 1}, Rgba{0, 1, 0, 1}, Rgba{0, 0, 1, 1},
                                      Rgba{1, 1, 0, 1}};
  const auto& x = scene.simulation.objects[0].system.state.position;
  const auto shrunk = shrunk_tetrahedron<double>({x[0], x[1], x[2], x[3]});
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(geometry.triangles.colors[3 * k + c], colors[k]) << "triangle " << k;
      EXPECT_TRUE(geometry.triangles.positions[3 * k + c].isApprox(
          shrunk[kDrawnFaces[k][c]].cast<float>()));
    }
  }
  // Point 0 is fixed; the BoxROI gives one box of 12 edges.
  ASSERT_EQ(geometry.points.size(), 1u);
  EXPECT_EQ(geometry.points.positions[0], Eigen::Vector3f::Zero());
  EXPECT_EQ(geometry.lines.size(), 12u);
  EXPECT_TRUE(geometry.bounds().contains(Eigen::Vector3d(0.1, 0.1, 0.1)));
  EXPECT_TRUE(geometry.bounds().contains(Eigen::Vector3d(-0.1, -0.1, -0.1)));
  // The camera frames the objects, not the boxes around them.
  EXPECT_TRUE(geometry.framing_bounds().min().isApprox(Eigen::Vector3d::Zero()));
  EXPECT_FALSE(geometry.framing_bounds().contains(Eigen::Vector3d(-0.1, -0.1, -0.1)));
  DrawGeometry lines_only;
  lines_only.lines = geometry.lines;
  EXPECT_TRUE(lines_only.framing_bounds().isApprox(lines_only.bounds()));
}

TEST(DrawGeometry, WithoutDrawingTheBoundarySurfaceIsShaded) {
  const LoadedScene scene = build_test_scene(testing::small_beam("false"));
  SceneDrawer drawer;
  DrawOptions options;
  const DrawGeometry geometry = drawer.draw(scene.simulation, options);
  // A 2×1×1 box of unit cubes, each square face split in two: 2·(2 + 2 + 1)·2 = 20 triangles.
  EXPECT_EQ(geometry.triangles.size(), 20u);
  for (const Rgba& c : geometry.triangles.colors) EXPECT_EQ(c, options.surface_color);
  for (std::size_t t = 0; t < geometry.triangles.size(); ++t) {
    // Outward normals: on the box's faces, pointing away from its centre (1, 0.5, 0.5).
    const Eigen::Vector3f centre(1, 0.5f, 0.5f);
    const Eigen::Vector3f mid =
        (geometry.triangles.positions[3 * t] + geometry.triangles.positions[3 * t + 1] +
         geometry.triangles.positions[3 * t + 2]) /
        3;
    EXPECT_GT(geometry.triangles.normals[3 * t].dot(mid - centre), 0) << "triangle " << t;
  }
  EXPECT_EQ(geometry.points.size(), 4u);  // the x = 0 face
  EXPECT_EQ(geometry.lines.size(), 12u);
  options.surface_edges = true;
  EXPECT_EQ(drawer.draw(scene.simulation, options).lines.size(), 12u + 3 * 20u);
}

TEST(DrawGeometry, TheModeOverridesTheScene) {
  const LoadedScene off = build_test_scene(testing::small_beam("false"));
  const LoadedScene on = build_test_scene(testing::small_beam("true"));
  SceneDrawer drawer;
  DrawOptions options;
  EXPECT_EQ(drawer.draw(on.simulation, options).triangles.size(), 4u * 12u);
  options.tetrahedra = TetrahedronDrawing::all;
  EXPECT_EQ(drawer.draw(off.simulation, options).triangles.size(), 4u * 12u);
  options.tetrahedra = TetrahedronDrawing::none;
  EXPECT_EQ(drawer.draw(on.simulation, options).triangles.size(), 20u);
  options.fixed_points = false;
  options.boxes = false;
  const DrawGeometry bare = drawer.draw(on.simulation, options);
  EXPECT_EQ(bare.points.size(), 0u);
  EXPECT_EQ(bare.lines.size(), 0u);
}

TEST(DrawGeometry, FollowsThePositions) {
  LoadedScene scene = build_test_scene(testing::kDrawnTetrahedron);
  SceneDrawer drawer;
  auto& x = scene.simulation.objects[0].system.state.position;
  for (auto& p : x) p += Vec3<double>(5, 0, 0);
  const DrawGeometry geometry = drawer.draw(scene.simulation, DrawOptions{});
  EXPECT_EQ(geometry.points.positions[0], Eigen::Vector3f(5, 0, 0));
  EXPECT_GT(geometry.triangles.positions[0].x(), 5.0f);
}

TEST(DrawGeometry, TheSurfaceFollowsCutsEvenWhenTheCountComesBack) {
  // Small beam: cell 0 (x in [0, 1]) is tetrahedra 0..5, cell 1 (x in [1, 2]) is 6..11.
  LoadedScene scene = build_test_scene(testing::small_beam("false"));
  auto& object = scene.simulation.objects[0];
  SceneDrawer drawer;
  EXPECT_EQ(drawer.draw(scene.simulation, DrawOptions{}).triangles.size(), 20u);
  auto x_range = [](const DrawGeometry& geometry) {
    float low = 1e9f, high = -1e9f;
    for (const auto& p : geometry.triangles.positions) {
      low = std::min(low, p.x());
      high = std::max(high, p.x());
    }
    return std::array<float, 2>{low, high};
  };
  const std::vector<Index> cell_1 = {6, 7, 8, 9, 10, 11};
  const TopologyChange cut = object.system.remove_tetrahedra(*object.mesh, cell_1);
  const DrawGeometry left = drawer.draw(scene.simulation, DrawOptions{});
  EXPECT_EQ(left.triangles.size(), 12u);  // one cube: 6 faces of 2 triangles
  EXPECT_EQ(x_range(left), (std::array<float, 2>{0, 1}));
  // Cell 1 back, cell 0 away: six tetrahedra again, as before, but the other cube.
  object.system.add_tetrahedra(*object.mesh, cut.removed_tetrahedron_vertices);
  const std::vector<Index> cell_0 = {0, 1, 2, 3, 4, 5};
  object.system.remove_tetrahedra(*object.mesh, cell_0);
  ASSERT_EQ(object.mesh->num_tetrahedra(), 6);
  const DrawGeometry right = drawer.draw(scene.simulation, DrawOptions{});
  EXPECT_EQ(right.triangles.size(), 12u);
  EXPECT_EQ(x_range(right), (std::array<float, 2>{1, 2}));
}

TEST(DrawGeometry, ObjectsWithoutDrawingInformationShowTheirSurface) {
  LoadedScene scene = build_test_scene(testing::kDrawnTetrahedron);
  scene.simulation.objects[0].force_field_drawing.clear();  // as a hand-built object has
  EXPECT_FALSE(draws_tetrahedra(scene.simulation.objects[0], 0, TetrahedronDrawing::scene));
  SceneDrawer drawer;
  EXPECT_EQ(drawer.draw(scene.simulation, DrawOptions{}).triangles.size(), 4u);  // the boundary
}

TEST(DrawGeometry, ParsesTheDrawingMode) {
  EXPECT_EQ(parse_tetrahedron_drawing("scene"), TetrahedronDrawing::scene);
  EXPECT_EQ(parse_tetrahedron_drawing("on"), TetrahedronDrawing::all);
  EXPECT_EQ(parse_tetrahedron_drawing("off"), TetrahedronDrawing::none);
  try {
    parse_tetrahedron_drawing("yes");
    FAIL() << "accepted \"yes\"";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("--drawing \"yes\""), std::string::npos)
        << error.what();
  }
  EXPECT_TRUE(DrawGeometry{}.bounds().isEmpty());
}

// A rigid body is drawn as its frame: three segments from its centre along its turned axes (x red,
// y green, z blue), and a fixed rigid as one dot at its centre (not at its angular block's zeros).
TEST(DrawGeometry, RigidBodiesShowTheirFrames) {
  LoadedScene scene = build_scene(parse_scene_text(
      "<Node name=\"root\"><EulerImplicitSolver/><CGLinearSolver/>"
      "<MechanicalObject template=\"Rigid3d\" position=\"1 2 3 0 0 0.7071067811865476 0.7071067811865476  5 5 5 0 0 0 1\"/>"
      "<UniformMass totalMass=\"1\"/><FixedProjectiveConstraint indices=\"1\"/></Node>",
      "rigid.scn"));
  SceneDrawer drawer;
  const DrawGeometry g = drawer.draw(scene.simulation, DrawOptions{});
  ASSERT_EQ(g.lines.size(), 6u);
  const Eigen::Vector3f centre(1, 2, 3);
  EXPECT_LT((g.lines.positions[0] - centre).norm(), 1e-6f);
  // Turned 90° about z: the body's x axis is the world's y, drawn in red.
  const Eigen::Vector3f x_axis = (g.lines.positions[1] - g.lines.positions[0]).normalized();
  EXPECT_LT((x_axis - Eigen::Vector3f(0, 1, 0)).norm(), 1e-6f);
  EXPECT_GT(g.lines.colors[0][0], 0.5f);
  ASSERT_EQ(g.points.size(), 1u);
  EXPECT_LT((g.points.positions[0] - Eigen::Vector3f(5, 5, 5)).norm(), 1e-6f);
  DrawOptions without;
  without.rigid_frames = false;
  EXPECT_EQ(drawer.draw(scene.simulation, without).lines.size(), 0u);
}

// SOFA's soft cube over a floor: once it reaches the floor, each contact of the last detection is
// drawn as its two points (markers) joined by a segment and its normal from the second point, in
// colours apart from the constraints'; nothing with the switch off.
TEST(DrawGeometry, ContactsAreTheirPointsJoinedAndTheirNormals) {
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("cube_on_floor.scn"));
  Simulation<double>& simulation = scene.simulation;
  ASSERT_TRUE(simulation.collisions);
  SceneDrawer drawer;
  DrawOptions off;
  off.contacts = false;
  // Before the first step nothing was detected.
  EXPECT_EQ(drawer.draw(simulation, DrawOptions{}).lines.size(), drawer.draw(simulation, off).lines.size());
  for (int step = 0; step < 30; ++step) simulation.step();
  const auto contacts = simulation.collisions->contacts();
  const std::size_t n = contacts.size();
  ASSERT_EQ(n, 15u);  // SOFA's count at step 30 (cube_on_floor_trajectory.json)
  ASSERT_EQ(static_cast<int>(n), simulation.collision_report().contacts);

  const DrawGeometry without = drawer.draw(simulation, off);
  const DrawGeometry with = drawer.draw(simulation, DrawOptions{});
  ASSERT_EQ(with.markers.size(), without.markers.size() + 2 * n);
  ASSERT_EQ(with.lines.size(), without.lines.size() + 2 * n);
  ASSERT_EQ(with.triangles.size(), without.triangles.size());
  // The contacts come last: 2 markers and 2 segments each, in the stage's order.
  const DrawOptions options;
  const float length = static_cast<float>(simulation.scene_size()) / 20;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3f a = contacts[k].point[0].cast<float>(), b = contacts[k].point[1].cast<float>();
    const std::size_t marker = without.markers.size() + 2 * k, end = 2 * (without.lines.size() + 2 * k);
    EXPECT_EQ(with.markers.positions[marker], a) << "contact " << k;
    EXPECT_EQ(with.markers.positions[marker + 1], b) << "contact " << k;
    EXPECT_EQ(with.markers.colors[marker], options.contact_color);
    EXPECT_EQ(with.lines.positions[end], a);
    EXPECT_EQ(with.lines.positions[end + 1], b);
    EXPECT_EQ(with.lines.colors[end], options.contact_color);
    // The floor's normal is +y: the normal segment rises from the cube's point by a twentieth of the scene.
    EXPECT_EQ(with.lines.positions[end + 2], b);
    EXPECT_TRUE(with.lines.positions[end + 3].isApprox(b + length * Eigen::Vector3f::UnitY(), 1e-6f))
        << with.lines.positions[end + 3].transpose();
    EXPECT_EQ(with.lines.colors[end + 2], options.contact_normal_color);
  }
  for (const Rgba& c : {options.constraint_color, options.inactive_constraint_color, options.constraint_force_color}) {
    EXPECT_NE(options.contact_color, c);
    EXPECT_NE(options.contact_normal_color, c);
  }
  // A chosen normal length.
  DrawOptions longer;
  longer.contact_normal_length = 0.5;
  const DrawGeometry scaled = drawer.draw(simulation, longer);
  const std::size_t end = 2 * (without.lines.size() + 1);
  EXPECT_NEAR((scaled.lines.positions[end + 1] - scaled.lines.positions[end]).norm(), 0.5f, 1e-6f);
}

}  // namespace
}  // namespace fastcorot
