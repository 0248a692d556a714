// SoftRobots' CableConstraint through the scene builder, on a cantilever beam with a cable along its
// top: in displacement mode the cable shortens by the command (to the solver's tolerance, once the
// beam is at rest); in force mode λ is the command, and the displacement reached with the impulse
// the displacement mode found is the displacement it was given; bounds cap the impulse; the row is
// -∂L/∂x (against finite differences of the length); bad input is refused naming the attribute.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/softrobots/cable_constraint.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const char* kRoot = "dt=\"0.01\" gravity=\"0 -9.81 0\"";

// A beam of 6 × 2 × 2 points along x in [0, 1], its left end held; a cable of three points along
// its top, pulled from (-0.1, 0.18, 0.1) beyond the held end, with the CableConstraint's `cable`
// attributes.
std::string cable_scene(const std::string& cable, const std::string& indices = "0 1 2") {
  return "<FreeMotionAnimationLoop/><GenericConstraintSolver maxIterations=\"1000\" tolerance=\"1e-12\"/>"
         "<Node name=\"beam\"><EulerImplicitSolver rayleighMass=\"0.1\" rayleighStiffness=\"0.1\"/><SparseLDLSolver/>"
         "<RegularGridTopology name=\"grid\" n=\"6 2 2\" min=\"0 0 0\" max=\"1 0.2 0.2\"/><MechanicalObject name=\"dofs\"/>"
         "<TetrahedronFEMForceField youngModulus=\"5e4\" poissonRatio=\"0.3\"/><UniformMass totalMass=\"1\"/>"
         "<BoxROI name=\"box\" box=\"-0.01 -0.01 -0.01 0.01 0.21 0.21\"/><FixedProjectiveConstraint indices=\"@box.indices\"/>"
         "<LinearSolverConstraintCorrection/>"
         "<Node name=\"cable\"><MechanicalObject name=\"points\" position=\"0.1 0.18 0.1  0.5 0.18 0.1  0.95 0.18 0.1\"/>"
         "<CableConstraint name=\"cable\" indices=\"" + indices + "\" pullPoint=\"-0.1 0.18 0.1\" " + cable + "/>"
         "<BarycentricMapping/></Node></Node>";
}

std::string text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

const CableConstraint<double>& cable_of(const LoadedScene& scene) {
  const auto* loop = dynamic_cast<const FreeMotionAnimationLoop<double>*>(scene.simulation.constraints.get());
  EXPECT_NE(loop, nullptr);
  const auto* cable = dynamic_cast<const CableConstraint<double>*>(loop->constraints.at(0).get());
  EXPECT_NE(cable, nullptr);
  return *cable;
}

TEST(CableConstraint, DisplacementModeShortensTheCableByTheCommand) {
  LoadedScene scene = build_scene_text(cable_scene("valueType=\"displacement\" value=\"0.02\""), kRoot);
  const auto& cable = cable_of(scene);
  const double initial = cable.outputs().initial_length;
  EXPECT_NEAR(initial, 0.2 + 0.4 + 0.45, 1e-12);  // the rest positions' length
  const double tip_rest = scene.simulation.objects[0].system.state.position[5].y();
  for (int step = 0; step < 400; ++step) scene.simulation.step();
  // The beam at rest: the step's start positions, where the output is measured, are its end ones.
  EXPECT_NEAR(cable.outputs().displacement, 0.02, 1e-7);
  EXPECT_NEAR(cable.outputs().cable_length, initial - 0.02, 1e-7);
  EXPECT_GT(cable.outputs().force, 0);  // pulling
  EXPECT_GT(scene.simulation.objects[0].system.state.position[5].y(), tip_rest + 1e-3) << "the top shortens: the tip rises";
}

TEST(CableConstraint, ForceModeImposesTheImpulseAndReachesTheDisplacementThatNeedsIt) {
  LoadedScene by_displacement = build_scene_text(cable_scene("valueType=\"displacement\" value=\"0.02\""), kRoot);
  for (int step = 0; step < 400; ++step) by_displacement.simulation.step();
  const double impulse = cable_of(by_displacement).outputs().force;
  LoadedScene by_force = build_scene_text(cable_scene("valueType=\"force\" value=\"" + text(impulse) + "\""), kRoot);
  const auto& cable = cable_of(by_force);
  for (int step = 0; step < 400; ++step) {
    by_force.simulation.step();
    ASSERT_EQ(cable.outputs().force, impulse) << "step " << step;
  }
  EXPECT_NEAR(cable.outputs().displacement, 0.02, 2e-5);
}

TEST(CableConstraint, ForceBoundsCapTheImpulse) {
  LoadedScene free = build_scene_text(cable_scene("value=\"0.02\""), kRoot);
  for (int step = 0; step < 50; ++step) free.simulation.step();
  const double needed = cable_of(free).outputs().force;
  const double cap = 0.5 * needed;
  LoadedScene capped = build_scene_text(cable_scene("value=\"0.02\" maxForce=\"" + text(cap) + "\""), kRoot);
  for (int step = 0; step < 50; ++step) capped.simulation.step();
  EXPECT_EQ(cable_of(capped).outputs().force, cap);
  EXPECT_LT(cable_of(capped).outputs().displacement, 0.02 - 1e-4);
  // In force mode the command itself is capped.
  LoadedScene force = build_scene_text(cable_scene("valueType=\"force\" value=\"5\" maxForce=\"0.001\""), kRoot);
  force.simulation.step();
  EXPECT_EQ(cable_of(force).outputs().force, 0.001);
}

TEST(CableConstraint, TheRowIsMinusTheLengthsGradient) {
  // Straight from the class: points of an unmapped state, with and without a pull point.
  for (const bool pull : {true, false}) {
    ConstraintPoints<double> points;
    points.blocks = {0, 1, 2, 3};
    const std::vector<Vec3<double>> x = {{0.1, 0.3, 0}, {0.5, 0.2, 0.1}, {0.9, 0.35, -0.1}, {1.3, 0.1, 0.2}};
    points.rest_position = x;
    points.position = x;
    points.free_position = x;
    typename CableConstraint<double>::Parameters p;
    p.indices = {0, 1, 2, 3};
    p.has_pull_point = pull;
    p.pull_point = Vec3<double>(-0.2, 0.1, 0.3);
    CableConstraint<double> cable("test", points, x, p);
    ConstraintRows<double> rows(1);
    cable.build(rows);
    for (const auto& [i, c] : cable.row()) {
      for (int a = 0; a < 3; ++a) {
        std::vector<Vec3<double>> plus = x, minus = x;
        plus[i][a] += 1e-6;
        minus[i][a] -= 1e-6;
        const double derivative = (cable.length(plus) - cable.length(minus)) / 2e-6;
        EXPECT_NEAR(c[a], -derivative, 1e-8) << "pull " << pull << " point " << i << " axis " << a;
      }
    }
    EXPECT_EQ(cable.row().size(), 4u);
  }
}

TEST(CableConstraint, RefusesWhatItCannotSimulate) {
  EXPECT_NE(scene_error(cable_scene("method=\"geodesic\"")).find("only the point method"), std::string::npos);
  // An unknown valueType: SOFA's OptionsGroup keeps its default with a warning, and so it is here.
  const LoadedScene unknown = build_scene_text(cable_scene("valueType=\"position\""), kRoot);
  bool warned = false;
  for (const auto& line : unknown.warnings) warned = warned || line.find("valueType = \"position\" is not displacement or force") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_EQ(cable_of(unknown).parameters().value_type, CableConstraint<double>::ValueType::displacement);
  EXPECT_NE(scene_error(cable_scene("hasPullPoint=\"false\"", "1")).find("at least two indices"), std::string::npos);
  EXPECT_NE(scene_error(cable_scene("", "0 7")).find("indices[1] = 7 is out of range"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
