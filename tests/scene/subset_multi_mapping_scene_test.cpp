// SubsetMultiMapping through the scene builder, with MeshSplittingEngine sharing a beam's points
// among input states as SOFA's MeshSplittingEngine.scn does: a FEM on the joined state of two free
// parts moves as the same FEM on one object; a fixed rigid carrying one end holds it as fixed
// points do; a free rigid carrying one end falls with the free part without deforming (implicit
// Euler's closed form); 1 and 2 threads give the same bits; bad input is refused in one line.
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

constexpr int kLength = 5;  // points along x: a beam of kLength × 2 × 2 points

// The beam's MeshTopology: point (i, j, k) at (i, 0.5 j, 0.5 k), 6 tetrahedra per cube.
std::string beam_mesh() {
  std::ostringstream points, tetrahedra;
  for (int i = 0; i < kLength; ++i) {
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 2; ++k) points << i << ' ' << 0.5 * j << ' ' << 0.5 * k << "  ";
    }
  }
  const int paths[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (int i = 0; i + 1 < kLength; ++i) {
    const auto corner = [&](int bits) { return (i + (bits & 1)) * 4 + ((bits >> 1) & 1) * 2 + ((bits >> 2) & 1); };
    for (const auto& p : paths) {
      tetrahedra << corner(0) << ' ' << corner(p[0]) << ' ' << corner(p[0] | p[1]) << ' ' << corner(7) << "  ";
    }
  }
  return "<MeshTopology name=\"mesh\" position=\"" + points.str() + "\" tetrahedra=\"" + tetrahedra.str() + "\"/>";
}

const std::string kEnd = "0 1 2 3";  // the points at x = 0
const std::string kFem = "<TetrahedronFEMForceField youngModulus=\"2000\" poissonRatio=\"0.3\"/>";

std::string solver(const std::string& linear) {
  return "<EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0\"/>" + linear;
}

// The beam as one object, its end fixed.
std::string whole(const std::string& linear) {
  return beam_mesh() + "<Node name=\"beam\">" + solver(linear) +
         "<MechanicalObject name=\"dofs\" position=\"@/mesh.position\"/><UniformMass vertexMass=\"0.1\"/>"
         "<FixedProjectiveConstraint indices=\"" + kEnd + "\"/>" + kFem + "</Node>";
}

// The closing tags of the nodes `body` opens.
std::string closing(const std::string& body) {
  std::string tags;
  for (std::size_t at = body.find("<Node "); at != std::string::npos; at = body.find("<Node ", at + 1)) tags += "</Node>";
  return tags;
}

// The beam's end as a part of its own (`first`: its node's body, the end's points at
// @/split.position1) and the rest as a free part, joined by a SubsetMultiMapping that the FEM acts on.
std::string split(const std::string& linear, const std::string& first, const std::string& multi_extra = "") {
  return beam_mesh() + "<MeshSplittingEngine name=\"split\" src=\"@mesh\" nbInputs=\"1\" indices1=\"" + kEnd + "\"/>" +
         "<Node name=\"beam\">" + solver(linear) + first +
         "<Node name=\"free\"><MechanicalObject name=\"rest\" position=\"@/split.position2\"/><UniformMass vertexMass=\"0.1\"/>"
         "<Node name=\"whole\"><MeshTopology src=\"@/mesh\"/><MechanicalObject name=\"joined\"/>"
         "<SubsetMultiMapping template=\"Vec3,Vec3\" input=\"@../../ @../\" output=\"@./\" indexPairs=\"@/split.indexPairs\"/>" +
         kFem + multi_extra + "</Node></Node>" + closing(first) + "</Node>";
}

// Part 1 as free points fixed in place, or carried by a rigid (fixed, or free with mass 1).
const std::string kFixedPart =
    "<Node name=\"end\"><MechanicalObject name=\"end\" position=\"@/split.position1\"/><UniformMass vertexMass=\"0.1\"/>"
    "<FixedProjectiveConstraint indices=\"0 1 2 3\"/>";
std::string rigid_part(bool fixed) {
  return "<Node name=\"frame\"><MechanicalObject name=\"frame\" template=\"Rigid3\" "
         "position=\"0.3 0.2 0.1  0.1 0.2 0.3 0.9273618495495703\"/><UniformMass totalMass=\"1\"/>" +
         std::string(fixed ? "<FixedProjectiveConstraint indices=\"0\"/>" : "") +
         "<Node name=\"end\"><MechanicalObject name=\"carried\" position=\"@/split.position1\"/><RigidMapping globalToLocalCoords=\"1\"/>";
}

// The positions of the state named `name` after `steps` steps.
std::vector<Vec3<double>> run(LoadedScene scene, int steps, const std::string& name, int threads = 1) {
  scene.simulation.threads = threads;
  for (int s = 0; s < steps; ++s) scene.simulation.step();
  for (const auto& snapshot : state_snapshots(scene.simulation.objects.at(0))) {
    if (snapshot.name == name) return snapshot.position;
  }
  ADD_FAILURE() << "no state " << name;
  return {};
}

double largest_difference(const std::vector<Vec3<double>>& a, const std::vector<Vec3<double>>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

const std::string kLDL = "<SparseLDLSolver/>";
const std::string kCG = "<CGLinearSolver iterations=\"400\" tolerance=\"1e-24\" threshold=\"1e-30\"/>";

TEST(SubsetMultiMappingScene, TwoFreePartsJoinedMoveAsOneObject) {
  for (const std::string& linear : {kLDL, kCG}) {
    const auto reference = run(build_scene_text(whole(linear), "dt=\"0.01\""), 40, "dofs");
    const auto joined = run(build_scene_text(split(linear, kFixedPart), "dt=\"0.01\""), 40, "joined");
    ASSERT_GT(largest_difference(reference, run(build_scene_text(whole(linear), "dt=\"0.01\""), 0, "dofs")), 0.01) << "the beam bends";
    EXPECT_LT(largest_difference(joined, reference), 1e-10) << linear;
  }
}

TEST(SubsetMultiMappingScene, AFixedRigidCarryingTheEndHoldsItAsFixedPoints) {
  for (const std::string& linear : {kLDL, kCG}) {
    const auto reference = run(build_scene_text(whole(linear), "dt=\"0.01\""), 40, "dofs");
    const auto joined = run(build_scene_text(split(linear, rigid_part(true)), "dt=\"0.01\""), 40, "joined");
    const auto start = run(build_scene_text(split(linear, rigid_part(true)), "dt=\"0.01\""), 0, "joined");
    ASSERT_GT(largest_difference(joined, start), 0.01) << "the free part bends";
    EXPECT_LT(largest_difference(joined, reference), 1e-10) << linear;
  }
}

TEST(SubsetMultiMappingScene, AFreeRigidCarryingTheEndFallsWithTheRestUndeformed) {
  // No rayleighMass: implicit Euler's free fall is exact, x_n = x_0 + h² g n(n + 1)/2, and a
  // translation strains nothing, so every point and the rigid's centre follow it.
  const int steps = 30;
  const double h = 0.01;
  const Vec3<double> drop = Vec3<double>(0, -9.81, 0) * h * h * steps * (steps + 1) / 2;
  for (const std::string& linear : {kLDL, kCG}) {
    const auto start = run(build_scene_text(split(linear, rigid_part(false)), "dt=\"0.01\""), 0, "joined");
    const auto end = run(build_scene_text(split(linear, rigid_part(false)), "dt=\"0.01\""), steps, "joined");
    ASSERT_EQ(start.size(), static_cast<std::size_t>(4 * kLength));
    for (std::size_t i = 0; i < start.size(); ++i) EXPECT_LT((end[i] - start[i] - drop).norm(), 1e-9) << linear << " point " << i;
    LoadedScene scene = build_scene_text(split(linear, rigid_part(false)), "dt=\"0.01\"");
    for (int s = 0; s < steps; ++s) scene.simulation.step();
    int frames = 0;
    for (const auto& snapshot : state_snapshots(scene.simulation.objects.at(0))) {
      if (snapshot.name != "frame") continue;
      ++frames;
      ASSERT_EQ(snapshot.rigid_position.size(), 7u);
      EXPECT_LT((Vec3<double>(snapshot.rigid_position[0], snapshot.rigid_position[1], snapshot.rigid_position[2]) -
                 Vec3<double>(0.3, 0.2, 0.1) - drop).norm(), 1e-9);
      EXPECT_NEAR(snapshot.rigid_position[6], 0.9273618495495703, 1e-12) << "the rigid does not turn";
    }
    EXPECT_EQ(frames, 1);
  }
}

TEST(SubsetMultiMappingScene, AJoinedStateWithoutPositionsOfItsOwnRestsAtZeroAsSofa) {
  // Two points (mass 1 each) a unit apart, joined by a SubsetMultiMapping into a state with no
  // positions of its own and a spring on its edge (SOFA's NearestPointROI.scn fuses points so): SOFA
  // stores that state's rest positions before the mapping fills it, all zero, so the spring's rest
  // length is 0 and it pulls the points together. Implicit Euler, u'' = -ω² u with ω² = 2k/m: after
  // one step from rest u = u0 / (1 + h² ω²).
  const double k = 50, h = 0.01;
  LoadedScene scene = build_scene_text(
      "<EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><CGLinearSolver iterations=\"100\" tolerance=\"1e-30\" threshold=\"1e-30\"/>"
      "<Node name=\"a\"><MechanicalObject name=\"point\" position=\"0 0 0\"/><UniformMass totalMass=\"1\"/></Node>"
      "<Node name=\"b\"><MechanicalObject name=\"point\" position=\"1 0 0\"/><UniformMass totalMass=\"1\"/></Node>"
      "<Node name=\"joined\"><MechanicalObject name=\"points\"/>"
      "<SubsetMultiMapping input=\"@../a/point @../b/point\" output=\"@points\" indexPairs=\"0 0  1 0\"/>"
      "<EdgeSetTopologyContainer edges=\"0 1\"/><MeshSpringForceField linesStiffness=\"50\" linesDamping=\"0\"/></Node>",
      "dt=\"0.01\" gravity=\"0 0 0\"");
  bool said = false;
  for (const auto& line : scene.info) said = said || line.find("have no rest position of their own") != std::string::npos;
  EXPECT_TRUE(said);
  scene.simulation.step();
  const auto& x = scene.simulation.objects[0].system.state.position;
  EXPECT_NEAR(x[1].x() - x[0].x(), 1.0 / (1.0 + h * h * 2 * k), 1e-12);
}

TEST(SubsetMultiMappingScene, OneAndTwoThreadsGiveTheSameBits) {
  const std::string scene = split(kCG, rigid_part(false));
  const auto one = run(build_scene_text(scene, "dt=\"0.01\""), 15, "joined", 1);
  const auto two = run(build_scene_text(scene, "dt=\"0.01\""), 15, "joined", 2);
  EXPECT_EQ(largest_difference(one, two), 0.0);
}

TEST(SubsetMultiMappingScene, BadInputIsRefusedInOneLine) {
  const auto refused = [](const std::string& scene, const std::string& expected) {
    const std::string message = scene_error(scene);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  std::string odd = split(kLDL, kFixedPart);
  odd.replace(odd.find("indexPairs=\"@/split.indexPairs\""), 31, "indexPairs=\"0 1 1\"");
  refused(odd, "indexPairs has 3 numbers");
  std::string far = split(kLDL, kFixedPart);
  far.replace(far.find("indexPairs=\"@/split.indexPairs\""), 31, "indexPairs=\"0 0 1 99\"");
  refused(far, "takes point 99 of input 1");
  std::string rigid = split(kLDL, rigid_part(true));
  rigid.replace(rigid.find("input=\"@../../ @../\""), 20, "input=\"@/beam/frame @../\"");
  refused(rigid, "is a Rigid3 state");
  std::string outside = "<Node name=\"other\"><MechanicalObject name=\"other\" position=\"0 0 0\"/></Node>" + split(kLDL, kFixedPart);
  outside.replace(outside.find("input=\"@../../ @../\""), 20, "input=\"@/other @../\"");
  refused(outside, "is not a state this node's ODE solver integrates");
  // A lumped mass on the joined state goes up point by point (python/tests/test_multi_mapping.py
  // compares it with the masses on the inputs); a mass matrix would couple rigid-carried points
  // with others, which is not made.
  EXPECT_EQ(scene_error(split(kLDL, rigid_part(true), "<UniformMass vertexMass=\"1\"/>")), "");
  refused(split(kLDL, rigid_part(true), "<MeshMatrixMass massDensity=\"1\" lumping=\"false\"/>"),
          "a mass matrix (MeshMatrixMass without lumping) on a SubsetMultiMapping");
}

}  // namespace
}  // namespace fastcorot
