// SlidingLagrangianConstraint and the Rigid3 Fixed and Bilateral Lagrangian constraints through the
// scene builder. Sliding: a bead on a rail stays on it to the solver's tolerance and moves along it
// as a point mass sliding without friction (the implicit Euler closed form: with the rows across
// the rail, s_n = s_0 + h² g_a n (n + 1) / 2); the stop at the rail's end holds; a rigid cube slides
// on a point it carries a segment through. Rigid3: FixedLagrangianConstraint holds a body at its
// rest pose under gravity and a torque; BilateralLagrangianConstraint keeps two bodies' frames
// together (keepOrientationDifference) or at a rest offset. Bad input is refused naming the component.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const std::string kLoop = "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"1000\" tolerance=\"1e-14\"/>";

// A bead (one point of mass 1) at x on a rail from (0, 0, 0) to (4, 0, 0) that no solver moves.
std::string bead_on_rail(double x) {
  return kLoop +
         "<Node name=\"rail\"><MechanicalObject name=\"ends\" position=\"0 0 0  4 0 0\"/></Node>"
         "<Node name=\"bead\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
         "<MechanicalObject name=\"point\" position=\"" + std::to_string(x) + " 0 0\"/><UniformMass totalMass=\"1\"/>"
         "<LinearSolverConstraintCorrection/></Node>"
         "<SlidingLagrangianConstraint object1=\"@bead/point\" object2=\"@rail/ends\" sliding_point=\"0\" axis_1=\"0\" axis_2=\"1\"/>";
}

TEST(SlidingLagrangianConstraintScene, BeadSlidesFreelyAlongItsRail) {
  // Gravity has 2 m/s² along the rail: the bead slides toward x = 4 and must not fall.
  const double h = 0.01, ga = 2, x0 = 0.5;
  LoadedScene scene = build_scene_text(bead_on_rail(x0), "dt=\"0.01\" gravity=\"2 -9.81 0.5\"");
  ASSERT_TRUE(scene.simulation.constraints);
  const auto& x = scene.simulation.objects[0].system.state.position;
  for (int n = 1; n <= 100; ++n) {
    scene.simulation.step();
    ASSERT_LT(std::hypot(x[0].y(), x[0].z()), 1e-12) << "step " << n << ": off the rail";
    const double closed_form = x0 + h * h * ga * n * (n + 1) / 2;
    ASSERT_NEAR(x[0].x(), closed_form, 1e-12) << "step " << n;
  }
  EXPECT_NEAR(x[0].x(), x0 + 0.5 * ga * 1.0, 0.03) << "½ g t² after 1 s, to the implicit scheme's O(h) drift";
  EXPECT_EQ(scene.simulation.constraint_report().rows, 4);
  EXPECT_TRUE(scene.simulation.constraint_report().converged);
  bool said = false;
  for (const auto& line : scene.info) said = said || line.find("is not simulated (no ODE solver)") != std::string::npos;
  EXPECT_TRUE(said) << "the rail is reported as not simulated";
}

TEST(SlidingLagrangianConstraintScene, DrawsTheBeadTheRailAndTheForcesThatHoldIt) {
  // One step from rest: the rows across the rail cancel gravity's part across it, so the force on
  // the bead is -m g_perp = (0, 9.81, -0.5); the rail's ends take the opposite force, split by β =
  // x / 4 = 0.125 (the bead's place along the rail at the step's start), and the three sum to zero.
  LoadedScene scene = build_scene_text(bead_on_rail(0.5), "dt=\"0.01\" gravity=\"2 -9.81 0.5\"");
  scene.simulation.step();
  ConstraintDrawing drawing;
  scene.simulation.constraints->draw(scene.simulation.objects, scene.simulation.dt, drawing);
  ASSERT_EQ(drawing.points.size(), 3u);
  ASSERT_EQ(drawing.pairs.size(), 1u);
  EXPECT_EQ(drawing.pairs[0], (std::array<std::size_t, 2>{1, 2})) << "the rail's ends joined";
  const Vec3<double> held(0, 9.81, -0.5);
  EXPECT_LT((drawing.points[0].force - held).norm(), 1e-9);
  EXPECT_LT((drawing.points[1].force + 0.875 * held).norm(), 1e-9);
  EXPECT_LT((drawing.points[2].force + 0.125 * held).norm(), 1e-9);
  EXPECT_EQ(drawing.points[2].position, Vec3<double>(4, 0, 0));
}

TEST(SlidingLagrangianConstraintScene, BeadSlidesFreelyAlongAnInclinedRail) {
  // A rail from (0, 0, 0) to (-2, -1, 0.5) under gravity (0, -9.81, 0): g_a = g·a along it.
  const std::string body = kLoop +
                           "<Node name=\"rail\"><MechanicalObject name=\"ends\" position=\"0 0 0  -2 -1 0.5\"/></Node>"
                           "<Node name=\"bead\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>"
                           "<MechanicalObject name=\"point\" position=\"-0.2 -0.1 0.05\"/><UniformMass totalMass=\"1\"/>"
                           "<LinearSolverConstraintCorrection/></Node>"
                           "<SlidingLagrangianConstraint object1=\"@bead/point\" object2=\"@rail/ends\" sliding_point=\"0\" axis_1=\"0\" axis_2=\"1\"/>";
  LoadedScene scene = build_scene_text(body, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const Vec3<double> a = Vec3<double>(-2, -1, 0.5).normalized();
  const double h = 0.01, ga = Vec3<double>(0, -9.81, 0).dot(a), s0 = Vec3<double>(-0.2, -0.1, 0.05).dot(a);
  const auto& x = scene.simulation.objects[0].system.state.position;
  for (int n = 1; n <= 60; ++n) {
    scene.simulation.step();
    const double s = x[0].dot(a);
    ASSERT_LT((x[0] - s * a).norm(), 1e-12) << "step " << n << ": off the rail";
    ASSERT_NEAR(s, s0 + h * h * ga * n * (n + 1) / 2, 1e-12) << "step " << n;
  }
  EXPECT_GT(x[0].dot(a) - s0, 0.5) << "it slid down";
}

TEST(SlidingLagrangianConstraintScene, StopAtTheRailsEndHolds) {
  // Gravity pulls the bead toward x = 0 (reached after 0.71 s); it stays there.
  LoadedScene scene = build_scene_text(bead_on_rail(0.5), "dt=\"0.01\" gravity=\"-2 -9.81 0\"");
  const auto& x = scene.simulation.objects[0].system.state.position;
  const auto& v = scene.simulation.objects[0].system.state.velocity;
  for (int n = 1; n <= 200; ++n) {
    scene.simulation.step();
    ASSERT_GT(x[0].x(), -1e-12) << "step " << n << ": past the end";
    ASSERT_LT(std::abs(x[0].y()), 1e-12) << "step " << n;
  }
  EXPECT_LT(std::abs(x[0].x()), 1e-12) << "at rest on the end";
  EXPECT_LT(v[0].norm(), 1e-9);
}

TEST(SlidingLagrangianConstraintScene, RigidCubeSlidesOnAPointThroughItsSegment) {
  // SOFA's example (SlidingLagrangianConstraint.scn, without its meshes and collision): a rigid cube
  // carries the segment (1, 1.25, ±1); a point that no solver moves, at (1, 1.25, -0.2), must stay on it.
  LoadedScene scene = build_scene_text(
      kLoop +
          "<Node name=\"slider\"><MechanicalObject name=\"points\" position=\"1 1.25 -0.2  1 1.25 0.2\"/></Node>"
          "<Node name=\"cube\"><EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/>"
          "<CGLinearSolver iterations=\"25\" tolerance=\"1e-9\" threshold=\"1e-9\"/>"
          "<MechanicalObject name=\"frame\" template=\"Rigid3d\"/><UniformMass totalMass=\"10\"/><UncoupledConstraintCorrection/>"
          "<Node name=\"constraints\"><MechanicalObject name=\"points\" position=\"1 1.25 1  1 1.25 -1  0 0 0\"/><RigidMapping/></Node>"
          "</Node>"
          "<SlidingLagrangianConstraint object1=\"@slider/points\" object2=\"@cube/constraints/points\" sliding_point=\"0\" "
          "axis_1=\"0\" axis_2=\"1\"/>",
      "dt=\"0.001\" gravity=\"0 -9.81 0\"");
  const auto& system = scene.simulation.objects[0].system;
  const Vec3<double> slider(1, 1.25, -0.2);
  for (int n = 1; n <= 300; ++n) {
    scene.simulation.step();
    const RigidCoord<double> frame = system.rigids->coord(system.state.position, 0);
    const Vec3<double> a = frame.project_point({1, 1.25, 1}), b = frame.project_point({1, 1.25, -1});
    const Vec3<double> axis = (b - a).normalized();
    const Vec3<double> off = (slider - a) - axis * (slider - a).dot(axis);
    ASSERT_LT(off.norm(), 1e-6) << "step " << n;
  }
  // Hung by one point, the cube swings down: its centre leaves its start.
  EXPECT_GT(system.state.position[0].norm(), 1e-4);
}

TEST(SlidingLagrangianConstraintScene, BadInputIsRefusedNamingTheComponent) {
  const std::string bead = "<Node name=\"bead\"><EulerImplicitSolver/><SparseLDLSolver/><MechanicalObject name=\"point\" position=\"0 0 0\"/>"
                           "<UniformMass totalMass=\"1\"/><LinearSolverConstraintCorrection/></Node>";
  const std::string rail = "<Node name=\"rail\"><MechanicalObject name=\"ends\" position=\"0 0 0  4 0 0\"/></Node>";
  const std::string error = scene_error("<FreeMotionAnimationLoop/>" + rail + bead +
                                        "<SlidingLagrangianConstraint object1=\"@bead/point\" object2=\"@rail/ends\" axis_2=\"2\"/>");
  EXPECT_NE(error.find("SlidingLagrangianConstraint"), std::string::npos) << error;
  EXPECT_NE(error.find("axis_2 = 2 is out of range"), std::string::npos) << error;
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" + rail + bead +
                        "<SlidingLagrangianConstraint object1=\"@bead/point\" object2=\"@nowhere/ends\" axis_2=\"1\"/>"),
            "");
  const std::string both = scene_error("<FreeMotionAnimationLoop/>" + rail + bead +
                                       "<SlidingLagrangianConstraint object1=\"@rail/ends\" object2=\"@rail/ends\" axis_2=\"1\"/>");
  EXPECT_NE(both.find("both unsimulated"), std::string::npos) << both;
  const std::string rigid = scene_error(
      "<FreeMotionAnimationLoop/>" + bead +
      "<Node name=\"r\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject name=\"f\" template=\"Rigid3d\"/><UniformMass totalMass=\"1\"/>"
      "<UncoupledConstraintCorrection/></Node>"
      "<SlidingLagrangianConstraint template=\"Rigid3d\" object1=\"@r/f\" object2=\"@r/f\" axis_2=\"0\"/>");
  EXPECT_NE(rigid.find("SlidingLagrangianConstraint"), std::string::npos) << rigid;
  EXPECT_NE(rigid.find("Rigid3"), std::string::npos) << rigid;
  // (Stopper and Uniform, which SOFA defines on Vec1 states only: vec1_constraints_scene_test.cpp.)
}

// A rigid body of mass 2 (inertia 2 I) at `pose` with `extra` components, under its own solver.
std::string rigid_body(const std::string& name, const std::string& pose, const std::string& extra) {
  return "<Node name=\"" + name + "\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><CGLinearSolver iterations=\"100\" "
         "tolerance=\"1e-30\" threshold=\"1e-30\"/><MechanicalObject name=\"frame\" template=\"Rigid3d\" position=\"" + pose +
         "\"/><UniformMass totalMass=\"2\"/><UncoupledConstraintCorrection/>" + extra + "</Node>";
}

Eigen::Quaterniond quaternion_of(const RigidCoord<double>& c) { return c.orientation.normalized(); }

TEST(RigidLagrangianConstraintsScene, FixedHoldsARigidBodyAtItsRestPose) {
  // Gravity and a torque of (1, -2, 0.5) act; the body stays where it rests, turned as it rests.
  const std::string pose = "0.5 1 -0.25  0.1 0.2 -0.3 0.9273618495495703";
  LoadedScene scene = build_scene_text(
      kLoop + rigid_body("body", pose, "<ConstantForceField force=\"0 0 0 1 -2 0.5\"/><FixedLagrangianConstraint indices=\"0\"/>"),
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const auto& system = scene.simulation.objects[0].system;
  const RigidCoord<double> rest = system.rigids->coord(system.state.position, 0);
  for (int n = 1; n <= 200; ++n) {
    scene.simulation.step();
    const RigidCoord<double> now = system.rigids->coord(system.state.position, 0);
    ASSERT_LT((now.center - rest.center).norm(), 1e-10) << "step " << n;
    ASSERT_LT(quaternion_of(now).angularDistance(quaternion_of(rest)), 1e-7) << "step " << n;
  }
  EXPECT_EQ(scene.simulation.constraint_report().rows, 6);
  // Without the constraint the same body falls and turns.
  LoadedScene free = build_scene_text(kLoop + rigid_body("body", pose, "<ConstantForceField force=\"0 0 0 1 -2 0.5\"/>"),
                                      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  for (int n = 0; n < 20; ++n) free.simulation.step();
  const auto& f = free.simulation.objects[0].system;
  EXPECT_GT((f.rigids->coord(f.state.position, 0).center - rest.center).norm(), 0.01);
  EXPECT_GT(quaternion_of(f.rigids->coord(f.state.position, 0)).angularDistance(quaternion_of(rest)), 0.01);
}

TEST(RigidLagrangianConstraintsScene, BilateralKeepsTwoRigidFramesTogether) {
  // Body a is pushed and twisted, body b follows: with keepOrientationDifference the constraint
  // keeps b.c - a.c and a⁻¹ b at their initial values (SOFA's definition: the offset in the world frame).
  const std::string tie = "<BilateralLagrangianConstraint template=\"Rigid3d\" object1=\"@a/frame\" object2=\"@b/frame\" "
                          "first_point=\"0\" second_point=\"0\" keepOrientationDifference=\"1\"/>";
  LoadedScene scene = build_scene_text(
      kLoop + rigid_body("a", "0 0 0  0 0 0 1", "<ConstantForceField force=\"1 0 0 0 0 2\"/>") +
          rigid_body("b", "1 0.5 0  0 0 0.38268343236508978 0.92387953251128674", "") + tie,
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const auto& a = scene.simulation.objects[0].system;
  const auto& b = scene.simulation.objects[1].system;
  const RigidCoord<double> a0 = a.rigids->coord(a.state.position, 0), b0 = b.rigids->coord(b.state.position, 0);
  const Eigen::Quaterniond relative0 = quaternion_of(a0).conjugate() * quaternion_of(b0);
  for (int n = 1; n <= 100; ++n) {
    scene.simulation.step();
    const RigidCoord<double> an = a.rigids->coord(a.state.position, 0), bn = b.rigids->coord(b.state.position, 0);
    ASSERT_LT(((bn.center - an.center) - (b0.center - a0.center)).norm(), 1e-6) << "step " << n;
    ASSERT_LT((quaternion_of(an).conjugate() * quaternion_of(bn)).angularDistance(relative0), 1e-6) << "step " << n;
  }
  const RigidCoord<double> end = a.rigids->coord(a.state.position, 0);
  EXPECT_LT(end.center.y(), -1) << "both fall together";
  EXPECT_GT(quaternion_of(end).angularDistance(quaternion_of(a0)), 0.05) << "a turned, and b with it";
  EXPECT_EQ(scene.simulation.constraint_report().rows, 6);
}

TEST(RigidLagrangianConstraintsScene, BilateralRestVectorOffsetsTheFrames) {
  // Without keepOrientationDifference, b is held at a.c + (0, -1, 0) and a's orientation turned by
  // rest's angular part (here none): a fixed body, b hanging below it.
  LoadedScene scene = build_scene_text(
      kLoop + rigid_body("a", "0 0 0  0 0 0 1", "<FixedProjectiveConstraint indices=\"0\"/>") +
          rigid_body("b", "0 -1 0  0 0 0 1", "") +
          "<BilateralLagrangianConstraint object1=\"@a/frame\" object2=\"@b/frame\" first_point=\"0\" second_point=\"0\" "
          "rest_vector=\"0 -1 0 0 0 0\"/>",
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  const auto& b = scene.simulation.objects[1].system;
  for (int n = 1; n <= 100; ++n) {
    scene.simulation.step();
    const RigidCoord<double> bn = b.rigids->coord(b.state.position, 0);
    ASSERT_LT((bn.center - Vec3<double>(0, -1, 0)).norm(), 1e-10) << "step " << n;
    ASSERT_LT(quaternion_of(bn).angularDistance(Eigen::Quaterniond::Identity()), 1e-10) << "step " << n;
  }
}

TEST(RigidLagrangianConstraintsScene, DrawsTheHeldCentresWithTheForcesHoldingThem) {
  // A fixed body of mass 2 is held against its weight: the force at its centre is -m g. A body
  // hanging from a fixed one by a Rigid3 bilateral constraint: the pair joined, +m g on the hanging
  // body's centre, -m g on the other's.
  const Vec3<double> weight(0, -2 * 9.81, 0);
  LoadedScene fixed = build_scene_text(
      kLoop + rigid_body("body", "0.5 1 -0.25  0 0 0 1", "<ConstantForceField force=\"0 0 0 1 -2 0.5\"/><FixedLagrangianConstraint indices=\"0\"/>"),
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  for (int n = 0; n < 5; ++n) fixed.simulation.step();
  ConstraintDrawing held;
  fixed.simulation.constraints->draw(fixed.simulation.objects, fixed.simulation.dt, held);
  ASSERT_EQ(held.points.size(), 1u);
  EXPECT_LT((held.points[0].position - Vec3<double>(0.5, 1, -0.25)).norm(), 1e-9);
  EXPECT_LT((held.points[0].force + weight).norm(), 1e-6);
  LoadedScene hanging = build_scene_text(
      kLoop + rigid_body("a", "0 0 0  0 0 0 1", "<FixedProjectiveConstraint indices=\"0\"/>") + rigid_body("b", "0 -1 0  0 0 0 1", "") +
          "<BilateralLagrangianConstraint object1=\"@a/frame\" object2=\"@b/frame\" first_point=\"0\" second_point=\"0\" "
          "rest_vector=\"0 -1 0 0 0 0\"/>",
      "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  for (int n = 0; n < 5; ++n) hanging.simulation.step();
  ConstraintDrawing tied;
  hanging.simulation.constraints->draw(hanging.simulation.objects, hanging.simulation.dt, tied);
  ASSERT_EQ(tied.points.size(), 2u);
  ASSERT_EQ(tied.pairs.size(), 1u);
  EXPECT_LT((tied.points[1].force + weight).norm(), 1e-6) << "the hanging body is held up";
  EXPECT_LT((tied.points[0].force - weight).norm(), 1e-6);
}

TEST(RigidLagrangianConstraintsScene, BadRigidInputIsRefusedClearly) {
  const std::string body = rigid_body("a", "0 0 0  0 0 0 1", "");
  const std::string beadless = "<Node name=\"p\"><EulerImplicitSolver/><SparseLDLSolver/><MechanicalObject name=\"points\" position=\"0 0 0\"/>"
                               "<UniformMass totalMass=\"1\"/><LinearSolverConstraintCorrection/></Node>";
  const auto refused = [&](const std::string& scene, const std::string& expected) {
    const std::string error = scene_error("<FreeMotionAnimationLoop/>" + scene);
    EXPECT_NE(error.find(expected), std::string::npos) << error;
  };
  refused(rigid_body("a", "0 0 0  0 0 0 1", "<FixedLagrangianConstraint indices=\"1\"/>"), "indices[0] = 1 is out of range");
  refused(body + beadless + "<BilateralLagrangianConstraint object1=\"@a/frame\" object2=\"@p/points\" first_point=\"0\" second_point=\"0\"/>",
          "one is a Rigid3 state and the other not");
  refused(body + "<BilateralLagrangianConstraint object1=\"@a/frame\" object2=\"@a/frame\" first_point=\"0\" second_point=\"0\" "
                 "rest_vector=\"0 0 0\"/>",
          "a Rigid3 pair's is 6");
  refused(body + "<BilateralLagrangianConstraint object1=\"@a/frame\" object2=\"@missing/frame\" first_point=\"0\" second_point=\"0\"/>",
          "BilateralLagrangianConstraint");
  refused(rigid_body("a", "0 0 0  0 0 0 1", "<FixedLagrangianConstraint template=\"Vec3d\" indices=\"0\"/>"),
          "template=\"Vec3d\" but");
  refused(rigid_body("a", "0 0 0  0 0 0 1", "<FixedLagrangianConstraint template=\"Vec2d\" indices=\"0\"/>"),
          "only Vec3 and Rigid3");
}

}  // namespace
}  // namespace fastcorot
