// Scenes with SOFA's spring components through the real parser and builder: SpringForceField
// between two objects of one solver (the same springs as on one object holding both), its alias
// StiffSpringForceField, RegularGridSpringForceField on a grid, RestShapeSpringsForceField at
// equilibrium (x = p0 + F / k, Hooke's law), HexahedronFEMForceFieldAndMass's mass, and the errors
// that name the component and the attribute.
#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/spring_force_field.h"

#include "support/scene_text.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace fastcorot {
namespace {

std::vector<Vec3<double>> run(const std::string& body, int steps) {
  LoadedScene scene = testing::build_scene_text(body, "dt=\"0.01\" gravity=\"0 -9.81 0\"");
  for (int s = 0; s < steps; ++s) scene.simulation.step();
  return scene.simulation.objects.at(0).system.state.position;
}

TEST(SpringScenes, SpringsBetweenTwoObjectsAreThoseOfOneObjectHoldingBoth) {
  const std::string solver = "<EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/><EigenSimplicialLDLT/>";
  const std::string pair =
      solver +
      "<Node name=\"A\"><MechanicalObject name=\"dofs\" position=\"0 0 0  1 0 0\"/><UniformMass vertexMass=\"0.5\"/>"
      "<FixedProjectiveConstraint indices=\"0\"/><SpringForceField spring=\"0 1 40 1 1\"/></Node>"
      "<Node name=\"B\"><MechanicalObject name=\"dofs\" position=\"2 0 0  3 0.5 0\"/><UniformMass vertexMass=\"0.5\"/></Node>"
      "<SpringForceField object1=\"@A/dofs\" object2=\"@B/dofs\" spring=\"1 0 50 2 1  0 1 30 0 2.5\"/>"
      "<StiffSpringForceField object1=\"@B/dofs\" object2=\"@B/dofs\" indices1=\"0\" indices2=\"1\" stiffness=\"20\" damping=\"1\" lengths=\"1\"/>";
  const std::string single =
      solver +
      "<Node name=\"AB\"><MechanicalObject position=\"0 0 0  1 0 0  2 0 0  3 0.5 0\"/><UniformMass vertexMass=\"0.5\"/>"
      "<FixedProjectiveConstraint indices=\"0\"/><SpringForceField spring=\"0 1 40 1 1  1 2 50 2 1  0 3 30 0 2.5  2 3 20 1 1\"/></Node>";
  const auto merged = run(pair, 30), one = run(single, 30);
  ASSERT_EQ(merged.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((merged[i] - one[i]).norm(), 1e-12) << i;
  EXPECT_GT((one[3] - Vec3<double>(3, 0.5, 0)).norm(), 1e-3);  // it moved
}

TEST(SpringScenes, AMasslessFixedAnchorHoldsAHangingPoint) {
  // As SOFA's StiffSpringForceField_simple.scn: the anchor object has no mass, all its points fixed.
  // Hooke's law along the vertical spring: y = -1 - m g / k = -1 - 10 / 50 (the ball kept on the
  // vertical: a spring at rest has no stiffness across it).
  LoadedScene scene = testing::build_scene_text(
      "<StaticSolver/><EigenSimplicialLDLT/>"
      "<Node name=\"fix\"><MechanicalObject name=\"dofs\" position=\"0 0 0\"/><FixedProjectiveConstraint indices=\"0\"/></Node>"
      "<Node name=\"ball\"><MechanicalObject name=\"dofs\" position=\"0 -1 0\"/><UniformMass totalMass=\"1\"/>"
      "<PartialFixedProjectiveConstraint indices=\"0\" fixedDirections=\"1 0 1\"/></Node>"
      "<SpringForceField object1=\"@fix/dofs\" object2=\"@ball/dofs\" spring=\"0 0 50 1 1\"/>",
      "gravity=\"0 -10 0\"");
  scene.simulation.step();
  const auto& x = scene.simulation.objects[0].system.state.position;
  EXPECT_LT((x[1] - Vec3<double>(0, -1.2, 0)).norm(), 1e-10);
  EXPECT_EQ(x[0].norm(), 0);
}

TEST(SpringScenes, RestShapeSpringsHoldAConstantForceAtFOverK) {
  // Static solve of f = F - k (x - p0) = 0: x = p0 + F / k (per point stiffness, one axis off).
  LoadedScene scene = testing::build_scene_text(
      "<Node name=\"N\"><StaticSolver/><EigenSimplicialLDLT/>"
      "<MechanicalObject position=\"0 0 0  1 0 0\"/><UniformMass vertexMass=\"1\"/>"
      "<ConstantForceField force=\"3 6 -1.5\"/>"
      "<RestShapeSpringsForceField stiffness=\"12 3\" activeDirections=\"1 1 1\"/></Node>",
      "gravity=\"0 0 0\"");
  scene.simulation.step();
  const auto& x = scene.simulation.objects[0].system.state.position;
  EXPECT_LT((x[0] - Vec3<double>(0.25, 0.5, -0.125)).norm(), 1e-10);
  EXPECT_LT((x[1] - Vec3<double>(2, 2, -0.5)).norm(), 1e-10);
}

TEST(SpringScenes, RestShapeSpringsToAStateThatDoesNotMove) {
  LoadedScene scene = testing::build_scene_text(
      "<Node name=\"Anchor\"><MechanicalObject name=\"ms\" position=\"5 5 5  7 7 7\"/></Node>"
      "<Node name=\"N\"><StaticSolver/><EigenSimplicialLDLT/>"
      "<MechanicalObject position=\"0 0 0  1 0 0\"/><UniformMass vertexMass=\"1\"/><FixedProjectiveConstraint indices=\"0\"/>"
      "<RestShapeSpringsForceField stiffness=\"10\" points=\"1\" external_rest_shape=\"@../Anchor/ms\" external_points=\"1\"/></Node>",
      "gravity=\"0 0 0\"");
  scene.simulation.step();
  const auto& x = scene.simulation.objects[0].system.state.position;
  EXPECT_LT((x[1] - Vec3<double>(7, 7, 7)).norm(), 1e-10);
  EXPECT_EQ(x[0].norm(), 0);
}

TEST(SpringScenes, RegularGridSpringsAreTheGridsAndAssembleOnlyTheListedOnes) {
  LoadedScene scene = testing::build_scene_text(
      "<Node name=\"N\"><EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-12\" threshold=\"1e-12\"/>"
      "<MechanicalObject/><UniformMass totalMass=\"1\"/>"
      "<RegularGridTopology n=\"3 2 2\" min=\"0 0 0\" max=\"4 1 0.5\"/>"
      "<RegularGridSpringForceField stiffness=\"200\" damping=\"2\" linesStiffness=\"50\"/></Node>");
  auto& system = scene.simulation.objects[0].system;
  ASSERT_EQ(system.force_fields.size(), 1u);
  const auto* springs = dynamic_cast<const SpringForceField<double>*>(system.force_fields[0].get());
  ASSERT_NE(springs, nullptr);
  ASSERT_EQ(springs->springs().size(), 50u);  // 20 lines, 22 face diagonals, 8 cell diagonals
  EXPECT_DOUBLE_EQ(springs->springs()[0].stiffness, 25);                  // linesStiffness 50 over dx = 2
  EXPECT_DOUBLE_EQ(springs->springs()[0].damping, 1);                     // damping 2 over 2
  EXPECT_DOUBLE_EQ(springs->springs()[49].stiffness * springs->springs()[49].rest_length, 200);
  std::vector<Vec3<double>> f(12, Vec3<double>::Zero());
  system.force_fields[0]->add_force(system.state.position, f);
  EXPECT_EQ(Eigen::MatrixXd(system.force_fields[0]->stiffness_matrix()).norm(), 0);  // no listed spring
  for (int s = 0; s < 10; ++s) scene.simulation.step();
  for (const auto& p : system.state.position) EXPECT_TRUE(p.allFinite());
}

TEST(SpringScenes, HexahedronFEMForceFieldAndMassIsTheObjectsMass) {
  LoadedScene scene = testing::build_scene_text(
      "<Node name=\"M1\"><EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/>"
      "<CGLinearSolver iterations=\"25\" tolerance=\"1e-9\" threshold=\"1e-9\"/><MechanicalObject/>"
      "<RegularGridTopology nx=\"3\" ny=\"2\" nz=\"2\" xmin=\"0\" xmax=\"4\" ymin=\"0\" ymax=\"1\" zmin=\"0\" zmax=\"0.5\"/>"
      "<FixedProjectiveConstraint indices=\"0 3 6 9\"/>"
      "<HexahedronFEMForceFieldAndMass youngModulus=\"4000\" poissonRatio=\"0.3\" method=\"large\" density=\"2\"/></Node>");
  auto& system = scene.simulation.objects[0].system;
  ASSERT_EQ(system.force_fields.size(), 1u);
  ASSERT_FALSE(system.mass.is_lumped());
  // Two cells of volume 1: 64 entries of rho V 8/27 each; weight rho V / 8 per corner.
  EXPECT_NEAR(system.mass.total_mass(), 2 * 64 * 2 * 8.0 / 27, 1e-12);
  double weight = 0;
  for (double m : system.mass.gravity_masses()) weight += m;
  EXPECT_NEAR(weight, 2 * 2.0, 1e-13);
  for (int s = 0; s < 20; ++s) scene.simulation.step();
  EXPECT_LT(system.state.position[11].y(), 1.0);
  EXPECT_TRUE(system.state.position[11].allFinite());
  EXPECT_NE(testing::scene_error("<Node name=\"M\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject/>"
                                 "<RegularGridTopology n=\"2 2 2\"/><UniformMass vertexMass=\"1\"/>"
                                 "<HexahedronFEMForceFieldAndMass density=\"1\"/></Node>")
                .find("a second mass"),
            std::string::npos);
  EXPECT_NE(testing::scene_error("<Node name=\"M\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject/>"
                                 "<RegularGridTopology n=\"2 2 2\"/><HexahedronFEMForceFieldAndMass density=\"-1\"/></Node>")
                .find("density"),
            std::string::npos);
}

TEST(SpringScenes, BadSpringsAreNamedWithTheirAttribute) {
  const std::string two = "<Node name=\"A\"><MechanicalObject name=\"dofs\" position=\"0 0 0  1 0 0\"/><UniformMass vertexMass=\"1\"/></Node>"
                          "<Node name=\"B\"><MechanicalObject name=\"dofs\" position=\"2 0 0\"/><UniformMass vertexMass=\"1\"/></Node>";
  const std::string solver = "<EulerImplicitSolver/><CGLinearSolver/>";
  const auto error = [&](const std::string& body) { return testing::scene_error(body); };
  const auto has = [](const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; };
  std::string e = error(solver + two + "<SpringForceField object1=\"@A/dofs\" object2=\"@B/dofs\" spring=\"0 1 10 0 1\"/>");
  EXPECT_TRUE(has(e, "SpringForceField") && has(e, "spring: spring 0 index 1 out of range [0, 1) of object2")) << e;
  e = error(solver + two + "<SpringForceField object1=\"@A/dofs\" object2=\"@B/dofs\" spring=\"0 0 -10 0 1\"/>");
  EXPECT_TRUE(has(e, "SpringForceField") && has(e, "stiffness -10")) << e;
  e = error(solver + two + "<SpringForceField object1=\"@A/dofs\" spring=\"0 0 10 0 1\"/>");
  EXPECT_TRUE(has(e, "SpringForceField") && has(e, "object2 is not given")) << e;
  e = error(solver + two + "<SpringForceField object1=\"@A/dofs\" object2=\"@B/dofs\" indices1=\"0 1\" indices2=\"0\"/>");
  EXPECT_TRUE(has(e, "indices1 has 2 points, indices2 1")) << e;
  // Objects of two solvers.
  e = error("<Node name=\"A\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject name=\"dofs\" position=\"0 0 0\"/>"
            "<UniformMass vertexMass=\"1\"/></Node><Node name=\"B\"><EulerImplicitSolver/><CGLinearSolver/>"
            "<MechanicalObject name=\"dofs\" position=\"1 0 0\"/><UniformMass vertexMass=\"1\"/></Node>"
            "<SpringForceField object1=\"@A/dofs\" object2=\"@B/dofs\" spring=\"0 0 10 0 1\"/>");
  EXPECT_TRUE(has(e, "SpringForceField") && has(e, "different solvers")) << e;
  e = error("<Node name=\"N\">" + solver + "<MechanicalObject position=\"0 0 0\"/><UniformMass vertexMass=\"1\"/>"
            "<RestShapeSpringsForceField points=\"3\"/></Node>");
  EXPECT_TRUE(has(e, "RestShapeSpringsForceField") && has(e, "points: index 3 out of range")) << e;
  e = error("<Node name=\"N\">" + solver + "<MechanicalObject position=\"0 0 0\"/><UniformMass vertexMass=\"1\"/>"
            "<RestShapeSpringsForceField stiffness=\"-2\"/></Node>");
  EXPECT_TRUE(has(e, "RestShapeSpringsForceField") && has(e, "stiffness = -2")) << e;
  e = error("<Node name=\"N\">" + solver + "<MechanicalObject position=\"0 0 0\"/><UniformMass vertexMass=\"1\"/>"
            "<SpringForceField fileSprings=\"a.xs3\"/></Node>");
  EXPECT_TRUE(has(e, "fileSprings")) << e;
}

}  // namespace
}  // namespace fastcorot
