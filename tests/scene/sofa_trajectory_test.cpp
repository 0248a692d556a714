// SOFA's four-beam example scene (tests/data/sofa_reference/four_beams.scn, methods small, large,
// polar, polar2; implicit Euler with Rayleigh damping; EigenSimplicialLDLT) against the positions
// SOFA itself computed after init and after 1 and 10 steps (four_beams_trajectory.json).
#include "fastcorot/scene/scene_builder.h"

#include "support/sofa_reference.h"

#include <gtest/gtest.h>

#include <fstream>

namespace fastcorot {
namespace {

TEST(SofaTrajectory, FourBeamsMatchSofaAfter1And10Steps) {
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("four_beams.scn"));
  std::ifstream in(testing::sofa_reference_path("four_beams_trajectory.json"));
  const auto reference = nlohmann::json::parse(in);
  auto& simulation = scene.simulation;
  EXPECT_EQ(simulation.dt, reference["dt"].get<double>());
  ASSERT_EQ(simulation.objects.size(), 4u);
  for (const int step : {0, 1, 10}) {
    while (simulation.steps_done() < step) simulation.step();
    const auto& frame = reference["steps"][std::to_string(step)];
    for (const auto& object : simulation.objects) {
      ASSERT_TRUE(frame.contains(object.path)) << object.path;
      const auto expected = testing::json_points(frame[object.path]);
      const auto rest = testing::json_points(reference["steps"]["0"][object.path]);
      ASSERT_EQ(object.system.state.position.size(), expected.size());
      double max_difference = 0, max_displacement = 0;
      for (std::size_t i = 0; i < expected.size(); ++i) {
        max_difference = std::max(max_difference, (object.system.state.position[i] - expected[i]).cwiseAbs().maxCoeff());
        max_displacement = std::max(max_displacement, (expected[i] - rest[i]).cwiseAbs().maxCoeff());
      }
      // Relative to the displacement (positions themselves agree far more closely).
      EXPECT_LE(max_difference, 1e-9 * max_displacement + 1e-15) << object.path << " at step " << step;
    }
  }
}

}  // namespace
}  // namespace fastcorot
