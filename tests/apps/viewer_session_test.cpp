// The viewer's state without a window: play/pause and steps, live method and material changes
// (refused values change nothing and leave a message), divergence pauses, reload starts over, and
// cutting under a pixel (what the picked ray hits goes, an empty pixel changes nothing, a cut
// across a beam separates it and the simulation goes on).
#include "viewer_session.h"

#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_graph.h"
#include "render/render_scenes.h"
#include "support/force_fields.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <utility>

namespace fastcorot::cli {
namespace {

ViewOptions options_for(const std::string& name, const std::string& body) {
  const auto dir = std::filesystem::path(FASTCOROT_TEST_OUTPUT_DIR) / name;
  std::filesystem::create_directories(dir);
  const auto path = dir / "scene.scn";
  std::ofstream(path) << "<Node name=\"root\" gravity=\"0 -9.81 0\" dt=\"0.01\">\n"
                      << body << "\n</Node>\n";
  ViewOptions options;
  options.scene = path.string();
  return options;
}

TEST(ViewerSession, StepsWhilePlayingAndMeasuresSpeed) {
  ViewOptions options = options_for("session_steps", testing::small_beam());
  options.paused = true;
  ViewerSession session(options);
  EXPECT_FALSE(session.playing);
  EXPECT_EQ(session.title(), "scene.scn");
  session.advance();
  EXPECT_EQ(session.simulation().steps_done(), 0);
  session.step();
  EXPECT_EQ(session.simulation().steps_done(), 1);
  session.playing = true;
  session.steps_per_frame = 3;
  session.advance();
  EXPECT_EQ(session.simulation().steps_done(), 4);
  EXPECT_GT(session.steps_per_second(), 0);
  session.reload();
  EXPECT_EQ(session.simulation().steps_done(), 0);
  EXPECT_TRUE(session.message.empty());
}

TEST(ViewerSession, ChangesMethodAndMaterialLive) {
  ViewerSession session(options_for("session_material", testing::small_beam()));
  ASSERT_EQ(session.materials.size(), 1u);
  EXPECT_EQ(session.materials[0].method, RotationMethod::qr);
  EXPECT_EQ(session.materials[0].young_modulus, 1000);
  EXPECT_EQ(session.materials[0].poisson_ratio, 0.3);
  auto& fields = session.simulation().objects[0].system.force_fields;
  session.set_method(0, RotationMethod::polar);
  EXPECT_EQ(testing::corotational(fields[0]).method(), RotationMethod::polar);
  session.set_material(0, 5000, 0.45);
  EXPECT_TRUE(session.message.empty()) << session.message;
  EXPECT_EQ(testing::corotational(fields[0]).parameters().young_modulus, (std::vector<double>{5000}));
  EXPECT_EQ(testing::corotational(fields[0]).parameters().poisson_ratio, (std::vector<double>{0.45}));
  EXPECT_EQ(testing::corotational(fields[0]).method(), RotationMethod::polar);  // kept
  EXPECT_EQ(session.materials[0].young_modulus, 5000);
  const auto before = fields[0];
  session.set_material(0, 5000, 0.5);  // refused: nu must be below 0.5
  EXPECT_EQ(fields[0], before);
  EXPECT_NE(session.message.find("root/beam"), std::string::npos) << session.message;
  session.set_material(0, -1, 0.3);
  EXPECT_EQ(fields[0], before);
  session.step();  // the rebuilt field simulates
  EXPECT_EQ(session.simulation().steps_done(), 1);
}

TEST(ViewerSession, DivergencePausesWithAMessage) {
  ViewerSession session(options_for("session_diverge", testing::small_beam()));
  session.simulation().objects[0].system.state.velocity[5].x() =
      std::numeric_limits<double>::quiet_NaN();
  session.advance();
  EXPECT_FALSE(session.playing);
  EXPECT_NE(session.message.find("diverged"), std::string::npos) << session.message;
}

TEST(ViewerSession, BadOptionsAreErrors) {
  ViewOptions options = options_for("session_bad", testing::small_beam());
  options.threads = -1;
  EXPECT_THROW(ViewerSession{options}, Error);
  options.threads = 1;
  options.dt = -1.0;
  EXPECT_THROW(ViewerSession{options}, Error);
  options.dt.reset();
  options.picture.drawing = "sometimes";
  EXPECT_THROW(ViewerSession{options}, Error);
  options.picture.drawing = "scene";
  options.scene = "/nonexistent.scn";
  EXPECT_THROW(ViewerSession{options}, Error);
}

// Looks straight down −y at (x, z) from y = 20 (right is +x), in a 201 × 201 picture.
Camera camera_above(double x, double z) {
  Camera camera;
  camera.eye = {x, 20, z};
  camera.target = {x, 0, z};
  camera.up = {0, 0, -1};
  return camera;
}
constexpr int kSize = 201;

// Tetrahedra of `mesh` connected (through shared vertices) to tetrahedra holding point `from`,
// reaching point `to`: whether the two points are still in one piece.
bool connected(const TetMesh& mesh, Index from, Index to) {
  std::vector<Index> parent(static_cast<std::size_t>(mesh.num_points()));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](Index v) {
    while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)];
    return v;
  };
  for (const Tetrahedron& t : mesh.tetrahedra()) {
    for (std::size_t k = 1; k < 4; ++k) parent[static_cast<std::size_t>(root(t[k]))] = root(t[0]);
  }
  return root(from) == root(to);
}

TEST(ViewerSession, CutAtAPixelRemovesTheTetrahedronUnderIt) {
  // Small beam: cells x in [0, 1] (tetrahedra 0..5, fixed end) and [1, 2] (6..11), y, z in [0, 1].
  // The centre pixel looks down at (1.3, 0.6), off the diagonals of the top face of cell 1: the
  // ray meets y = 1 in a tetrahedron of cell 1, whose vertices all have x >= 1.
  ViewOptions options = options_for("session_cut", testing::small_beam());
  options.paused = true;
  ViewerSession session(options);
  const TetMesh& mesh = *session.simulation().objects[0].mesh;
  const auto& rest = session.simulation().objects[0].system.state.rest_position;
  auto in_cell_1 = [&] {
    int count = 0;
    for (const Tetrahedron& t : mesh.tetrahedra()) {
      bool inside = true;
      for (Index v : t) inside = inside && rest[static_cast<std::size_t>(v)].x() >= 1;
      count += inside;
    }
    return count;
  };
  ASSERT_EQ(in_cell_1(), 6);
  EXPECT_GT(session.cut_radius, 0);  // a small brush by default
  session.cut_radius = 0;            // one tetrahedron per cut
  const Camera camera = camera_above(1.3, 0.6);
  EXPECT_EQ(session.cut_at(camera, kSize, kSize, {100.5, 100.5}), 1u);
  EXPECT_TRUE(session.message.empty()) << session.message;
  EXPECT_EQ(mesh.num_tetrahedra(), 11);
  EXPECT_EQ(in_cell_1(), 5);
  EXPECT_EQ(session.removed_tetrahedra(), 1u);
  // The force field and the mass followed: the cut beam steps.
  session.step();
  session.step();
  EXPECT_EQ(session.simulation().steps_done(), 2);
  EXPECT_TRUE(session.message.empty()) << session.message;
  EXPECT_EQ(session.simulation().objects[0].system.force_fields[0]->mesh().num_tetrahedra(), 11);

  // The corner pixel looks at about (1.3 - 5.4, 0, 0.6 - 5.4) (30 degrees of view from 20 above):
  // no object, no change.
  EXPECT_EQ(session.cut_at(camera, kSize, kSize, {0.5, 0.5}), 0u);
  EXPECT_EQ(mesh.num_tetrahedra(), 11);
  EXPECT_EQ(session.removed_tetrahedra(), 1u);
  EXPECT_TRUE(session.message.empty());
  // A window minimised to nothing cuts nothing either.
  EXPECT_EQ(session.cut_at(camera, 0, 0, {0, 0}), 0u);

  // A brush wide enough for the beam takes every tetrahedron but the last one, which stays.
  session.cut_radius = 10;
  EXPECT_EQ(session.cut_at(camera, kSize, kSize, {100.5, 100.5}), 10u);
  EXPECT_EQ(session.simulation().objects[0].mesh->num_tetrahedra(), 1);
  EXPECT_NE(session.message.find("last tetrahedron"), std::string::npos) << session.message;
  session.step();
  EXPECT_EQ(session.simulation().steps_done(), 3);

  session.reload();  // a fresh beam, nothing removed yet
  EXPECT_EQ(session.simulation().objects[0].mesh->num_tetrahedra(), 12);
  EXPECT_EQ(session.removed_tetrahedra(), 0u);
}

TEST(ViewerSession, BadCutsChangeNothingAndSayWhy) {
  ViewerSession session(options_for("session_bad_cut", testing::small_beam()));
  const std::vector<Index> out_of_range = {3, 12};
  EXPECT_EQ(session.cut(0, out_of_range), 0u);
  EXPECT_NE(session.message.find("root/beam"), std::string::npos) << session.message;
  EXPECT_EQ(session.simulation().objects[0].mesh->num_tetrahedra(), 12);
  const std::vector<Index> twice = {4, 4};
  EXPECT_EQ(session.cut(0, twice), 0u);
  EXPECT_EQ(session.simulation().objects[0].mesh->num_tetrahedra(), 12);
  EXPECT_EQ(session.cut(7, out_of_range), 0u);
  EXPECT_NE(session.message.find("no object 7"), std::string::npos) << session.message;
  EXPECT_EQ(session.removed_tetrahedra(), 0u);
  const std::vector<Index> two = {11, 0};
  EXPECT_EQ(session.cut(0, two), 2u);
  EXPECT_TRUE(session.message.empty()) << session.message;
  EXPECT_EQ(session.removed_tetrahedra(), 2u);
}

TEST(ViewerSession, ACutAcrossABeamSeparatesItsFreeEnd) {
  // A 4 × 1 × 1 beam of unit cells (points 5 × 2 × 2), stiff enough to barely sag, fixed at x = 0.
  // Drilling down through cell [2, 3] on a 10 × 10 grid of pixels takes all six of its tetrahedra:
  // each projects to a triangle of area >= 1/2 of the cell's top, which the grid cannot miss. The
  // rays spread out from the eye 20 above: one through (x, 1, z) on the top meets the bottom at
  // 2 + (x - 2) 20 / 19 (likewise z), so x in [2.07, 2.88] stays inside (2, 3) all the way down.
  // Other cells' centroids are at x <= 1.75 or >= 3.25, over 0.3 from every hit, so a brush of
  // 0.2 takes none of them: exactly 6 go, and the end
  // x in [3, 4] is a free body that falls: about g t² / 2 = 1.2 in 0.5 s (less a little damping).
  ViewOptions options = options_for("session_separate", R"(
  <Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    <EigenSimplicialLDLT/>
    <RegularGridTopology name="grid" n="5 2 2" min="0 0 0" max="4 1 1"/>
    <MechanicalObject name="state"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
    <DiagonalMass massDensity="2"/>
    <FastTetrahedralCorotationalForceField youngModulus="1e6" poissonRatio="0.3"/>
    <BoxROI name="roi" box="-0.1 -0.1 -0.1 0.1 1.1 1.1"/>
    <FixedProjectiveConstraint indices="@roi.indices"/>
  </Node>)");
  options.paused = true;
  ViewerSession session(options);
  const auto& object = session.simulation().objects[0];
  // Point (i, j, k) is i + 5 (j + 2 k): the top far corner of the free end and of the fixed part.
  const Index tip = 4 + 5 * (1 + 2 * 1), inner = 2 + 5 * (1 + 2 * 1);
  ASSERT_TRUE(connected(*object.mesh, 0, tip));
  session.cut_radius = 0.2;
  const Camera camera = camera_above(2, 0.5);
  for (int i = 0; i < 10; ++i) {
    for (int k = 0; k < 10; ++k) {
      const auto pixel = camera.project({2.07 + 0.09 * i, 1, 0.07 + 0.1 * k}, kSize, kSize);
      ASSERT_TRUE(pixel);
      for (int drill = 0; drill < 7 && session.cut_at(camera, kSize, kSize, *pixel) > 0; ++drill) {
      }
    }
  }
  EXPECT_EQ(session.removed_tetrahedra(), 6u);
  EXPECT_EQ(object.mesh->num_tetrahedra(), 18);
  EXPECT_FALSE(connected(*object.mesh, 0, tip));
  EXPECT_TRUE(connected(*object.mesh, 0, inner));

  session.playing = true;
  session.steps_per_frame = 50;  // 0.5 s
  session.advance();
  EXPECT_EQ(session.simulation().steps_done(), 50);
  EXPECT_TRUE(session.message.empty()) << session.message;
  const auto& x = object.system.state.position;
  EXPECT_LT(x[static_cast<std::size_t>(tip)].y(), 1 - 0.9);
  EXPECT_GT(x[static_cast<std::size_t>(inner)].y(), 1 - 0.05);
}

// A script's scene (through a loader written here in place of the Python module's): each step is
// wrapped in the controllers' begin and end, keys reach them, and reload builds the scene again.
class KeyedSource final : public SceneSource {
 public:
  explicit KeyedSource(std::vector<std::string>& events) : events_(events), scene_(build()) {}
  LoadedScene& scene() override { return scene_; }
  LoadedScene& reload() override {
    events_.push_back("reload");
    scene_ = build();
    return scene_;
  }
  void begin_step() override { events_.push_back("begin"); }
  void end_step() override { events_.push_back("end"); }
  void key_pressed(char key) override {
    if (key == 'X') throw make_error("script.py:3: ValueError: no X (in a controller's KeypressedEvent)");
    events_.push_back(std::string("key ") + key);
    if (key == 'G') {  // a controller adding a node: the scene built again in place, with a second beam
      scene_ = build(2);
      rebuilt_ = true;
    }
  }
  bool take_rebuilt() override { return std::exchange(rebuilt_, false); }

 private:
  static LoadedScene build(int beams = 1) {
    std::string nodes;
    for (int b = 0; b < beams; ++b) nodes += "<Node name=\"beam" + std::to_string(b) + "\">" + testing::small_beam() + "</Node>";
    return build_scene(parse_scene_text("<Node name=\"root\">" + nodes + "</Node>", "script.py"));
  }
  std::vector<std::string>& events_;
  LoadedScene scene_;
  bool rebuilt_ = false;
};

TEST(ViewerSession, AScriptsControllersGetTheStepsAndTheKeys) {
  std::vector<std::string> events;
  set_script_loader([&](const std::string&, bool) -> std::unique_ptr<SceneSource> {
    return std::make_unique<KeyedSource>(events);
  });
  ViewOptions options;
  options.scene = "script.py";
  options.paused = true;
  {
    ViewerSession session(options);
    session.step();
    session.key_pressed('L');
    ASSERT_EQ(session.materials.size(), 1u);
    session.key_pressed('G');
    EXPECT_EQ(session.materials.size(), 2u) << "the viewer follows a scene its script built again";
    session.step();
    session.reload();
    EXPECT_EQ(session.simulation().steps_done(), 0);
    session.key_pressed('X');
    EXPECT_NE(session.message.find("no X"), std::string::npos);
  }
  set_script_loader(nullptr);
  EXPECT_EQ(events, (std::vector<std::string>{"begin", "end", "key L", "key G", "begin", "end", "reload"}));
}

}  // namespace
}  // namespace fastcorot::cli
