// SOFA's four-beam example scene (tests/data/sofa_reference/four_beams.scn, methods small, large,
// polar, polar2; implicit Euler with Rayleigh damping; EigenSimplicialLDLT) against the positions
// SOFA itself computed after init and after 1 and 10 steps (four_beams_trajectory.json); and a
// TetrahedronFEMForceField beam solved by SparseLDLSolver against SOFA's positions at every step it
// dumped up to 100 (tfem_beam_direct_trajectory.json): a converged solve does not amplify rounding,
// so the two agree to the last digits all along (docs/behaviour.md, "Comparing runs with SOFA's").
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"

#include "support/sofa_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

TEST(SofaTrajectory, DirectlySolvedBeamMatchesSofaAtEveryDumpedStepTo100) {
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("tfem_beam_direct.scn"));
  std::ifstream in(testing::sofa_reference_path("tfem_beam_direct_trajectory.json"));
  const auto reference = nlohmann::json::parse(in);
  auto& simulation = scene.simulation;
  ASSERT_EQ(simulation.objects.size(), 1u);
  const auto& state = simulation.objects[0].system.state;
  const auto rest = testing::json_points(reference["steps"]["0"]);
  ASSERT_EQ(state.position.size(), rest.size());
  std::vector<long> steps;  // the JSON object's keys, in numeric order
  for (const auto& item : reference["steps"].items()) steps.push_back(std::stol(item.key()));
  std::sort(steps.begin(), steps.end());
  int compared = 0;
  for (const long step : steps) {
    while (simulation.steps_done() < step) simulation.step();
    const auto expected = testing::json_points(reference["steps"][std::to_string(step)]);
    double max_difference = 0, max_displacement = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      max_difference = std::max(max_difference, (state.position[i] - expected[i]).cwiseAbs().maxCoeff());
      max_displacement = std::max(max_displacement, (expected[i] - rest[i]).cwiseAbs().maxCoeff());
    }
    EXPECT_LE(max_difference, 1e-11 * max_displacement + 1e-15) << "step " << step;
    ++compared;
  }
  EXPECT_EQ(compared, 8);
  EXPECT_EQ(simulation.steps_done(), 100);
}

// Why a run compared with SOFA's must be converged: SOFA's usual CG of 25 iterations stops far from
// the solution, and each step's error feeds the next, so a change in the last bits grows. Young's
// modulus changed by 1e-12 of itself moves the CG trajectory by far more than 1e-6 of the
// displacement by step 100 (7e-4 measured), and the directly solved one by about 1e-12, at every
// step (docs/behaviour.md, "Comparing runs with SOFA's").
std::vector<std::vector<Vec3<double>>> beam_positions(const std::string& solver, const std::string& young,
                                                      const std::vector<long>& steps) {
  std::ifstream in(testing::sofa_reference_path("tfem_beam_direct.scn"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto replace = [&text](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("<SparseLDLSolver name=\"linearsolver\" template=\"CompressedRowSparseMatrixMat3x3d\"/>", solver);
  replace("youngModulus=\"3000\"", "youngModulus=\"" + young + "\"");
  LoadedScene scene = build_scene(parse_scene_text(text, "tfem_beam_variant.scn"));
  std::vector<std::vector<Vec3<double>>> positions;
  positions.push_back(scene.simulation.objects.at(0).system.state.position);
  for (const long step : steps) {
    while (scene.simulation.steps_done() < step) scene.simulation.step();
    positions.push_back(scene.simulation.objects.at(0).system.state.position);
  }
  return positions;
}

// The largest difference between two runs' positions at each step, relative to the displacement.
std::vector<double> parting(const std::vector<std::vector<Vec3<double>>>& a,
                            const std::vector<std::vector<Vec3<double>>>& b) {
  std::vector<double> relative;
  for (std::size_t s = 1; s < a.size(); ++s) {
    double difference = 0, displacement = 0;
    for (std::size_t i = 0; i < a[s].size(); ++i) {
      difference = std::max(difference, (a[s][i] - b[s][i]).cwiseAbs().maxCoeff());
      displacement = std::max(displacement, (a[s][i] - a[0][i]).cwiseAbs().maxCoeff());
    }
    relative.push_back(difference / displacement);
  }
  return relative;
}

TEST(SofaTrajectory, AnUnconvergedCgAmplifiesRoundingAndADirectSolveDoesNot) {
  const std::vector<long> steps = {10, 30, 100};
  const std::string cg = "<CGLinearSolver iterations=\"25\" tolerance=\"1e-9\" threshold=\"1e-9\"/>";
  const std::string direct = "<SparseLDLSolver/>";
  const auto cg_parting = parting(beam_positions(cg, "3000", steps), beam_positions(cg, "3000.000000003", steps));
  const auto direct_parting =
      parting(beam_positions(direct, "3000", steps), beam_positions(direct, "3000.000000003", steps));
  EXPECT_LT(cg_parting[0], 1e-10);  // step 10: the change itself
  EXPECT_GT(cg_parting[2], 1e-6);   // step 100: grown a million times
  for (std::size_t s = 0; s < steps.size(); ++s) EXPECT_LT(direct_parting[s], 1e-10) << "step " << steps[s];
}

}  // namespace
}  // namespace fastcorot
