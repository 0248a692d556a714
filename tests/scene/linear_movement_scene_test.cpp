// LinearMovementProjectiveConstraint on points and on rigid bodies, through the scene builder,
// against SOFA's rules worked out here (LinearMovementProjectiveConstraint.inl, master 2a278d891f):
// after the step that starts at t, a moved point is at x0 + m(t), m interpolated linearly between
// the keys around t, with the keys' rate as velocity; it is held during the solve (a spring pulling
// on it does not move it); a rigid body's orientation is q0 times the slerp between the keys'
// Euler-angle rotations (computed here with Eigen's AngleAxis products and slerp); from the last key
// on the point is free. Bad input refused in one line.
#include "fastcorot/io/checkpoint.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/mapped_state.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const std::string kSolvers = "<EulerImplicitSolver/><CGLinearSolver iterations=\"100\" tolerance=\"1e-30\" threshold=\"1e-30\"/>";

// Two points joined by a spring: point 0 moved by `movement`, point 1 free (no gravity).
std::string two_points(const std::string& movement) {
  return "<Node name=\"pair\">" + kSolvers +
         "<MechanicalObject name=\"dofs\" position=\"1 2 3  2 2 3\"/><UniformMass vertexMass=\"1\"/>"
         "<SpringForceField spring=\"0 1 100 0 1\"/>" + movement + "</Node>";
}

void step(LoadedScene& scene, int steps) {
  for (int s = 0; s < steps; ++s) scene.simulation.step();
}

TEST(LinearMovementScene, APointFollowsTheKeysOneStepBehindAndIsFreeAfterTheLast) {
  const std::string movement =
      "<LinearMovementProjectiveConstraint indices=\"0\" keyTimes=\"0 1 2\" movements=\"0 0 0  1 0 0  1 2 0\"/>";
  const Vec3<double> x0(1, 2, 3);
  // m(t) for t in [0, 2).
  const auto m = [](double t) { return t < 1 ? Vec3<double>(t, 0, 0) : Vec3<double>(1, 2 * (t - 1), 0); };
  LoadedScene scene = build_scene_text(two_points(movement), "dt=\"0.1\" gravity=\"0 0 0\"");
  const auto& state = scene.simulation.objects.at(0).system.state;
  double t = 0;  // the step's start: SOFA's context time when it projects, summed step by step as SOFA's
  for (int n = 1; n <= 20; t += 0.1, ++n) {
    step(scene, 1);
    EXPECT_LT((state.position[0] - (x0 + m(t))).norm(), 1e-14) << "step " << n;
    const Vec3<double> rate = t < 1 ? Vec3<double>(1, 0, 0) : Vec3<double>(0, 2, 0);
    EXPECT_LT((state.velocity[0] - rate).norm(), 1e-14) << "step " << n;
  }
  EXPECT_GT((state.position[1] - Vec3<double>(2, 2, 3)).norm(), 0.1) << "the spring pulled the free point";
  // Step 21 starts at t = 2 (to round-off), the last key: the point is free and moves on with its velocity (the
  // spring's pull added).
  const Vec3<double> before = state.position[0];
  step(scene, 1);
  EXPECT_GT((state.position[0] - before - 0.1 * Vec3<double>(0, 2, 0)).norm(), 1e-6) << "the spring acts on it now";
  EXPECT_LT((state.position[0] - before - 0.1 * Vec3<double>(0, 2, 0)).norm(), 0.05);
}

TEST(LinearMovementScene, AbsoluteMovementsAreThePositions) {
  LoadedScene scene = build_scene_text(
      two_points("<LinearMovementProjectiveConstraint indices=\"0\" relativeMovements=\"0\" keyTimes=\"0 1\" movements=\"5 5 5  7 5 5\"/>"),
      "dt=\"0.1\" gravity=\"0 0 0\"");
  step(scene, 4);
  EXPECT_LT((scene.simulation.objects.at(0).system.state.position[0] - Vec3<double>(5.6, 5, 5)).norm(), 1e-14);
}

Eigen::Quaterniond euler(double a0, double a1, double a2) {
  return Eigen::AngleAxisd(a2, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(a1, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(a0, Eigen::Vector3d::UnitX());
}

TEST(LinearMovementScene, ARigidBodyTurnsBySlerpBetweenTheKeysEulerRotations) {
  // Under gravity with a mass: held during the solve, it does not fall while it moves.
  const std::string scene_text =
      "<Node name=\"body\">" + kSolvers +
      "<MechanicalObject name=\"frame\" template=\"Rigid3d\" position=\"1 0 0  0 0 0.3826834323650898 0.9238795325112867\"/>"
      "<UniformMass totalMass=\"2\"/>"
      "<LinearMovementProjectiveConstraint template=\"Rigid3\" keyTimes=\"0 1 2\" "
      "movements=\"0 0 0 0 0 0   1 0 0 0 0 1.2   1 1 0 0.5 0 1.2\"/>"
      "<Node name=\"carried\"><MechanicalObject name=\"tip\" position=\"1 0 0\"/><RigidMapping/></Node></Node>";
  LoadedScene scene = build_scene_text(scene_text, "dt=\"0.1\"");
  const Eigen::Quaterniond q0(0.9238795325112867, 0, 0, 0.3826834323650898);
  const auto& system = scene.simulation.objects.at(0).system;
  double t = 0;
  for (int n = 1; n <= 20; t += 0.1, ++n) {
    step(scene, 1);
    Vec3<double> centre;
    Eigen::Quaterniond turn;
    Vec3<double> v, w;
    if (t < 1) {  // step 11 starts at 0.1 summed ten times, just below 1, as in SOFA
      centre = Vec3<double>(1 + t, 0, 0);
      turn = euler(0, 0, 0).slerp(t, euler(0, 0, 1.2));
      v = {1, 0, 0}, w = {0, 0, 1.2};
    } else {
      centre = Vec3<double>(2, t - 1, 0);
      turn = euler(0, 0, 1.2).slerp(t - 1, euler(0.5, 0, 1.2));
      v = {0, 1, 0}, w = {0.5, 0, 0};
    }
    const RigidCoord<double> x = system.rigids->coord(system.state.position, 0);
    EXPECT_LT((x.center - centre).norm(), 1e-13) << "step " << n;
    EXPECT_LT((x.orientation.coeffs() - (q0 * turn).coeffs()).norm(), 1e-13) << "step " << n;
    EXPECT_LT((system.state.velocity[0] - v).norm(), 1e-13) << "step " << n;
    EXPECT_LT((system.state.velocity[1] - w).norm(), 1e-13) << "step " << n;
    // The carried point follows the turned frame.
    const auto states = state_snapshots(scene.simulation.objects.at(0));
    ASSERT_EQ(states.size(), 2u);
    EXPECT_LT((states[1].position[0] - (centre + q0 * turn * Vec3<double>(1, 0, 0))).norm(), 1e-12) << "step " << n;
  }
  // From t = 2 on it is free: it falls.
  const Vec3<double> before = system.rigids->coord(system.state.position, 0).center;
  step(scene, 1);
  EXPECT_NEAR(system.state.velocity[0].y(), 1 - 9.81 * 0.1, 1e-12);
  EXPECT_LT((system.rigids->coord(system.state.position, 0).center - before - 0.1 * Vec3<double>(0, 1 - 0.981, 0)).norm(), 1e-12);
}

TEST(LinearMovementScene, BadInputIsRefusedInOneLine) {
  const auto refused = [](const std::string& movement, const std::string& expected) {
    const std::string message = scene_error(two_points(movement));
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  refused("<LinearMovementProjectiveConstraint keyTimes=\"0 2 1\" movements=\"0 0 0 1 0 0 2 0 0\"/>", "key times must be in order");
  refused("<LinearMovementProjectiveConstraint keyTimes=\"0 1\" movements=\"0 0 0 1 0\"/>", "movements has 5 numbers: 2 key times need 6");
  refused("<LinearMovementProjectiveConstraint indices=\"7\" keyTimes=\"0 1\" movements=\"0 0 0 1 0 0\"/>", "index 7 out of range");
  const std::string rigid = scene_error(
      "<Node name=\"body\">" + kSolvers + "<MechanicalObject template=\"Rigid3d\"/><UniformMass totalMass=\"1\"/>"
      "<LinearMovementProjectiveConstraint keyTimes=\"0 1\" movements=\"0 0 0  1 0 0\"/></Node>");
  EXPECT_NE(rigid.find("6 per key: the centre's movement and Euler angles"), std::string::npos) << rigid;
}

TEST(LinearMovementScene, AtInitTheMovingPointGetsTheKeysRateAsSofasInitProjectsIt) {
  LoadedScene scene = build_scene_text(
      two_points("<LinearMovementProjectiveConstraint keyTimes=\"0 1\" movements=\"0 0 0  1 0 0\"/>"), "dt=\"0.1\"");
  EXPECT_EQ(scene.simulation.objects.at(0).system.state.velocity[0], Vec3<double>(1, 0, 0));
  EXPECT_EQ(scene.simulation.objects.at(0).system.state.velocity[1], Vec3<double>::Zero());
}

TEST(LinearMovementScene, ACheckpointResumesTheMovementBitwise) {
  // x0 is the scene's positions (recorded at init), so a resumed run rebuilt from the scene has it.
  const std::string scene_text =
      "<Node name=\"body\">" + kSolvers +
      "<MechanicalObject name=\"frame\" template=\"Rigid3d\" position=\"1 0 0  0 0 0 1\"/><UniformMass totalMass=\"2\"/>"
      "<LinearMovementProjectiveConstraint template=\"Rigid3\" keyTimes=\"0 1 5\" movements=\"0 0 0 0 0 0  1 0 0 0 0 1.2  1 1 0 0.5 0 1.2\"/>"
      "</Node>" + two_points("<LinearMovementProjectiveConstraint keyTimes=\"0 1 5\" movements=\"0 0 0  1 0 0  1 2 0\"/>");
  const std::string path = ::testing::TempDir() + "linear_movement.ckpt";
  LoadedScene uninterrupted = build_scene_text(scene_text, "dt=\"0.1\"");
  step(uninterrupted, 7);
  write_checkpoint(path, uninterrupted.simulation, "test.scn");
  step(uninterrupted, 8);
  LoadedScene resumed = build_scene_text(scene_text, "dt=\"0.1\"");
  restore_checkpoint(path, resumed.simulation);
  step(resumed, 8);
  for (std::size_t o = 0; o < 2; ++o) {
    const auto& a = uninterrupted.simulation.objects.at(o).system;
    const auto& b = resumed.simulation.objects.at(o).system;
    EXPECT_EQ(a.state.position, b.state.position) << o;
    EXPECT_EQ(a.state.velocity, b.state.velocity) << o;
  }
  EXPECT_EQ(uninterrupted.simulation.objects.at(0).system.rigids->orientation[0].coeffs(),
            resumed.simulation.objects.at(0).system.rigids->orientation[0].coeffs());
  std::remove(path.c_str());
}

}  // namespace
}  // namespace fastcorot
