// Mechanics in mapped nodes, through the scene builder: springs and masses written on a mapped state
// (IdentityMapping, SubsetMapping, BarycentricMapping) act on the simulated object as the same
// springs and masses written on its own points; chains fold; 1 and 2 threads give the same bits;
// what cannot be carried is refused in one line.
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

// A 4 × 2 × 2 grid fixed at x = 0, under its own weight; `own` goes in the object's node, `child`
// is the body of a child node.
std::string grid(const std::string& own, const std::string& child = "") {
  return "<Node name=\"beam\">"
         "<EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/><SparseLDLSolver/>"
         "<RegularGridTopology name=\"grid\" n=\"4 2 2\" min=\"0 0 0\" max=\"3 1 1\"/>"
         "<MechanicalObject name=\"dofs\"/>"
         "<FixedProjectiveConstraint indices=\"0 4 8 12\"/>" +
         own + (child.empty() ? "" : "<Node name=\"mapped\">" + child + "</Node>") + "</Node>";
}

const std::string kSprings =
    "<SpringForceField spring=\"0 1 800 2 1  1 2 700 1 1  2 3 600 0 1  5 6 900 3 1  1 5 500 0 1.2  "
    "6 10 400 0 1  10 11 300 1 1  3 7 800 0 1  7 15 700 0 1.4  2 14 650 0 1.5\"/>";

std::vector<Vec3<double>> run(LoadedScene scene, int steps, int threads = 1) {
  scene.simulation.threads = threads;
  for (int s = 0; s < steps; ++s) scene.simulation.step();
  return scene.simulation.objects.at(0).system.state.position;
}

double largest_difference(const std::vector<Vec3<double>>& a, const std::vector<Vec3<double>>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

TEST(MappedMechanicsScene, SpringsOnAnIdentityMappedStateAreTheSpringsOnTheObject) {
  const auto direct = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>" + kSprings)), 40);
  const auto mapped = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>", "<MechanicalObject/>" + kSprings + "<IdentityMapping/>")), 40);
  const auto rest = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>" + kSprings)), 0);
  ASSERT_GT(largest_difference(direct, rest), 0.05);  // the springs hold the beam up: it moved
  EXPECT_LT(largest_difference(mapped, direct), 1e-12);
}

TEST(MappedMechanicsScene, SpringsOnASubsetActOnThePointsTheyPick) {
  // The mapped state is points 3, 2, 1, 0, 7, 6, 5 of the object (in that order); the springs name
  // them in the mapped numbering.
  const std::string subset =
      "<MechanicalObject/><SubsetMapping indices=\"3 2 1 0 7 6 5\"/>"
      "<SpringForceField spring=\"3 2 800 2 1  2 1 700 1 1  1 0 600 0 1  6 5 900 3 1  2 6 500 0 1.2  0 4 800 0 1\"/>";
  const std::string same =
      "<SpringForceField spring=\"0 1 800 2 1  1 2 700 1 1  2 3 600 0 1  5 6 900 3 1  1 5 500 0 1.2  3 7 800 0 1\"/>";
  const auto mapped = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>", subset)), 40);
  const auto direct = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>" + same)), 40);
  EXPECT_LT(largest_difference(mapped, direct), 1e-12);
}

TEST(MappedMechanicsScene, AMassOnAnIdentityMappedStateIsTheObjectsMass) {
  const auto direct = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>" + kSprings)), 30);
  const auto mapped = run(build_scene_text(grid(kSprings, "<MechanicalObject/><UniformMass totalMass=\"2\"/><IdentityMapping/>")), 30);
  EXPECT_LT(largest_difference(mapped, direct), 1e-12);
}

TEST(MappedMechanicsScene, AChainOfMappedNodesFolds) {
  // springs two mapped levels down, each an IdentityMapping
  const auto chained = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>",
                                                 "<MechanicalObject/><IdentityMapping/><Node name=\"deeper\"><MechanicalObject/>" +
                                                     kSprings + "<IdentityMapping/></Node>")),
                           30);
  const auto direct = run(build_scene_text(grid("<UniformMass totalMass=\"2\"/>" + kSprings)), 30);
  EXPECT_LT(largest_difference(chained, direct), 1e-12);
  const LoadedScene scene = build_scene_text(grid("<UniformMass totalMass=\"2\"/>",
                                                  "<MechanicalObject/><IdentityMapping/><Node name=\"deeper\"><MechanicalObject/>" +
                                                      kSprings + "<IdentityMapping/></Node>"));
  // Both mapped MechanicalObjects are outputs (the deeper one through the chain).
  EXPECT_EQ(scene.simulation.objects.at(0).mapped_states.size(), 2u);
}

TEST(MappedMechanicsScene, BarycentricallyMappedSpringsGiveTheSameBitsOnOneAndTwoThreads) {
  const std::string body = grid(
      "<UniformMass totalMass=\"2\"/><Node name=\"tets\"><TetrahedronSetTopologyContainer name=\"tets\"/>"
      "<Hexa2TetraTopologicalMapping input=\"@../grid\" output=\"@tets\"/></Node>",
      "<MechanicalObject position=\"0.5 0.5 0.5  1.5 0.5 0.5  2.5 0.5 0.5  2.9 0.9 0.9\"/>"
      "<SpringForceField spring=\"0 1 2000 0 0.8  1 2 2000 0 0.8  2 3 1000 0 0.3\"/><BarycentricMapping/>");
  const auto one = run(build_scene_text(body), 20, 1), two = run(build_scene_text(body), 20, 2);
  EXPECT_EQ(largest_difference(one, two), 0.0);
  EXPECT_GT(largest_difference(one, run(build_scene_text(body), 0)), 0.01);
}

TEST(MappedMechanicsScene, WhatAMappedNodeCannotCarryIsRefusedInOneLine) {
  const std::string fixed = scene_error(grid("<UniformMass totalMass=\"2\"/>",
                                             "<MechanicalObject/><IdentityMapping/><FixedProjectiveConstraint indices=\"1\"/>"));
  EXPECT_NE(fixed.find("projective constraints in a mapped node are not supported"), std::string::npos) << fixed;
  const std::string two = scene_error(grid("<UniformMass totalMass=\"2\"/>",
                                           "<MechanicalObject name=\"a\"/><MechanicalObject name=\"b\"/>" + kSprings + "<IdentityMapping/>"));
  EXPECT_NE(two.find("has 2 MechanicalObjects"), std::string::npos) << two;
  const std::string far = scene_error(grid("<UniformMass totalMass=\"2\"/>",
                                           "<MechanicalObject/><SubsetMapping indices=\"0 99\"/>" + kSprings));
  EXPECT_NE(far.find("99"), std::string::npos) << far;
  EXPECT_EQ(far.find('\n'), std::string::npos) << far;
}

TEST(MappedMechanicsScene, AMechanicalPointFarOutsideEveryTetrahedronIsRefusedAndOneNearTheSurfaceIsNot) {
  // One tetrahedron; springs between a point inside and `second` on a barycentrically mapped state.
  const auto scene = [](const std::string& second) {
    return "<Node name=\"tet\"><EulerImplicitSolver/><CGLinearSolver iterations=\"50\" tolerance=\"1e-12\" threshold=\"1e-12\"/>"
           "<MeshTopology name=\"mesh\" position=\"0 0 0  1 0 0  0 1 0  0 0 1\" tetrahedra=\"0 1 2 3\"/>"
           "<MechanicalObject name=\"dofs\"/><UniformMass totalMass=\"1\"/><FixedProjectiveConstraint indices=\"0 1 2\"/>"
           "<TetrahedronFEMForceField youngModulus=\"100\" poissonRatio=\"0.3\"/>"
           "<Node name=\"marks\"><MechanicalObject name=\"marks\" position=\"0.2 0.2 0.2  " + second + "\"/>"
           "<SpringForceField spring=\"0 1 100 0 0.3\"/><BarycentricMapping/></Node></Node>";
  };
  EXPECT_EQ(scene_error(scene("0.5 0.5 0.1")), "");  // just outside the slanted face: extrapolated, as in SOFA
  const std::string far = scene_error(scene("3 3 3"));
  EXPECT_NE(far.find("mapped node root/tet/marks: point 1 of its MechanicalObject lies outside every tetrahedron"), std::string::npos) << far;
  EXPECT_EQ(far.find('\n'), std::string::npos) << far;
}

}  // namespace
}  // namespace fastcorot
