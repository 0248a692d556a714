// SoftRobots' SurfacePressureConstraint through the scene builder, on a block held at its base with
// a closed cubic cavity inside it (a mapped surface): in volumeGrowth mode the cavity grows by the
// command once at rest; in pressure mode λ is the command, and the pressure the volumeGrowth mode
// found gives the same growth; the row is ∂V/∂x (against finite differences of the volume), quads
// give the volume of their two triangles; bad input is refused naming what is wrong.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/softrobots/surface_pressure_constraint.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const char* kRoot = "dt=\"0.01\" gravity=\"0 0 0\"";

// The cube [0.3, 0.7]³: its corners and its twelve triangles, normals facing out.
const char* kCorners = "0.3 0.3 0.3  0.7 0.3 0.3  0.7 0.7 0.3  0.3 0.7 0.3  0.3 0.3 0.7  0.7 0.3 0.7  0.7 0.7 0.7  0.3 0.7 0.7";
const char* kTriangles = "0 2 1  0 3 2  4 5 6  4 6 7  0 1 5  0 5 4  3 7 6  3 6 2  0 4 7  0 7 3  1 2 6  1 6 5";

std::string text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

// A block [0, 1]³ of 5 × 5 × 5 points held at y = 0, with the cavity's SurfacePressureConstraint
// given `cavity` attributes (and the cube's triangles unless `own_triangles` is false).
std::string cavity_scene(const std::string& cavity, bool own_triangles = true) {
  return "<FreeMotionAnimationLoop/><GenericConstraintSolver maxIterations=\"1000\" tolerance=\"1e-14\"/>"
         "<Node name=\"block\"><EulerImplicitSolver rayleighMass=\"0.1\" rayleighStiffness=\"0.1\"/><SparseLDLSolver/>"
         "<RegularGridTopology n=\"5 5 5\" min=\"0 0 0\" max=\"1 1 1\"/><MechanicalObject/>"
         "<TetrahedronFEMForceField youngModulus=\"1e3\" poissonRatio=\"0.3\"/><UniformMass totalMass=\"1\"/>"
         "<BoxROI name=\"base\" box=\"-0.01 -0.01 -0.01 1.01 0.01 1.01\"/><FixedProjectiveConstraint indices=\"@base.indices\"/>"
         "<LinearSolverConstraintCorrection/>"
         "<Node name=\"cavity\"><MeshTopology name=\"surface\" position=\"" + std::string(kCorners) + "\" triangles=\"" + kTriangles +
         "\"/><MechanicalObject position=\"" + kCorners + "\"/><SurfacePressureConstraint name=\"pressure\" " +
         (own_triangles ? std::string("triangles=\"") + kTriangles + "\" " : std::string()) + cavity +
         "/><BarycentricMapping/></Node></Node>";
}

const SurfacePressureConstraint<double>& cavity_of(const LoadedScene& scene) {
  const auto* loop = dynamic_cast<const FreeMotionAnimationLoop<double>*>(scene.simulation.constraints.get());
  EXPECT_NE(loop, nullptr);
  const auto* cavity = dynamic_cast<const SurfacePressureConstraint<double>*>(loop->constraints.at(0).get());
  EXPECT_NE(cavity, nullptr);
  return *cavity;
}

TEST(SurfacePressureConstraint, VolumeGrowthModeGrowsTheCavityByTheCommand) {
  LoadedScene scene = build_scene_text(cavity_scene("valueType=\"volumeGrowth\" value=\"0.002\""), kRoot);
  const auto& cavity = cavity_of(scene);
  EXPECT_NEAR(cavity.outputs().initial_volume, 0.064, 1e-15);
  for (int step = 0; step < 300; ++step) scene.simulation.step();
  EXPECT_NEAR(cavity.outputs().volume_growth, 0.002, 1e-9);
  EXPECT_NEAR(cavity.outputs().volume, 0.066, 1e-9);
  EXPECT_GT(cavity.outputs().pressure, 0);  // inflating
}

TEST(SurfacePressureConstraint, PressureModeImposesTheImpulseAndReachesTheGrowthThatNeedsIt) {
  LoadedScene by_growth = build_scene_text(cavity_scene("valueType=\"volumeGrowth\" value=\"0.002\""), kRoot);
  for (int step = 0; step < 300; ++step) by_growth.simulation.step();
  const double impulse = cavity_of(by_growth).outputs().pressure;
  // The default valueType is pressure; SoftRobots' own topology: the node's triangles.
  LoadedScene by_pressure = build_scene_text(cavity_scene("value=\"" + text(impulse) + "\"", false), kRoot);
  const auto& cavity = cavity_of(by_pressure);
  for (int step = 0; step < 300; ++step) {
    by_pressure.simulation.step();
    ASSERT_EQ(cavity.outputs().pressure, impulse) << "step " << step;
  }
  EXPECT_NEAR(cavity.outputs().volume_growth, 0.002, 1e-8);
  // maxVolumeGrowth stops it short.
  LoadedScene capped = build_scene_text(cavity_scene("value=\"" + text(impulse) + "\" maxVolumeGrowth=\"0.001\""), kRoot);
  for (int step = 0; step < 300; ++step) capped.simulation.step();
  EXPECT_NEAR(cavity_of(capped).outputs().volume_growth, 0.001, 1e-8);
}

TEST(SurfacePressureConstraint, TheRowIsTheVolumesGradientAndQuadsAreTwoTriangles) {
  const std::vector<Vec3<double>> x = {{0.3, 0.3, 0.3}, {0.72, 0.31, 0.29}, {0.7, 0.69, 0.3}, {0.3, 0.7, 0.33},
                                       {0.31, 0.3, 0.7}, {0.7, 0.28, 0.71}, {0.69, 0.7, 0.7}, {0.3, 0.71, 0.7}};
  ConstraintPoints<double> points;
  points.blocks = {0, 1, 2, 3, 4, 5, 6, 7};
  points.rest_position = points.position = points.free_position = x;
  typename SurfacePressureConstraint<double>::Parameters p;
  p.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                 {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  SurfacePressureConstraint<double> cavity("test", points, x, p);
  ConstraintRows<double> rows(1);
  cavity.build(rows);
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      std::vector<Vec3<double>> plus = x, minus = x;
      plus[i][a] += 1e-6;
      minus[i][a] -= 1e-6;
      EXPECT_NEAR(cavity.row()[i][a], (cavity.volume(plus) - cavity.volume(minus)) / 2e-6, 1e-8) << i << " " << a;
    }
  }
  // The same cube as six quads split along the diagonals the triangles use.
  typename SurfacePressureConstraint<double>::Parameters q;
  q.quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  SurfacePressureConstraint<double> quads("test", points, x, q);
  EXPECT_NEAR(quads.volume(x), cavity.volume(x), 1e-15);
}

TEST(SurfacePressureConstraint, RefusesWhatItCannotSimulate) {
  const LoadedScene unknown = build_scene_text(cavity_scene("valueType=\"force\" value=\"0.001\""), kRoot);
  EXPECT_EQ(cavity_of(unknown).parameters().value_type, SurfacePressureConstraint<double>::ValueType::pressure);  // SOFA's default, warned
  EXPECT_NE(scene_error(cavity_scene("triangles=\"0 1 9\"", false)).find("triangles[0] has point 9, out of range"), std::string::npos);
  EXPECT_NE(scene_error(cavity_scene("triangles=\"0 1\"", false)).find("triangles needs 3 indices each"), std::string::npos);
}

}  // namespace
}  // namespace fastcorot
