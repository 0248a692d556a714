// A state no ODE solver integrates, moved by a LinearMovementProjectiveConstraint (on its own
// points, or on the rigid body that carries them), with a point tied to it by a
// BilateralLagrangianConstraint: SOFA's FreeMotionAnimationLoop projects every state at a step's
// end at the step's start time, so the target reaches x0 + m(t_k) after step k + 1 and the tied
// point, which meets the target's position at the start of its step, follows one step later:
// x_bob(k) = x0 + m((k - 2) dt) from step 2 on. The movement is written here in closed form. And a
// beam tied to still states and to points a moving rigid carries, with the solver's SVD
// regularisation, against SOFA's own trajectory (tests/data/sofa_reference/moving_target_beam*).
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/scene/scene_graph.h"

#include "../support/scene_text.h"
#include "support/sofa_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;

const double kDt = 0.01;

// Point `bob` (mass 1, no gravity) under its own solver, tied to point 0 of `target`.
std::string tied_to(const std::string& target) {
  return "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver tolerance=\"1e-15\" maxIterations=\"1000\"/>" + target +
         "<Node name=\"bob\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
         "<MechanicalObject name=\"point\" position=\"0.5 0.2 0\"/><UniformMass totalMass=\"1\"/>"
         "<LinearSolverConstraintCorrection/></Node>"
         "<BilateralLagrangianConstraint object1=\"@bob/point\" object2=\"@target/points\" first_point=\"0\" second_point=\"0\"/>";
}

TEST(UnsimulatedMotion, APointMovedByItsOwnLinearMovementDrawsTheTiedPointAlong) {
  // m(t) = (t, 2t, 0) for t in [0, 1): the target starts at (0.5, 0.2, 0).
  LoadedScene scene = build_scene_text(
      tied_to("<Node name=\"target\"><MechanicalObject name=\"points\" position=\"0.5 0.2 0  3 3 3\"/>"
              "<LinearMovementProjectiveConstraint indices=\"0\" keyTimes=\"0 1\" movements=\"0 0 0  1 2 0\"/></Node>"),
      "dt=\"0.01\" gravity=\"0 0 0\"");
  const auto& x = scene.simulation.objects[0].system.state.position;
  bool said = false;
  for (const auto& line : scene.info) said = said || line.find("moves it at each step's end") != std::string::npos;
  EXPECT_TRUE(said);
  for (int k = 1; k <= 60; ++k) {
    scene.simulation.step();
    const double t = std::max(0, k - 2) * kDt;
    ASSERT_NEAR(x[0].x(), 0.5 + t, 1e-12) << "step " << k;
    ASSERT_NEAR(x[0].y(), 0.2 + 2 * t, 1e-12) << "step " << k;
    ASSERT_NEAR(x[0].z(), 0.0, 1e-12) << "step " << k;
  }
}

TEST(UnsimulatedMotion, APointCarriedByAMovingRigidFollowsItsTurn) {
  // The rigid at (0.5, 0.2, 0) turns about z at 1 rad/s and moves along z at 0.5 m/s; its carried
  // point sits at local (1, 0, 0), so the tied point starts at (1.5, 0.2, 0).
  LoadedScene scene = build_scene_text(
      "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver tolerance=\"1e-15\" maxIterations=\"1000\"/>"
      "<Node name=\"frame\"><MechanicalObject name=\"rigid\" template=\"Rigid3d\" position=\"0.5 0.2 0 0 0 0 1\"/>"
      "<LinearMovementProjectiveConstraint indices=\"0\" keyTimes=\"0 2\" movements=\"0 0 0 0 0 0  0 0 1 0 0 2\"/>"
      "<Node name=\"target\"><MechanicalObject name=\"points\" position=\"1 0 0\"/><RigidMapping/></Node></Node>"
      "<Node name=\"bob\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
      "<MechanicalObject name=\"point\" position=\"1.5 0.2 0\"/><UniformMass totalMass=\"1\"/>"
      "<LinearSolverConstraintCorrection/></Node>"
      "<BilateralLagrangianConstraint object1=\"@bob/point\" object2=\"@frame/target/points\" first_point=\"0\" second_point=\"0\"/>",
      "dt=\"0.01\" gravity=\"0 0 0\"");
  const auto& x = scene.simulation.objects[0].system.state.position;
  for (int k = 1; k <= 60; ++k) {
    scene.simulation.step();
    const double t = std::max(0, k - 2) * kDt;
    ASSERT_NEAR(x[0].x(), 0.5 + std::cos(t), 1e-12) << "step " << k;
    ASSERT_NEAR(x[0].y(), 0.2 + std::sin(t), 1e-12) << "step " << k;
    ASSERT_NEAR(x[0].z(), 0.5 * t, 1e-12) << "step " << k;
  }
}

TEST(UnsimulatedMotion, AStillStateStaysPutAndOtherMovementsAreWarned) {
  LoadedScene still = build_scene_text(tied_to("<Node name=\"target\"><MechanicalObject name=\"points\" position=\"0.5 0.2 0\"/></Node>"),
                                       "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  for (int k = 0; k < 10; ++k) still.simulation.step();
  EXPECT_NEAR(still.simulation.objects[0].system.state.position[0].y(), 0.2, 1e-12);
  LoadedScene affine = build_scene_text(tied_to("<Node name=\"target\"><MechanicalObject name=\"points\" position=\"0.5 0.2 0\"/>"
                                                "<AffineMovementProjectiveConstraint indices=\"0\" endTime=\"1\"/></Node>"),
                                        "dt=\"0.01\"");
  const auto& warnings = affine.warnings;
  bool warned = false;
  for (const auto& line : warnings) warned = warned || line.find("no ODE solver integrates it here: it stays put") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(UnsimulatedMotion, BeamTiedToAMovingFrameFollowsSofaFor300Steps) {
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("moving_target_beam.scn"));
  const auto reference = testing::load_sofa_trajectory("moving_target_beam_trajectory.json");
  auto& simulation = scene.simulation;
  ASSERT_EQ(simulation.objects.size(), 1u);
  const auto& x = simulation.objects[0].system.state.position;
  const auto rest = testing::json_points(reference["steps"]["0"]);
  ASSERT_EQ(x.size(), rest.size());
  for (const long step : testing::dumped_steps(reference)) {
    while (simulation.steps_done() < step) simulation.step();
    const auto d = testing::compare_points(x, testing::json_points(reference["steps"][std::to_string(step)]), rest);
    // SOFA's solve stops at its tolerance (1e-4 per row) after two sweeps, and so does this one,
    // on the same sweeps: the two agree to rounding.
    EXPECT_LE(d.difference, 1e-9 * d.displacement + 1e-15) << "step " << step;
  }
  EXPECT_EQ(simulation.constraint_report().rows, 36);
}

TEST(UnsimulatedMotion, RigidDrivenByAMovementPullsASoftCubeAsSofa) {
  // A simulated rigid body driven by a LinearMovementProjectiveConstraint: SOFA's free motion
  // projects its free velocity to zero (projectResponse), so the cube tied to it is pulled by the
  // movement's positions, not by the rate its velocity holds (tests/data/sofa_reference).
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("moving_rigid_attachment.scn"));
  const auto reference = testing::load_sofa_trajectory("moving_rigid_attachment_trajectory.json");
  auto& simulation = scene.simulation;
  ASSERT_EQ(simulation.objects.size(), 2u);
  const auto rest = testing::json_points(reference["steps"]["0"]["cube"]);
  for (const long step : testing::dumped_steps(reference)) {
    while (simulation.steps_done() < step) simulation.step();
    const auto& frame = reference["steps"][std::to_string(step)];
    const auto expected = testing::json_points(frame["cube"]);
    ASSERT_EQ(simulation.objects[0].system.state.position.size(), expected.size());
    const auto d = testing::compare_points(simulation.objects[0].system.state.position, expected, rest);
    EXPECT_LE(d.difference, 1e-9 * d.displacement + 1e-15) << "step " << step;
    const auto& centre = frame["frame"][0];
    EXPECT_NEAR((simulation.objects[1].system.state.position[0] - Vec3<double>(centre[0], centre[1], centre[2])).norm(), 0.0, 1e-12)
        << "step " << step;
  }
}

TEST(UnsimulatedMotion, AStillStateIsPlacedOnceAndTwoMovementsAreRefused) {
  // The target's translation (dx) applies once: the tied point is pulled to (0.5 + 0.25, 0.2, 0).
  LoadedScene placed = build_scene_text(tied_to("<Node name=\"target\"><MechanicalObject name=\"points\" position=\"0.5 0.2 0\" dx=\"0.25\"/></Node>"),
                                        "dt=\"0.01\" gravity=\"0 0 0\"");
  placed.simulation.step();
  EXPECT_NEAR(placed.simulation.objects[0].system.state.position[0].x(), 0.75, 1e-12);
  const std::string two = tied_to("<Node name=\"target\"><MechanicalObject name=\"points\" position=\"0.5 0.2 0\"/>"
                                  "<LinearMovementProjectiveConstraint indices=\"0\" keyTimes=\"0 1\" movements=\"0 0 0  1 0 0\"/>"
                                  "<LinearMovementProjectiveConstraint indices=\"0\" keyTimes=\"0 1\" movements=\"0 0 0  0 1 0\"/></Node>");
  EXPECT_NE(testing::scene_error(two).find("a second LinearMovementProjectiveConstraint"), std::string::npos) << testing::scene_error(two);
}

TEST(UnsimulatedMotion, AnExplicitlyIntegratedMovingPointHasNoFreeMotion) {
  // The target is simulated by an explicit solver (no integration factors) and moved by a
  // LinearMovement: its free velocity is projected to zero, so its free position is where the step
  // began and the tied point follows one step behind, as with a still target.
  LoadedScene scene = build_scene_text(
      "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver tolerance=\"1e-15\" maxIterations=\"1000\"/>"
      "<Node name=\"target\"><EulerExplicitSolver/><MechanicalObject name=\"points\" position=\"0.5 0.2 0\"/><UniformMass totalMass=\"1\"/>"
      "<LinearMovementProjectiveConstraint indices=\"0\" keyTimes=\"0 1\" movements=\"0 0 0  1 2 0\"/>"
      "<UncoupledConstraintCorrection defaultCompliance=\"1e-12\" useOdeSolverIntegrationFactors=\"0\"/></Node>"
      "<Node name=\"bob\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
      "<MechanicalObject name=\"point\" position=\"0.5 0.2 0\"/><UniformMass totalMass=\"1\"/><LinearSolverConstraintCorrection/></Node>"
      "<BilateralLagrangianConstraint object1=\"@bob/point\" object2=\"@target/points\" first_point=\"0\" second_point=\"0\"/>",
      "dt=\"0.01\" gravity=\"0 0 0\"");
  const auto& bob = scene.simulation.objects[1].system.state.position;
  for (int k = 1; k <= 20; ++k) {
    scene.simulation.step();
    const double t = std::max(0, k - 2) * kDt;
    ASSERT_NEAR(bob[0].x(), 0.5 + t, 1e-9) << "step " << k;
  }
}

}  // namespace
}  // namespace fastcorot
