// The viewer's state without a window: play/pause and steps, live method and material changes
// (refused values change nothing and leave a message), divergence pauses, reload starts over.
#include "viewer_session.h"

#include "fastcorot/core/error.h"
#include "render/render_scenes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

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
  EXPECT_EQ(fields[0]->method(), RotationMethod::polar);
  session.set_material(0, 5000, 0.45);
  EXPECT_TRUE(session.message.empty()) << session.message;
  EXPECT_EQ(fields[0]->parameters().young_modulus, (std::vector<double>{5000}));
  EXPECT_EQ(fields[0]->parameters().poisson_ratio, (std::vector<double>{0.45}));
  EXPECT_EQ(fields[0]->method(), RotationMethod::polar);  // kept
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
  options.threads = 0;
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

}  // namespace
}  // namespace fastcorot::cli
