// What the Lagrangian constraints show (ConstraintStage::draw, constraint_drawing.h): their points
// where the objects stand, and the force each applies there, checked against λ worked out by hand.
// One step from rest of a tetrahedron with point masses m, a direct solver and exact W = h A⁻¹
// (A the free motion's matrix): the free motion is x_f = x + h² A⁻¹ M g, so holding every point
// (δ + W λ = 0) needs λ = -h M g, whatever the stiffness: the force on each point is -m g. A
// bilateral tie of a free tetrahedron to a fixed one needs the same λ, +λ/h on the free (second)
// points and -λ/h on the fixed (first) ones.
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;

const char* kRoot = "dt=\"0.01\" gravity=\"0 -9.81 0\"";
const Vec3<double> kGravity(0, -9.81, 0);
const double kMass = 0.5;  // each point's (UniformMass vertexMass)

std::string tetrahedron(const std::string& name, const std::string& extra) {
  return "<Node name=\"" + name + "\"><EulerImplicitSolver/><SparseLDLSolver/>"
         "<MechanicalObject name=\"dofs\" position=\"0 0 0  1 0 0  0 1 0  0 0 1\"/>"
         "<TetrahedronSetTopologyContainer tetrahedra=\"0 1 2 3\"/><UniformMass vertexMass=\"0.5\"/>"
         "<TetrahedronFEMForceField youngModulus=\"1000\" poissonRatio=\"0.3\"/>" + extra + "</Node>";
}

const std::string kSolver = "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"100000\" tolerance=\"1e-14\"/>";

ConstraintDrawing drawing_of(const LoadedScene& scene) {
  ConstraintDrawing drawing;
  scene.simulation.constraints->draw(scene.simulation.objects, scene.simulation.dt, drawing);
  return drawing;
}

void expect_near(const Vec3<double>& actual, const Vec3<double>& expected, double tolerance, const std::string& what) {
  EXPECT_LT((actual - expected).norm(), tolerance) << what << ": (" << actual.transpose() << ") expected (" << expected.transpose()
                                                   << ")";
}

TEST(ConstraintDrawing, FixedLagrangianConstraintHoldsEachPointWithMinusItsWeight) {
  LoadedScene scene = build_scene_text(
      kSolver + tetrahedron("tet", "<FixedLagrangianConstraint indices=\"0 1 2 3\"/><LinearSolverConstraintCorrection/>"), kRoot);
  ASSERT_TRUE(scene.simulation.constraints);
  // Before any step: the points, no force yet.
  ConstraintDrawing drawing = drawing_of(scene);
  ASSERT_EQ(drawing.points.size(), 4u);
  for (const auto& p : drawing.points) EXPECT_EQ(p.force, Vec3<double>::Zero());

  scene.simulation.step();
  drawing = drawing_of(scene);
  ASSERT_EQ(drawing.constraints.size(), 1u);
  EXPECT_NE(drawing.constraints[0].find("FixedLagrangianConstraint"), std::string::npos) << drawing.constraints[0];
  ASSERT_EQ(drawing.points.size(), 4u);
  EXPECT_TRUE(drawing.pairs.empty());
  const double h = 0.01;
  const Vec3<double> lambda = -h * kMass * kGravity;  // by hand, each point's block
  const auto impulses = scene.simulation.constraints->constraint_forces();
  ASSERT_EQ(impulses.size(), 12u);
  const auto& x = scene.simulation.objects[0].system.state.position;
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& p = drawing.points[k];
    EXPECT_EQ(p.constraint, 0u);
    EXPECT_TRUE(p.active);
    EXPECT_EQ(p.position, x[k]) << "drawn where the point is now";
    expect_near(Vec3<double>(impulses[3 * k], impulses[3 * k + 1], impulses[3 * k + 2]), lambda, 1e-9, "λ of point " + std::to_string(k));
    expect_near(p.force, lambda / h, 1e-7, "force on point " + std::to_string(k));
  }
}

std::string tied(const std::string& activate) {
  return kSolver +
         tetrahedron("A", "<FixedProjectiveConstraint indices=\"0 1 2 3\"/><LinearSolverConstraintCorrection/>") +
         tetrahedron("B", "<LinearSolverConstraintCorrection/>") +
         "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"@B/dofs\" first_point=\"0 1 2 3\" second_point=\"0 1 2 3\" activate=\"" +
         activate + "\"/>";
}

TEST(ConstraintDrawing, BilateralPairsAreJoinedWithOpposingForces) {
  LoadedScene scene = build_scene_text(tied("true"), kRoot);
  scene.simulation.step();
  const ConstraintDrawing drawing = drawing_of(scene);
  ASSERT_EQ(drawing.points.size(), 8u);
  ASSERT_EQ(drawing.pairs.size(), 4u);
  const double h = 0.01;
  const Vec3<double> lambda = -h * kMass * kGravity;
  const auto& a = scene.simulation.objects[0].system.state.position;
  const auto& b = scene.simulation.objects[1].system.state.position;
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& first = drawing.points[drawing.pairs[k][0]];
    const auto& second = drawing.points[drawing.pairs[k][1]];
    EXPECT_EQ(first.position, a[k]);
    EXPECT_EQ(second.position, b[k]);
    EXPECT_TRUE(first.active && second.active);
    expect_near(second.force, lambda / h, 1e-7, "force on B's point " + std::to_string(k));
    expect_near(first.force, -lambda / h, 1e-7, "force on A's point " + std::to_string(k));
  }
}

TEST(ConstraintDrawing, AnInactiveBilateralConstraintShowsItsPointsWithoutForce) {
  LoadedScene scene = build_scene_text(tied("false"), kRoot);
  scene.simulation.step();
  const ConstraintDrawing drawing = drawing_of(scene);
  ASSERT_EQ(drawing.points.size(), 8u);
  EXPECT_EQ(drawing.pairs.size(), 4u);
  for (const auto& p : drawing.points) {
    EXPECT_FALSE(p.active);
    EXPECT_EQ(p.force, Vec3<double>::Zero());
  }
}

}  // namespace
}  // namespace fastcorot
