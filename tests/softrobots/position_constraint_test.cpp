// SoftRobots' PositionConstraint through the scene builder: a beam held at its left end whose tip
// points are moved up along y by the command (displacement mode) reach it at rest; the impulse
// found there, commanded in force mode, is imposed each step and reaches the same; force bounds
// cap a force command, and displacement mode ignores them as SoftRobots does; the row is the
// weighted direction on each point; bad input is refused.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/softrobots/position_constraint.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const char* kRoot = "dt=\"0.01\" gravity=\"0 -9.81 0\"";

// A beam of 6 × 2 × 2 points along x in [0, 1] (point i + 6 (j + 2 k)), its left end held; the
// PositionConstraint's `attributes` on `indices` (by default its right end's four points).
std::string beam(const std::string& attributes, const std::string& indices = "5 11 17 23") {
  return "<FreeMotionAnimationLoop/><GenericConstraintSolver maxIterations=\"1000\" tolerance=\"1e-12\"/>"
         "<Node name=\"beam\"><EulerImplicitSolver rayleighMass=\"0.1\" rayleighStiffness=\"0.1\"/><SparseLDLSolver/>"
         "<RegularGridTopology name=\"grid\" n=\"6 2 2\" min=\"0 0 0\" max=\"1 0.2 0.2\"/><MechanicalObject name=\"dofs\"/>"
         "<TetrahedronFEMForceField youngModulus=\"5e4\" poissonRatio=\"0.3\"/><UniformMass totalMass=\"1\"/>"
         "<BoxROI name=\"box\" box=\"-0.01 -0.01 -0.01 0.01 0.21 0.21\"/><FixedProjectiveConstraint indices=\"@box.indices\"/>"
         "<GenericConstraintCorrection/><PositionConstraint name=\"lift\" indices=\"" + indices + "\" " + attributes + "/></Node>";
}

std::string text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

const PositionConstraint<double>& position_of(const LoadedScene& scene) {
  const auto* loop = dynamic_cast<const FreeMotionAnimationLoop<double>*>(scene.simulation.constraints.get());
  EXPECT_NE(loop, nullptr);
  const auto* constraint = dynamic_cast<const PositionConstraint<double>*>(loop->constraints.at(0).get());
  EXPECT_NE(constraint, nullptr);
  return *constraint;
}

TEST(PositionConstraint, DisplacementModeMovesThePointsByTheCommand) {
  LoadedScene scene = build_scene_text(beam("useDirections=\"0 1 0\" value=\"0.05\""), kRoot);
  const auto& x = scene.simulation.objects[0].system.state.position;
  const std::vector<Vec3<double>> start = x;
  for (int step = 0; step < 400; ++step) scene.simulation.step();
  for (const std::size_t i : {5, 11, 17, 23}) {
    EXPECT_NEAR(x[i].y() - start[i].y(), 0.05, 1e-7) << "point " << i;
    EXPECT_GT(std::abs(x[i].x() - start[i].x()) + std::abs(x[i].z() - start[i].z()), 0.0) << "free in x and z";
  }
  EXPECT_GT(position_of(scene).force(), 0);  // lifting against gravity and the beam
  // maxPositiveDisp limits the command.
  LoadedScene limited = build_scene_text(beam("useDirections=\"0 1 0\" value=\"0.05\" maxPositiveDisp=\"0.02\""), kRoot);
  for (int step = 0; step < 400; ++step) limited.simulation.step();
  EXPECT_NEAR(limited.simulation.objects[0].system.state.position[5].y() - start[5].y(), 0.02, 1e-7);
}

TEST(PositionConstraint, ForceModeImposesTheImpulseAndReachesTheDisplacementThatNeedsIt) {
  // One point (the top far corner, 23): one row, whose impulse at rest is the one that holds it.
  LoadedScene by_displacement = build_scene_text(beam("useDirections=\"0 1 0\" value=\"0.05\"", "23"), kRoot);
  const double y0 = by_displacement.simulation.objects[0].system.state.position[23].y();
  for (int step = 0; step < 400; ++step) by_displacement.simulation.step();
  const double impulse = position_of(by_displacement).force();
  LoadedScene by_force = build_scene_text(beam("useDirections=\"0 1 0\" valueType=\"force\" value=\"" + text(impulse) + "\"", "23"), kRoot);
  const auto& x = by_force.simulation.objects[0].system.state.position;
  for (int step = 0; step < 400; ++step) {
    by_force.simulation.step();
    ASSERT_EQ(position_of(by_force).force(), impulse) << "step " << step;
  }
  EXPECT_NEAR(x[23].y() - y0, 0.05, 2e-5);
  // minForce/maxForce cap a force command; in displacement mode SoftRobots drops them.
  LoadedScene capped = build_scene_text(beam("useDirections=\"0 1 0\" valueType=\"force\" value=\"5\" maxForce=\"0.001\""), kRoot);
  capped.simulation.step();
  EXPECT_EQ(position_of(capped).force(), 0.001);
  LoadedScene ignored = build_scene_text(beam("useDirections=\"0 1 0\" value=\"0.05\" maxForce=\"1e-9\""), kRoot);
  for (int step = 0; step < 5; ++step) ignored.simulation.step();
  EXPECT_GT(position_of(ignored).force(), 1e-6);
}

TEST(PositionConstraint, TheRowIsTheWeightedDirectionOnEachPoint) {
  ConstraintPoints<double> points;
  points.blocks = {0, 1};
  points.position = points.free_position = points.rest_position = {{0, 0, 0}, {1, 1, 1}};
  points.free_position[1] = {1.5, 1, 1};
  const std::vector<Vec3<double>> initial = {{0, 0, 0}, {0.5, 1, 1}};
  typename PositionConstraint<double>::Parameters p;
  p.indices = {1};
  p.directions[0] = {2, 0, 0};  // normalised to (1, 0, 0)
  p.use_directions = {true, false, false};
  p.weight = {3, 1, 1};
  PositionConstraint<double> constraint("test", points, initial, p);
  ConstraintRows<double> rows(2);
  constraint.build(rows);
  EXPECT_EQ(constraint.rows(), 1);
  double dfree = 0;
  constraint.violation(ConstraintOrder::position_and_velocity, 0.01, &dfree);
  EXPECT_DOUBLE_EQ(dfree, 3 * 0.5 + 3 * 0.5);  // J (x_free - x) + w u · (x - x0)
}

TEST(PositionConstraint, RefusesWhatItCannotSimulate) {
  EXPECT_NE(scene_error(beam("value=\"0.05\"")).find("useDirections keeps more than one direction"), std::string::npos);
  EXPECT_NE(scene_error(beam("useDirections=\"0 0 0\"")).find("useDirections keeps no direction"), std::string::npos);
  EXPECT_NE(scene_error(beam("useDirections=\"0 1 0\"", "99")).find("indices: 99 is out of range"), std::string::npos);
  EXPECT_NE(scene_error(beam("useDirections=\"0 1\"")).find("useDirections: 2 values given"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
