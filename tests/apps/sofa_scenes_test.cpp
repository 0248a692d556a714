// A fast subset of SOFA's own example scenes (../shared/sofa-scenes beside the project, where
// scripts/sofa-scenes runs them all): each runs 100 steps (FASTCOROT_TEST_SCENE_STEPS when set:
// scripts/test --sanitize sets 20) from its folder, as runSofa runs it, to finite positions; a scene that needs what fastcorot lacks is refused with status 2 and one error
// line naming it. Skipped where the scenes are not beside the checkout.
#include "fastcorot/core/error.h"
#include "support/command.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <filesystem>
#include <fstream>

namespace fastcorot {
namespace {

std::filesystem::path sofa_examples() {
  return std::filesystem::path(FASTCOROT_SOURCE_DIR) / "../shared/sofa-scenes/examples";
}

std::string scene_steps() {
  const char* set = std::getenv("FASTCOROT_TEST_SCENE_STEPS");
  const int steps = set != nullptr ? std::atoi(set) : 0;
  return std::to_string(steps > 0 ? steps : 100);
}

class SofaScene : public ::testing::TestWithParam<std::string> {};

TEST_P(SofaScene, RunsToFinitePositions) {
  const std::string steps = scene_steps();
  const auto scene = sofa_examples() / GetParam();
  if (!std::filesystem::exists(scene)) GTEST_SKIP() << "no " << scene;
  const auto dump = std::filesystem::temp_directory_path() /
                    ("fastcorot_sofa_scene_" + std::to_string(::getpid()) + "_" + scene.stem().string() + ".json");
  const auto result = testing::shell("cd '" + scene.parent_path().string() + "' && " FASTCOROT_EXECUTABLE " run '" +
                                     scene.filename().string() + "' --steps " + steps + " --quiet --dump-state '" + dump.string() +
                                     "' --dump-steps " + steps + " 2>&1");
  ASSERT_EQ(result.status, 0) << result.output;
  const auto state = nlohmann::json::parse(std::ifstream(dump));
  std::filesystem::remove(dump);
  std::size_t values = 0;
  for (const auto& [object, points] : state["steps"][steps].items()) {
    for (const auto& p : points) {
      for (const auto& v : p) {
        ASSERT_TRUE(std::isfinite(v.get<double>())) << object;
        ++values;
      }
    }
  }
  EXPECT_GT(values, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Examples, SofaScene,
    ::testing::Values("Component/SolidMechanics/FEM/TetrahedronFEMForceField.scn",
                      "Component/SolidMechanics/FEM/TetrahedronFEMForceField_Chain.scn",
                      "Component/SolidMechanics/FEM/FastTetrahedralCorotationalForceField.scn",
                      "Component/Topology/Mapping/Hexa2TetraTopologicalMapping.scn",
                      "Component/Topology/Container/Constant/MeshTopology.scn",
                      "Component/Mapping/Linear/BarycentricTetraMapping.scn", "Component/Mapping/Linear/SubsetMapping.scn",
                      "Component/Mapping/Linear/BarycentricMapping.scn", "Component/Engine/Select/SubsetTopology_subsetbehaviormodel.scn",
                      "Component/Engine/Select/MeshSplittingEngine.scn",
                      "Component/Playback/WriteState.scn", "Component/Playback/CompareState.scn",
                      "Component/Collision/Geometry/SphereModel.scn",
                      "Component/ODESolver/Forward/EulerSymplecticSolver_diagonal.scn",
                      "Component/ODESolver/Forward/RungeKutta4Solver.scn",
                      "Component/Constraint/Projective/PartialFixedProjectiveConstraint.scn",
                      "Component/Constraint/Projective/FixedPlaneProjectiveConstraint.scn",
                      "Component/Constraint/Projective/PlaneProjectiveConstraint.scn",
                      "Component/Constraint/Projective/PlaneConstraint.scn",
                      "Component/Constraint/Projective/AffineMovementProjectiveConstraint3D.scn",
                      "Component/Constraint/Projective/AttachProjectiveConstraint.scn",
                      "Component/Constraint/Projective/BilinearConstraint3D.scn",
                      "Component/LinearSolver/Preconditioner/FEMBAR_PCG_PrecomputedWarpPreconditioner.scn",
                      "Component/Constraint/Projective/AttachProjectiveConstraintMatrix.scn",
                      "Component/MechanicalLoad/ConicalForceField.scn",
                      "Component/MechanicalLoad/TrianglePressureForceField.scn",
                      "Component/Engine/Generate/GenerateCylinder.scn",
                      "Component/Topology/Container/Grid/CylinderGridTopology.scn",
                      "Component/Engine/Select/ValuesFromPositions_vectorField.scn",
                      "Component/Topology/Container/Dynamic/TetrahedronForceFieldTopologyChangeHandling.scn",
                      "Component/Constraint/Lagrangian/FixedLagrangianConstaint_Vec3.scn",
                      "Component/Constraint/Lagrangian/PreconditionedConjugateResidual.scn",
                      "Component/Constraint/Lagrangian/BilateralLagrangianConstraint_Soft_Rigid_Bodies.scn",
                      "Component/SolidMechanics/FEM/Heterogeneous-TetrahedronFEMForceField.scn",
                      "Component/Engine/Select/NearestPointROI.scn"),
    [](const auto& info) {
      std::string name = std::filesystem::path(info.param).stem().string();
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

TEST(SofaScenes, ASceneNeedingWhatIsMissingIsRefusedInOneLine) {
  const auto scene = sofa_examples() / "Component/SolidMechanics/FEM/StandardTetrahedralFEMForceField.scn";
  if (!std::filesystem::exists(scene)) GTEST_SKIP() << "no " << scene;
  const auto result = testing::shell("cd '" + scene.parent_path().string() + "' && " FASTCOROT_EXECUTABLE " run '" +
                                     scene.filename().string() + "' --steps 1 --quiet 2>&1");
  EXPECT_EQ(result.status, 2) << result.output;
  std::size_t errors = 0;
  for (std::size_t at = result.output.find("error:"); at != std::string::npos; at = result.output.find("error:", at + 1)) ++errors;
  EXPECT_EQ(errors, 1u) << result.output;
  EXPECT_NE(result.output.find("StandardTetrahedralFEMForceField: this scene needs what fastcorot does not have: "
                               "hyperelastic FEM is not simulated"),
            std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace fastcorot
