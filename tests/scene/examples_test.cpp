// Every shipped example scene loads and runs; the cylinder traction example is checked against
// the elongation of a bar, F L / (E A).
#include "fastcorot/scene/scene_builder.h"

#include <gtest/gtest.h>

#include <numbers>

namespace fastcorot {
namespace {

std::string example(const std::string& name) { return std::string(FASTCOROT_EXAMPLES_DIR) + "/" + name; }

class ExampleScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ExampleScene, LoadsAndRunsTwoSteps) {
  LoadedScene scene = load_scene_file(example(GetParam()));
  ASSERT_FALSE(scene.simulation.objects.empty());
  scene.simulation.step();
  scene.simulation.step();
  for (const auto& object : scene.simulation.objects) {
    double moved = 0;
    for (std::size_t i = 0; i < object.system.state.position.size(); ++i) {
      moved = std::max(moved, (object.system.state.position[i] - object.system.state.rest_position[i]).norm());
    }
    EXPECT_GT(moved, 0.0) << object.path << " did not move";
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, ExampleScene,
                         ::testing::Values("four_beams.scn", "cantilever_beam_40x10x10.scn",
                                           "cantilever_beam_76x16x16.scn", "cylinder_static.scn", "beam_cut.scn",
                                           "cantilever_beam_40x10x10_pcg.scn", "cantilever_beam_40x10x10_tfem.scn",
                                           "tetrahedron_fem_beams.scn", "softrobots/cable_finger.scn"),
                         [](const auto& info) {
                           std::string name = info.param.substr(0, info.param.find('.'));
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(CylinderTraction, ElongationApproachesTheBarFormula) {
  LoadedScene scene = load_scene_file(example("cylinder_static.scn"));
  auto& simulation = scene.simulation;
  simulation.step();
  const auto& state = simulation.objects.at(0).system.state;
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < state.position.size(); ++i) {
    if (state.rest_position[i].z() > 0.999) {
      sum += state.position[i].z() - state.rest_position[i].z();
      ++count;
    }
  }
  ASSERT_GT(count, 10);
  // F = 50, L = 1, E = 1000, A = π (radius 1): a free bar stretches by F L / (E A). The clamped base
  // cannot contract laterally, which stiffens the cylinder a little; the mesh's polygonal section
  // has slightly less area than π.
  const double bar = 50.0 / (1000.0 * std::numbers::pi);
  const double elongation = sum / count;
  EXPECT_GT(elongation, 0.95 * bar);
  EXPECT_LT(elongation, 1.02 * bar);
}

}  // namespace
}  // namespace fastcorot
