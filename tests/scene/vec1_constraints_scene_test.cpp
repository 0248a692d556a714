// Vec1 states through the scene builder: a DistanceMapping's edge extensions under
// UniformLagrangianConstraint (SOFA's InextensiblePendulum setting) against SOFA's own trajectory
// (tests/data/sofa_reference/inextensible_pendulum*.{scn,json}) over 300 steps, with and without
// the constraint forces' geometric stiffness; a StopperLagrangianConstraint bounding a soft edge's
// stretch; the Vec1 state in outputs (one coordinate); bad input refused naming the component.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"
#include "fastcorot/sim/mapped_state.h"

#include "../support/scene_text.h"
#include "support/sofa_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The largest distance to SOFA's positions at each dumped step, relative to SOFA's largest
// displacement from step 0 there; the extensions' largest difference absolutely.
struct Comparison {
  double particles = 0, extensions = 0;
};
std::vector<std::pair<int, Comparison>> compare_with_sofa(LoadedScene& scene, const nlohmann::json& reference) {
  std::vector<int> steps;
  for (const auto& item : reference["steps"].items()) steps.push_back(std::stoi(item.key()));
  std::sort(steps.begin(), steps.end());
  const auto rest = testing::json_points(reference["steps"]["0"]["particles"]);
  std::vector<std::pair<int, Comparison>> out;
  auto& simulation = scene.simulation;
  for (const int step : steps) {
    while (simulation.steps_done() < step) simulation.step();
    const auto& frame = reference["steps"][std::to_string(step)];
    const auto expected = testing::json_points(frame["particles"]);
    const auto snapshots = state_snapshots(simulation.objects[0]);
    const auto& x = simulation.objects[0].system.state.position;
    Comparison c;
    double displacement = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      c.particles = std::max(c.particles, (x[i] - expected[i]).norm());
      displacement = std::max(displacement, (expected[i] - rest[i]).norm());
    }
    if (displacement > 0) c.particles /= displacement;
    const auto& lengths = snapshots.back();
    EXPECT_EQ(lengths.coordinates, 1);
    const auto& values = frame["extensions"];
    for (std::size_t i = 0; i < values.size(); ++i) c.extensions = std::max(c.extensions, std::abs(lengths.position[i][0] - values[i].get<double>()));
    out.emplace_back(step, c);
  }
  return out;
}

TEST(Vec1Scene, InextensiblePendulumFollowsSofaFor300Steps) {
  LoadedScene scene = load_scene_file(testing::sofa_reference_path("inextensible_pendulum.scn"));
  std::ifstream in(testing::sofa_reference_path("inextensible_pendulum_trajectory.json"));
  const auto reference = nlohmann::json::parse(in);
  ASSERT_EQ(scene.simulation.objects.size(), 1u);
  ASSERT_EQ(scene.simulation.objects[0].system.size(), 20);
  for (const auto& [step, c] : compare_with_sofa(scene, reference)) {
    EXPECT_LT(c.particles, 1e-9) << "step " << step;
    EXPECT_LT(c.extensions, 1e-12) << "step " << step;
  }
  EXPECT_EQ(scene.simulation.constraint_report().rows, 19);
  EXPECT_TRUE(scene.simulation.constraint_report().converged);
}

TEST(Vec1Scene, WithoutTheGeometricStiffnessThePendulumLeavesSofasPath) {
  // The constraint forces' geometric stiffness is what SOFA's step has: without it the wire
  // swings differently within a few dozen steps (so the test above would see it missing).
  std::string text = read_file(testing::sofa_reference_path("inextensible_pendulum.scn"));
  text = std::regex_replace(text, std::regex("<DistanceMapping "), "<DistanceMapping geometricStiffness=\"None\" ");
  LoadedScene scene = build_scene(parse_scene_text(text, testing::sofa_reference_path("inextensible_pendulum.scn")));
  std::ifstream in(testing::sofa_reference_path("inextensible_pendulum_trajectory.json"));
  const auto comparison = compare_with_sofa(scene, nlohmann::json::parse(in));
  EXPECT_GT(comparison.back().second.particles, 1e-3);
}

// Three particles hanging from a fixed one along -y, joined by soft springs: the stopper on edge
// `stopped` keeps its extension at or below `max`.
std::string hanging_wire(const std::string& stopper) {
  return "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver tolerance=\"1e-12\" maxIterations=\"1000\"/>"
         "<EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/><GenericConstraintCorrection/>"
         "<EdgeSetTopologyContainer name=\"edges\" position=\"0 0 0  0 -1 0  0 -2 0\" edges=\"0 1  1 2\"/>"
         "<MechanicalObject name=\"particles\"/><FixedProjectiveConstraint indices=\"0\"/><UniformMass totalMass=\"3\"/>"
         "<MeshSpringForceField linesStiffness=\"20\" linesDamping=\"0\"/>"
         "<Node name=\"lengths\"><MechanicalObject name=\"extensions\" template=\"Vec1\"/>"
         "<DistanceMapping topology=\"@../edges\"/>" + stopper + "</Node>";
}

TEST(Vec1Scene, StopperKeepsAnEdgesStretchWithinItsBound) {
  const auto stretch = [](LoadedScene& scene, int steps) {
    double most = 0;
    for (int n = 0; n < steps; ++n) {
      scene.simulation.step();
      const auto& x = scene.simulation.objects[0].system.state.position;
      most = std::max(most, (x[1] - x[0]).norm() - 1.0);
    }
    return most;
  };
  LoadedScene free_wire = build_scene_text(hanging_wire(""), "dt=\"0.01\" gravity=\"0 -10 0\"");
  EXPECT_GT(stretch(free_wire, 100), 0.5) << "the soft spring alone stretches far";
  LoadedScene stopped = build_scene_text(hanging_wire("<StopperLagrangianConstraint template=\"Vec1\" index=\"0\" min=\"-1\" max=\"0.1\"/>"),
                                         "dt=\"0.01\" gravity=\"0 -10 0\"");
  // The row is linear at the step's start: the end-of-step stretch exceeds the bound only by the
  // linearisation's second-order error.
  EXPECT_LT(stretch(stopped, 100), 0.1 + 1e-3);
  EXPECT_EQ(stopped.simulation.constraint_report().rows, 1);
}

TEST(Vec1Scene, BadInputIsRefusedNamingTheComponent) {
  // A Vec1 state with a solver of its own.
  EXPECT_NE(scene_error("<EulerImplicitSolver/><CGLinearSolver/><MechanicalObject template=\"Vec1\" position=\"0 1\"/>"
                        "<UniformMass totalMass=\"1\"/>").find("Vec1 states are supported only as the output of a DistanceMapping"),
            std::string::npos);
  // A DistanceMapping onto a Vec3 state.
  const std::string vec3_output = hanging_wire("");
  EXPECT_NE(scene_error(std::regex_replace(vec3_output, std::regex("template=\"Vec1\""), "")).find("SOFA's DistanceMapping outputs Vec1"),
            std::string::npos);
  // Constraints that SOFA defines on Vec1 only, or not on Vec1.
  EXPECT_NE(scene_error(hanging_wire("<StopperLagrangianConstraint index=\"5\"/>")).find("index = 5 is out of range"), std::string::npos);
  EXPECT_NE(scene_error(hanging_wire("<FixedLagrangianConstraint indices=\"0\"/>")).find("is a Vec1 state"), std::string::npos);
  EXPECT_NE(scene_error(hanging_wire("<UniformLagrangianConstraint template=\"Vec3\"/>")).find("on Vec1 states only"),
            std::string::npos);
  // On the wire's own Vec3 state (no template written: the state's).
  const std::string on_vec3 = std::regex_replace(hanging_wire(""), std::regex("<Node name=\"lengths\">"),
                                                 "<StopperLagrangianConstraint/><Node name=\"lengths\">");
  EXPECT_NE(scene_error(on_vec3).find("is a Vec3d state: SOFA defines StopperLagrangianConstraint on Vec1 states only"), std::string::npos)
      << scene_error(on_vec3);
  EXPECT_NE(scene_error(std::regex_replace(hanging_wire(""), std::regex("<DistanceMapping "), "<DistanceMapping geometricStiffness=\"Soft\" "))
                .find("geometricStiffness = \"Soft\""),
            std::string::npos);
}

// Two wires of three particles under one solver (one merged object): the second one's edges are
// held by a UniformLagrangianConstraint on its DistanceMapping, whose points start after the first
// wire's in the object.
std::string two_wires(const std::string& solver, const std::string& mapping_extra = "", const std::string& uniform = "") {
  const auto wire = [](const std::string& name, const std::string& x, const std::string& inner) {
    return "<Node name=\"" + name + "\"><EdgeSetTopologyContainer name=\"edges\" position=\"" + x + "\" edges=\"0 1  1 2\"/>"
           "<MechanicalObject name=\"particles\"/><FixedProjectiveConstraint indices=\"0\"/><UniformMass totalMass=\"3\"/>"
           "<MeshSpringForceField linesStiffness=\"5\" linesDamping=\"0\"/><GenericConstraintCorrection/>" + inner + "</Node>";
  };
  return "<FreeMotionAnimationLoop/>" + solver + "<EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><SparseLDLSolver/>" +
         wire("a", "0 0 0  1 0 0  2 0 0", "") +
         wire("b", "0 0 1  1 0 1  2 0 1",
              "<Node name=\"lengths\"><MechanicalObject name=\"extensions\" template=\"Vec1\"/><DistanceMapping topology=\"@../edges\" " +
                  mapping_extra + "/><UniformLagrangianConstraint template=\"Vec1\" iterative=\"false\" " + uniform + "/></Node>");
}

double stretch(const LoadedScene& scene, std::size_t first) {
  const auto& x = scene.simulation.objects[0].system.state.position;
  return std::max(std::abs((x[first + 1] - x[first]).norm() - 1.0), std::abs((x[first + 2] - x[first + 1]).norm() - 1.0));
}

TEST(Vec1Scene, AWireAfterAnotherInOneObjectKeepsItsOwnLengths) {
  LoadedScene scene = build_scene_text(two_wires("<BlockGaussSeidelConstraintSolver tolerance=\"1e-14\" maxIterations=\"1000\"/>"),
                                       "dt=\"0.01\" gravity=\"0 -10 0\"");
  ASSERT_EQ(scene.simulation.objects.size(), 1u);
  ASSERT_EQ(scene.simulation.objects[0].system.size(), 6);
  for (int k = 0; k < 50; ++k) scene.simulation.step();
  EXPECT_LT(stretch(scene, 3), 1e-3) << "wire b is held (its own points, 3..5)";
  EXPECT_GT(stretch(scene, 0), 1e-2) << "wire a is only springs and stretches";
}

TEST(Vec1Scene, ApplyRestPositionHoldsTheRestLengthsWithConstrainToRestPos) {
  // computeDistance: the values are the lengths; applyRestPosition: the rest values too, so
  // constrainToRestPos holds the lengths at rest (without it the rest values are zero: collapse).
  LoadedScene held = build_scene_text(two_wires("<BlockGaussSeidelConstraintSolver tolerance=\"1e-14\" maxIterations=\"1000\"/>",
                                                "computeDistance=\"1\" applyRestPosition=\"1\"", "constrainToRestPos=\"1\""),
                                      "dt=\"0.01\" gravity=\"0 -10 0\"");
  for (int k = 0; k < 50; ++k) held.simulation.step();
  EXPECT_LT(stretch(held, 3), 1e-3);
  LoadedScene zero = build_scene_text(two_wires("<BlockGaussSeidelConstraintSolver tolerance=\"1e-14\" maxIterations=\"1000\"/>",
                                                "computeDistance=\"1\"", "constrainToRestPos=\"1\""),
                                      "dt=\"0.01\" gravity=\"0 -10 0\"");
  for (int k = 0; k < 50; ++k) zero.simulation.step();
  EXPECT_GT(stretch(zero, 3), 0.5) << "held at zero length";
}

TEST(Vec1Scene, UnderLcpTheConstraintForcesGiveNoGeometricStiffnessAsInSofa) {
  // SOFA's LCPConstraintSolver stores no λ on the states, so the mapping's geometric stiffness reads
  // nothing: Stabilized and None give the same trajectory.
  const std::string lcp = "<LCPConstraintSolver tolerance=\"1e-12\" maxIt=\"1000\" mu=\"0\"/>";
  LoadedScene stabilized = build_scene_text(two_wires(lcp), "dt=\"0.01\" gravity=\"0 -10 0\"");
  LoadedScene none = build_scene_text(two_wires(lcp, "geometricStiffness=\"None\""), "dt=\"0.01\" gravity=\"0 -10 0\"");
  for (int k = 0; k < 30; ++k) stabilized.simulation.step(), none.simulation.step();
  EXPECT_EQ(stabilized.simulation.objects[0].system.state.position, none.simulation.objects[0].system.state.position);
  // Under Gauss–Seidel they differ (the test above would see a stored λ).
  const std::string gs = "<BlockGaussSeidelConstraintSolver tolerance=\"1e-14\" maxIterations=\"1000\"/>";
  LoadedScene a = build_scene_text(two_wires(gs), "dt=\"0.01\" gravity=\"0 -10 0\"");
  LoadedScene b = build_scene_text(two_wires(gs, "geometricStiffness=\"None\""), "dt=\"0.01\" gravity=\"0 -10 0\"");
  for (int k = 0; k < 30; ++k) a.simulation.step(), b.simulation.step();
  EXPECT_NE(a.simulation.objects[0].system.state.position, b.simulation.objects[0].system.state.position);
}

TEST(Vec1Scene, VecThreeConstraintsOnAVecOneStateAreRefused) {
  // A SlidingLagrangianConstraint whose object2 is the Vec1 state.
  const std::string text = hanging_wire("") +
                           "<SlidingLagrangianConstraint object1=\"@particles\" object2=\"@lengths/extensions\" sliding_point=\"1\" "
                           "axis_1=\"0\" axis_2=\"1\"/>";
  EXPECT_NE(scene_error(text).find("is a Vec1 state"), std::string::npos) << scene_error(text);
}

TEST(Vec1Scene, DiagonalMassOnAWireTakesSofasPrecedence) {
  // Edges of lengths 1 and 2: with massDensity ρ each end of an edge gets ρ l / 2; totalMass wins
  // over it (scaled to the total); vertexMass alone gives each point its own.
  const auto masses = [](const std::string& mass) {
    LoadedScene scene = build_scene_text("<EulerImplicitSolver/><CGLinearSolver/><EdgeSetTopologyContainer position=\"0 0 0  1 0 0  3 0 0\" "
                                         "edges=\"0 1  1 2\"/><MechanicalObject/>" + mass);
    const auto m = scene.simulation.objects[0].system.mass.vertex_masses();
    return std::vector<double>(m.begin(), m.end());
  };
  const auto density = masses("<DiagonalMass massDensity=\"2\"/>");
  EXPECT_NEAR(density[0], 1.0, 1e-15);
  EXPECT_NEAR(density[1], 1.0 + 2.0, 1e-15);
  EXPECT_NEAR(density[2], 2.0, 1e-15);
  const auto total = masses("<DiagonalMass totalMass=\"3\" massDensity=\"2\"/>");
  EXPECT_NEAR(total[0] + total[1] + total[2], 3.0, 1e-14);
  EXPECT_NEAR(total[1] / total[0], 3.0, 1e-14);
  const auto given = masses("<DiagonalMass vertexMass=\"0.5 0.25 0.125\"/>");
  EXPECT_EQ(given, (std::vector<double>{0.5, 0.25, 0.125}));
  EXPECT_NE(scene_error("<EulerImplicitSolver/><CGLinearSolver/><EdgeSetTopologyContainer position=\"0 0 0  1 0 0\" edges=\"0 1\"/>"
                        "<MechanicalObject/><DiagonalMass vertexMass=\"1\"/>")
                .find("vertexMass has 1 values for 2 points"),
            std::string::npos);
}

}  // namespace
}  // namespace fastcorot
