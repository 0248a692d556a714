// SoftRobots' UnilateralPlaneConstraint through the scene builder: a cantilever beam's tip, which
// sags under gravity, is kept above the plane of three held points (y = 0): it stops on
// the plane instead; the row is SoftRobots' (the normal as it is on the point, -n/3 on the plane's);
// bad input is refused.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/softrobots/unilateral_plane_constraint.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

// A beam of 6 × 2 × 2 points along x in [0, 5] (x fastest: point i + 6 (j + 2 k)), its left end
// held up to x = 1 (so that the plane's three points below stay put), with `constraint`; point 5
// is its bottom tip (5, 0, 0). Unit cells: the plane's normal below has length 1, where
// SoftRobots' unnormalised row and normalised gap agree (with |n| = 0.04 the same beam, corrected
// 25 times over at each crossing, is thrown up: what SoftRobots' formula implies).
std::string beam(const std::string& constraint) {
  return "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"1000\" tolerance=\"1e-12\"/>"
         "<Node name=\"beam\"><EulerImplicitSolver rayleighMass=\"0.1\" rayleighStiffness=\"0.1\"/><SparseLDLSolver/>"
         "<RegularGridTopology n=\"6 2 2\" min=\"0 0 0\" max=\"5 1 1\"/><MechanicalObject/>"
         "<TetrahedronFEMForceField youngModulus=\"5e3\" poissonRatio=\"0.3\"/><UniformMass totalMass=\"1\"/>"
         "<BoxROI name=\"box\" box=\"-0.01 -0.01 -0.01 1.01 1.01 1.01\"/><FixedProjectiveConstraint indices=\"@box.indices\"/>"
         "<LinearSolverConstraintCorrection/>" + constraint + "</Node>";
}

double tip_height(const std::string& constraint) {
  LoadedScene scene = build_scene_text(beam(constraint), "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  double lowest = 1;
  for (int step = 0; step < 200; ++step) {
    scene.simulation.step();
    lowest = std::min(lowest, scene.simulation.objects[0].system.state.position[5].y());
  }
  return lowest;
}

TEST(UnilateralPlaneConstraint, KeepsAPointAboveAPlane) {
  // Points 0 (0, 0, 0), 12 (0, 0, 1) and 1 (1, 0, 0): the plane y = 0 at the held end; with this
  // order n = (p2 - p1) × (p3 - p1) = (0, 0, 1) × (1, 0, 0) = (0, 1, 0) points up.
  EXPECT_LT(tip_height(""), -1e-2) << "the free beam sags";
  EXPECT_GT(tip_height("<UnilateralPlaneConstraint indices=\"5 0 12 1\"/>"), -1e-4);
  // flipNormal keeps it below: no force while it sags.
  EXPECT_NEAR(tip_height("<UnilateralPlaneConstraint indices=\"5 0 12 1\" flipNormal=\"true\"/>"), tip_height(""), 1e-12);
}

TEST(UnilateralPlaneConstraint, TheRowIsTheNormalOnThePointAndAThirdOfItAgainstThePlane) {
  ConstraintPoints<double> points;
  points.blocks = {0, 1, 2, 3};
  points.position = points.free_position = points.rest_position = {{0.3, 2, 0.1}, {0, 0, 0}, {0, 0, 2}, {2, 0, 0}};
  UnilateralPlaneConstraint<double> plane("test", points, {{0, 1, 2, 3}, false});
  ConstraintRows<double> rows(1);
  plane.build(rows);
  EXPECT_EQ(plane.normal(), Vec3<double>(0, 4, 0));  // |n| = 4: not normalised, as SoftRobots
  double dfree = 0;
  plane.violation(ConstraintOrder::position_and_velocity, 0.01, &dfree);
  EXPECT_DOUBLE_EQ(dfree, 2.0);  // the gap along the unit normal
}

TEST(UnilateralPlaneConstraint, RefusesWhatItCannotSimulate) {
  EXPECT_NE(scene_error(beam("<UnilateralPlaneConstraint indices=\"5 0 12\"/>")).find("four are needed"), std::string::npos);
  EXPECT_NE(scene_error(beam("<UnilateralPlaneConstraint indices=\"5 0 12 99\"/>")).find("indices[3] = 99 is out of range"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
