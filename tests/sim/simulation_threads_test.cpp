// A whole simulation gives bitwise the same trajectory on any thread count: one object whose
// kernels and solver vectors run on several threads, and two objects run concurrently; also with
// another process keeping a core busy, whether the loops give up threads to it or not.
#include "fastcorot/core/parallel.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/scene/scene_graph.h"

#include "support/busy_core.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fastcorot {
namespace {

const std::string kCG = "<CGLinearSolver iterations=\"20\" tolerance=\"1e-9\" threshold=\"1e-12\"/>";

std::string beam(const std::string& name, const std::string& method, const std::string& solver = kCG) {
  return "<Node name=\"" + name + "\">"
         "<EulerImplicitSolver rayleighStiffness=\"0.1\" rayleighMass=\"0.1\"/>" + solver +
         "<RegularGridTopology name=\"grid\" n=\"26 8 8\" min=\"0 6 -2\" max=\"16 10 2\"/>"
         "<MechanicalObject name=\"state\"/>"
         "<TetrahedronSetTopologyContainer name=\"tetrahedra\"/>"
         "<Hexa2TetraTopologicalMapping input=\"@grid\" output=\"@tetrahedra\" swapping=\"true\"/>"
         "<DiagonalMass totalMass=\"50\"/>"
         "<FastTetrahedralCorotationalForceField youngModulus=\"2000\" poissonRatio=\"0.3\" method=\"" + method + "\"/>"
         "<BoxROI name=\"clamp\" box=\"-0.1 5 -3 0.1 11 3\"/>"
         "<FixedProjectiveConstraint indices=\"@clamp.indices\"/>"
         "</Node>";
}

std::vector<std::vector<Vec3<double>>> run(const std::string& children, int threads, int steps) {
  LoadedScene scene = build_scene(
      parse_scene_text("<Node name=\"root\" dt=\"0.02\" gravity=\"0 -9 0\">" + children + "</Node>", "threads.scn"));
  scene.simulation.threads = threads;
  for (int s = 0; s < steps; ++s) scene.simulation.step();
  std::vector<std::vector<Vec3<double>>> positions;
  for (const auto& object : scene.simulation.objects) positions.push_back(object.system.state.position);
  return positions;
}

TEST(SimulationThreads, OneObjectSameBitsOnOneTwoAndThreeThreads) {
  for (const std::string method : {"large", "polar"}) {
    const auto one = run(beam("beam", method), 1, 4);
    EXPECT_TRUE(run(beam("beam", method), 2, 4) == one) << method;
    EXPECT_TRUE(run(beam("beam", method), 3, 4) == one) << method;
    EXPECT_NE(one[0][one[0].size() - 1], run(beam("beam", method), 1, 3)[0][one[0].size() - 1]);  // it moves
  }
}

TEST(SimulationThreads, SameBitsWithACoreBusy) {
  const auto one = run(beam("beam", "large"), 1, 6);
  const testing::BusyCore busy;
  for (bool yield : {true, false}) {
    set_yield_cores_to_other_processes(yield);
    for (int threads : {1, 2, 3}) EXPECT_TRUE(run(beam("beam", "large"), threads, 6) == one) << threads << " " << yield;
  }
  set_yield_cores_to_other_processes(true);
}

TEST(SimulationThreads, PreconditionedSolversSameBitsOnOneAndTwoThreads) {
  // 1,664 points: the preconditioned passes over points run in two chunks, the sums in five.
  for (const std::string preconditioner : {"BlockJacobiPreconditioner", "JacobiPreconditioner", "SparseLDLSolver"}) {
    const std::string solver = "<PCGLinearSolver iterations=\"15\" tolerance=\"1e-12\" preconditioner=\"@P\"/><" +
                               preconditioner + " name=\"P\"/>";
    const auto one = run(beam("beam", "large", solver), 1, 3);
    EXPECT_TRUE(run(beam("beam", "large", solver), 2, 3) == one) << preconditioner;
    EXPECT_FALSE(run(beam("beam", "large"), 1, 3) == one);  // not the CG's trajectory
  }
}

TEST(SimulationThreads, TwoObjectsSameBitsAsEachAlone) {
  const auto both = run(beam("a", "large") + beam("b", "polar"), 4, 3);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_TRUE(run(beam("a", "large"), 1, 3)[0] == both[0]);
  EXPECT_TRUE(run(beam("b", "polar"), 1, 3)[0] == both[1]);
}

}  // namespace
}  // namespace fastcorot
