// FreeMotionAnimationLoop scenes through the scene builder: a FixedLagrangianConstraint gives the
// projective constraint's trajectory (the KKT solution equals the projected system when W is exact
// and the solve converges); a scene without constraints runs as under the default loop, to the bit;
// a BilateralLagrangianConstraint keeps its points together to the solver's tolerance (points of
// the objects themselves, mapped points, uncoupled corrections); 1 and 2 threads agree to the bit;
// bad input is refused in one line.
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/io/checkpoint.h"
#include "fastcorot/scene/scene_builder.h"

#include "../support/scene_text.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace fastcorot {
namespace {

using testing::build_scene_text;
using testing::scene_error;

const char* kRoot = "dt=\"0.01\" gravity=\"0 -9.81 0\"";

// A beam of 6 × 2 × 2 points from x = x0 to x0 + 1, with its solvers and `extra` components.
std::string beam(const std::string& name, double x0, const std::string& extra, const std::string& linear = "<SparseLDLSolver/>") {
  return "<Node name=\"" + name + "\"><EulerImplicitSolver rayleighMass=\"0.1\" rayleighStiffness=\"0.1\"/>" + linear +
         "<RegularGridTopology name=\"grid\" n=\"6 2 2\" min=\"" + std::to_string(x0) + " 0 0\" max=\"" + std::to_string(x0 + 1) +
         " 0.2 0.2\"/><MechanicalObject name=\"dofs\"/><TetrahedronFEMForceField youngModulus=\"5e4\" poissonRatio=\"0.3\"/>"
         "<UniformMass totalMass=\"1\"/>" + extra + "</Node>";
}

const std::string kLeftEnd = "<BoxROI name=\"box\" box=\"-0.01 -0.01 -0.01 0.01 0.21 0.21\"/>";

double max_difference(const std::vector<Vec3<double>>& a, const std::vector<Vec3<double>>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

TEST(LagrangianScene, FixedLagrangianConstraintGivesTheProjectiveTrajectory) {
  LoadedScene projective = build_scene_text(beam("beam", 0, kLeftEnd + "<FixedProjectiveConstraint indices=\"@box.indices\"/>"), kRoot);
  LoadedScene lagrangian = build_scene_text(
      "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"5000\" tolerance=\"1e-15\"/>" +
          beam("beam", 0, kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>"),
      kRoot);
  ASSERT_TRUE(lagrangian.simulation.constraints);
  const auto& a = projective.simulation.objects[0].system.state;
  const auto& b = lagrangian.simulation.objects[0].system.state;
  double sag = 0;
  for (int step = 1; step <= 200; ++step) {
    projective.simulation.step();
    lagrangian.simulation.step();
    ASSERT_LT(max_difference(a.position, b.position), 1e-10) << "step " << step;
    ASSERT_LT(max_difference(a.velocity, b.velocity), 1e-8) << "step " << step;
    sag = std::max(sag, -a.position[5].y());
  }
  EXPECT_GT(sag, 1e-3) << "the beam bends under its weight";
  EXPECT_EQ(lagrangian.simulation.constraint_report().rows, 12);  // 4 points held, 3 rows each
  EXPECT_TRUE(lagrangian.simulation.constraint_report().converged);
}

TEST(LagrangianScene, ACorrectionBesideTheOdeSolverServesTheObjectsBelowIt) {
  // SoftRobots' Trunk: solvers and GenericConstraintCorrection in one node, the body in a child.
  const std::string solver = "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"200\" tolerance=\"1e-12\"/>";
  const std::string held = kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/>";
  LoadedScene together = build_scene_text(solver + beam("beam", 0, held + "<GenericConstraintCorrection/>"), kRoot);
  const std::string body = beam("beam", 0, held);
  const std::string solvers = "<EulerImplicitSolver rayleighMass=\"0.1\" rayleighStiffness=\"0.1\"/><SparseLDLSolver/>";
  std::string child = body;
  child.replace(child.find(solvers), solvers.size(), "");
  LoadedScene above = build_scene_text(solver + "<Node name=\"Simulation\">" + solvers + "<GenericConstraintCorrection/>" + child + "</Node>", kRoot);
  ASSERT_EQ(above.simulation.objects.size(), 1u);
  for (int step = 1; step <= 50; ++step) {
    together.simulation.step();
    above.simulation.step();
  }
  EXPECT_EQ(together.simulation.objects[0].system.state.position, above.simulation.objects[0].system.state.position);
  EXPECT_EQ(above.simulation.constraint_report().rows, 12);
  // Without an ODE solver there, nothing to correct: refused naming the node.
  EXPECT_NE(scene_error(solver + "<Node name=\"S\"><GenericConstraintCorrection/>" + body + "</Node>")
                .find("node root/S has no MechanicalObject and no ODE solver whose objects it could correct"),
            std::string::npos);
}

TEST(LagrangianScene, WithoutConstraintsTheLoopGivesTheDefaultTrajectoryToTheBit) {
  const std::string body = beam("beam", 0, kLeftEnd + "<FixedProjectiveConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>");
  LoadedScene plain = build_scene_text(body, kRoot);
  LoadedScene loop = build_scene_text("<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver/>" + body, kRoot);
  for (int step = 0; step < 50; ++step) {
    plain.simulation.step();
    loop.simulation.step();
  }
  EXPECT_EQ(plain.simulation.objects[0].system.state.position, loop.simulation.objects[0].system.state.position);
  EXPECT_EQ(plain.simulation.objects[0].system.state.velocity, loop.simulation.objects[0].system.state.velocity);
  EXPECT_EQ(loop.simulation.constraint_report().rows, 0);
}

// Beam A, fixed at x = 0, and beam B from x = 1 to 2 held to A's end only by a bilateral constraint
// on the four points where they meet.
std::string tied_beams(const std::string& b_correction, const std::string& solver, const std::string& b_interface = "") {
  return "<FreeMotionAnimationLoop/>" + solver +
         beam("A", 0, kLeftEnd + "<FixedProjectiveConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>") +
         beam("B", 1, b_correction + b_interface) +
         "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"" + std::string(b_interface.empty() ? "@B/dofs" : "@B/interface/points") +
         "\" first_point=\"5 11 17 23\" second_point=\"0 " + (b_interface.empty() ? "6 12 18" : "1 2 3") + "\"/>";
}

// `limit`: how far below y = 0 B's far end may hang (free fall over the run would take it 4.9 m
// down in 1 s).
void expect_tied(LoadedScene& scene, int steps, double tolerance, bool mapped = false, double limit = 1.0) {
  const auto& a = scene.simulation.objects[0].system.state.position;
  const auto& b = scene.simulation.objects[1].system.state.position;
  const Index first[4] = {5, 11, 17, 23}, second[4] = {0, 6, 12, 18};
  for (int step = 1; step <= steps; ++step) {
    scene.simulation.step();
    for (int k = 0; k < 4; ++k) {
      const double gap = (b[static_cast<std::size_t>(second[k])] - a[static_cast<std::size_t>(first[k])]).norm();
      ASSERT_LT(gap, tolerance) << "step " << step << " pair " << k << (mapped ? " (mapped)" : "");
    }
  }
  EXPECT_LT(b[5].y(), -0.01) << "B hangs from A's end and sags";
  EXPECT_GT(b[5].y(), -limit) << "B is held";
}

TEST(LagrangianScene, BilateralConstraintKeepsTwoBeamsTogether) {
  LoadedScene scene = build_scene_text(
      tied_beams("<LinearSolverConstraintCorrection/>", "<BlockGaussSeidelConstraintSolver maxIterations=\"1000\" tolerance=\"1e-12\"/>"), kRoot);
  expect_tied(scene, 150, 1e-9);
  EXPECT_EQ(scene.simulation.constraint_report().rows, 12);
}

TEST(LagrangianScene, BilateralConstraintOnMappedPoints) {
  // B's end points reached through a BarycentricMapping of a mapped node with its own points.
  const std::string interface =
      "<Node name=\"interface\"><MechanicalObject name=\"points\" position=\"1 0 0  1 0.2 0  1 0 0.2  1 0.2 0.2\"/>"
      "<BarycentricMapping/></Node>";
  LoadedScene scene = build_scene_text(
      tied_beams("<LinearSolverConstraintCorrection/>", "<BlockGaussSeidelConstraintSolver maxIterations=\"1000\" tolerance=\"1e-12\"/>",
                 interface),
      kRoot);
  // Pairs: A 5 ↔ mapped 0 (B's point 0); A 11 ↔ mapped 1 (B's 6, y = 0.2); A 17 ↔ mapped 2 (B's 12, z = 0.2); A 23 ↔ mapped 3.
  expect_tied(scene, 100, 1e-8, true);
}

TEST(LagrangianScene, UncoupledCorrectionsTieBeamsToTheSolversTolerance) {
  // NearestPointROI.scn's settings: compliance 1, no ODE factors, the unbuilt solver.
  const std::string uncoupled = "<UncoupledConstraintCorrection defaultCompliance=\"1\" useOdeSolverIntegrationFactors=\"0\"/>";
  std::string body = "<FreeMotionAnimationLoop/><UnbuiltGaussSeidelConstraintSolver tolerance=\"1e-10\" maxIterations=\"1000\"/>" +
                     beam("A", 0, kLeftEnd + "<FixedProjectiveConstraint indices=\"@box.indices\"/>" + uncoupled) + beam("B", 1, uncoupled) +
                     "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"@B/dofs\" first_point=\"5 11 17 23\" second_point=\"0 6 12 18\"/>";
  LoadedScene scene = build_scene_text(body, kRoot);
  // The tied points move together; the rest of each beam feels the constraint only through its
  // elasticity in later steps (a diagonal compliance), so B swings lower than under LinearSolver.
  expect_tied(scene, 100, 1e-8, false, 2.0);
}

TEST(LagrangianScene, UnbuiltSolverReadsUncoupledComplianceWithoutTheOdeFactorAsSofa) {
  // A point (mass 1, no gravity, compliance 0.5) one unit from a still target it is tied to. Built
  // W = h c: one step closes the gap (x = 0). SOFA's unbuilt Gauss–Seidel reads c without h, so
  // λ = -δ / c and the correction x_f + h c λ closes only h of it: x = 1 - h, v = -1.
  const auto run = [](const std::string& solver, std::vector<std::string>* warnings) {
    LoadedScene scene = build_scene_text(
        "<FreeMotionAnimationLoop/>" + solver +
            "<Node name=\"target\"><MechanicalObject name=\"point\" position=\"0 0 0\"/></Node>"
            "<Node name=\"bob\"><EulerImplicitSolver rayleighMass=\"0\" rayleighStiffness=\"0\"/><CGLinearSolver/>"
            "<MechanicalObject name=\"point\" position=\"1 0 0\"/><UniformMass totalMass=\"1\"/>"
            "<UncoupledConstraintCorrection defaultCompliance=\"0.5\"/></Node>"
            "<BilateralLagrangianConstraint object1=\"@target/point\" object2=\"@bob/point\" first_point=\"0\" second_point=\"0\"/>",
        "dt=\"0.01\" gravity=\"0 0 0\"");
    scene.simulation.step();
    if (warnings) *warnings = scene.warnings;
    return std::make_pair(scene.simulation.objects[0].system.state.position[0], scene.simulation.objects[0].system.state.velocity[0]);
  };
  const auto built = run("<BlockGaussSeidelConstraintSolver tolerance=\"1e-14\"/>", nullptr);
  EXPECT_NEAR(built.first.x(), 0.0, 1e-12);
  std::vector<std::string> warnings;
  const auto unbuilt = run("<UnbuiltGaussSeidelConstraintSolver tolerance=\"1e-14\"/>", &warnings);
  EXPECT_NEAR(unbuilt.first.x(), 1 - 0.01, 1e-12);
  EXPECT_NEAR(unbuilt.second.x(), -1.0, 1e-12);
  bool warned = false;
  for (const auto& line : warnings) warned = warned || line.find("without the ODE factor h") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(LagrangianScene, OneAndTwoThreadsGiveTheSameBits) {
  const std::string body =
      tied_beams("<LinearSolverConstraintCorrection/>", "<BlockGaussSeidelConstraintSolver maxIterations=\"50\" tolerance=\"1e-6\"/>");
  LoadedScene one = build_scene_text(body, kRoot);
  LoadedScene two = build_scene_text(body, kRoot);
  two.simulation.threads = 2;
  for (int step = 0; step < 40; ++step) {
    one.simulation.step();
    two.simulation.step();
  }
  for (std::size_t o = 0; o < 2; ++o) {
    EXPECT_EQ(one.simulation.objects[o].system.state.position, two.simulation.objects[o].system.state.position);
    EXPECT_EQ(one.simulation.objects[o].system.state.velocity, two.simulation.objects[o].system.state.velocity);
  }
}

TEST(LagrangianScene, AnUnconvergedSolveIsReported) {
  LoadedScene scene = build_scene_text(
      tied_beams("<LinearSolverConstraintCorrection/>", "<BlockGaussSeidelConstraintSolver maxIterations=\"1\" tolerance=\"1e-14\"/>"), kRoot);
  scene.simulation.step();
  const ConstraintReport& report = scene.simulation.constraint_report();
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_GT(report.error, report.tolerance);
}

TEST(LagrangianScene, GenericConstraintSolverRunsAsItsReplacementWithAWarning) {
  const std::string fixed = beam("beam", 0, kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>");
  LoadedScene generic = build_scene_text("<FreeMotionAnimationLoop/><GenericConstraintSolver maxIt=\"40\" tolerance=\"1e-9\"/>" + fixed, kRoot);
  LoadedScene block =
      build_scene_text("<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"40\" tolerance=\"1e-9\"/>" + fixed, kRoot);
  bool warned = false;
  for (const auto& line : generic.warnings) warned = warned || line.find("BlockGaussSeidelConstraintSolver") != std::string::npos;
  EXPECT_TRUE(warned);
  for (int step = 0; step < 20; ++step) {
    generic.simulation.step();
    block.simulation.step();
  }
  EXPECT_EQ(generic.simulation.objects[0].system.state.position, block.simulation.objects[0].system.state.position);
}

TEST(LagrangianScene, GenericConstraintSolverWithNncgTakesNewtonIterations) {
  const std::string fixed = beam("beam", 0, kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>");
  LoadedScene generic = build_scene_text("<FreeMotionAnimationLoop/><GenericConstraintSolver resolutionMethod=\"NonsmoothNonlinearConjugateGradient\" "
                                         "newtonIterations=\"7\" maxIterations=\"500\" tolerance=\"1e-14\"/>" + fixed, kRoot);
  LoadedScene nncg = build_scene_text("<FreeMotionAnimationLoop/><NNCGConstraintSolver maxIterations=\"7\" tolerance=\"1e-14\"/>" + fixed, kRoot);
  LoadedScene projective = build_scene_text(beam("beam", 0, kLeftEnd + "<FixedProjectiveConstraint indices=\"@box.indices\"/>"), kRoot);
  for (int step = 0; step < 20; ++step) {
    generic.simulation.step();
    nncg.simulation.step();
    projective.simulation.step();
  }
  EXPECT_EQ(generic.simulation.constraint_report().iterations, 7);
  EXPECT_EQ(generic.simulation.objects[0].system.state.position, nncg.simulation.objects[0].system.state.position);
  // Seven sweeps a step on a fixed end (warm-started): the projective trajectory to a few micrometres.
  EXPECT_LT(max_difference(nncg.simulation.objects[0].system.state.position, projective.simulation.objects[0].system.state.position), 1e-5);
}

TEST(LagrangianScene, FreePositionsFollowTheDampedVelocityAsInSofa) {
  // SOFA's free motion ends with x_free = x + dt v_free: with vdamping the velocity is damped after
  // the ODE's position update, and the loop's positions follow the damped velocity.
  LoadedScene scene = build_scene_text(
      "<FreeMotionAnimationLoop/><Node name=\"p\"><EulerImplicitSolver vdamping=\"5\"/><SparseLDLSolver/>"
      "<MechanicalObject name=\"dofs\" position=\"0 0 0\" velocity=\"1 2 0\"/><UniformMass vertexMass=\"1\"/>"
      "<LinearSolverConstraintCorrection/></Node>",
      kRoot);
  const auto& state = scene.simulation.objects[0].system.state;
  for (int step = 0; step < 5; ++step) {
    const Vec3<double> x = state.position[0];
    scene.simulation.step();
    EXPECT_EQ(state.position[0], Vec3<double>(x + 0.01 * state.velocity[0])) << step;
  }
}

TEST(LagrangianScene, PreconditionedCgCorrectionsLeaveItsWarmStartAlone) {
  // LinearSolverConstraintCorrection through a PCG (iterative): its extra solves for W and the
  // correction leave the next free motion's guess and count as they were, so two tied beams
  // under PCG agree with the same beams under a direct solver to the solvers' tolerance.
  const std::string pcg = "<PCGLinearSolver iterations=\"500\" tolerance=\"1e-20\" preconditioner=\"@p\"/><SparseLDLSolver name=\"p\"/>";
  const auto tied = [&](const std::string& linear) {
    return "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"1000\" tolerance=\"1e-12\"/>" +
           beam("A", 0, kLeftEnd + "<FixedProjectiveConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>", linear) +
           beam("B", 1, "<LinearSolverConstraintCorrection/>", linear) +
           "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"@B/dofs\" first_point=\"5 11 17 23\" second_point=\"0 6 12 18\"/>";
  };
  LoadedScene iterative = build_scene_text(tied(pcg), kRoot);
  LoadedScene direct = build_scene_text(tied("<SparseLDLSolver/>"), kRoot);
  for (int step = 0; step < 30; ++step) {
    iterative.simulation.step();
    direct.simulation.step();
  }
  for (std::size_t o = 0; o < 2; ++o) {
    EXPECT_LT(max_difference(iterative.simulation.objects[o].system.state.position, direct.simulation.objects[o].system.state.position), 1e-8);
  }
}

TEST(LagrangianScene, RefusesWhatCannotBeSolved) {
  const std::string fixed = kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/>";
  // A matrix-free linear solver under LinearSolverConstraintCorrection (SOFA's GraphScattered).
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" + beam("beam", 0, fixed + "<LinearSolverConstraintCorrection/>", "<CGLinearSolver/>"))
                .find("matrix-free"),
            std::string::npos);
  // An assembled CG template is accepted.
  EXPECT_EQ(scene_error("<FreeMotionAnimationLoop/>" + beam("beam", 0, fixed + "<LinearSolverConstraintCorrection/>",
                                                            "<CGLinearSolver template=\"CompressedRowSparseMatrixMat3x3d\"/>")),
            "");
  // No correction on the object a constraint acts on.
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" + beam("beam", 0, fixed)).find("no constraint correction"), std::string::npos);
  // A constraint between two states no solver integrates: nothing can move.
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" + beam("A", 0, "<LinearSolverConstraintCorrection/>") +
                        "<Node name=\"loose\"><MechanicalObject name=\"p\" position=\"0 0 0\"/></Node>"
                        "<Node name=\"other\"><MechanicalObject name=\"p\" position=\"1 0 0\"/></Node>"
                        "<BilateralLagrangianConstraint object1=\"@other/p\" object2=\"@loose/p\" first_point=\"0\" second_point=\"0\"/>")
                .find("both unsimulated"),
            std::string::npos);
  // A still-looking point that a RigidMapping takes from a rigid an ODE solver moves, from outside
  // that solver's node: not followed here, so refused rather than held.
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" + beam("A", 0, "<LinearSolverConstraintCorrection/>") +
                        "<Node name=\"R\"><EulerImplicitSolver/><CGLinearSolver/><MechanicalObject name=\"frame\" template=\"Rigid3\"/>"
                        "<UniformMass totalMass=\"1\"/><UncoupledConstraintCorrection/></Node>"
                        "<Node name=\"carried\"><MechanicalObject name=\"p\" position=\"0 0 0\"/><RigidMapping input=\"@../R/frame\"/></Node>"
                        "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"@carried/p\" first_point=\"0\" second_point=\"0\"/>")
                .find("which an ODE solver moves"),
            std::string::npos);
  // An index out of range, a non-finite rest vector.
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" +
                        beam("beam", 0, "<FixedLagrangianConstraint indices=\"24\"/><LinearSolverConstraintCorrection/>"))
                .find("out of range"),
            std::string::npos);
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" + beam("A", 0, "<LinearSolverConstraintCorrection/>") +
                        "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"@A/dofs\" first_point=\"0\" second_point=\"1\" "
                        "rest_vector=\"nan 0 0\"/>")
                .find("rest_vector"),
            std::string::npos);
  // Mixed kinds of correction on one object.
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/>" +
                        beam("beam", 0, fixed + "<LinearSolverConstraintCorrection/><UncoupledConstraintCorrection defaultCompliance=\"1\"/>"))
                .find("one kind of correction"),
            std::string::npos);
  // Two MechanicalObjects under one solver, only the second with an UncoupledConstraintCorrection:
  // a constraint on the first would have no compliance.
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/><Node name=\"both\"><EulerImplicitSolver/><CGLinearSolver/>"
                        "<Node name=\"a\"><MechanicalObject name=\"p\" position=\"0 0 0\"/><UniformMass vertexMass=\"1\"/></Node>"
                        "<Node name=\"b\"><MechanicalObject name=\"p\" position=\"1 0 0\"/><UniformMass vertexMass=\"1\"/>"
                        "<UncoupledConstraintCorrection defaultCompliance=\"1\"/></Node></Node>"
                        "<BilateralLagrangianConstraint object1=\"@both/a/p\" object2=\"@both/b/p\" first_point=\"0\" second_point=\"0\"/>")
                .find("needs its own"),
            std::string::npos);
}

TEST(LagrangianScene, BilateralConstraintTiesAPointToAStateNoSolverMoves) {
  // SOFA's BilateralLagrangianConstraint_PGS and regularization scenes: a simulated point tied to a
  // MechanicalObject without ODE solver, which stays where the scene puts it. The beam's point 0
  // (at the origin) is tied to (0, 0.05, 0): it is lifted there and held while the beam sags. The
  // anchor written directly, or carried by a still rigid at (0, 0.02, 0) turned 90° about z from
  // local coordinates (0.03, 0, 0) (SOFA's RigidMapping places it in the rigid's frame).
  const std::string anchors[] = {
      "<Node name=\"anchor\"><MechanicalObject name=\"p\" position=\"0 0.05 0\"/></Node>",
      "<Node name=\"frame\"><MechanicalObject template=\"Rigid3\" position=\"0 0.02 0 0 0 0.70710678118654752 0.70710678118654752\"/>"
      "<Node name=\"anchor\"><MechanicalObject name=\"p\" position=\"0.03 0 0\"/><RigidMapping/></Node></Node>"};
  for (const std::string& anchor : anchors) {
    const std::string link = anchor.find("frame") != std::string::npos ? "@frame/anchor/p" : "@anchor/p";
    LoadedScene scene = build_scene_text(
        "<FreeMotionAnimationLoop/><BlockGaussSeidelConstraintSolver maxIterations=\"1000\" tolerance=\"1e-12\"/>" +
            beam("A", 0, "<LinearSolverConstraintCorrection/>") + anchor +
            "<BilateralLagrangianConstraint object1=\"@A/dofs\" object2=\"" + link + "\" first_point=\"0\" second_point=\"0\"/>",
        kRoot);
    bool told = false;
    for (const auto& line : scene.info) told = told || line.find("is not simulated (no ODE solver): its points stay put") != std::string::npos;
    EXPECT_TRUE(told) << link;
    const auto& state = scene.simulation.objects[0].system.state;
    for (int step = 0; step < 100; ++step) scene.simulation.step();
    EXPECT_LT((state.position[0] - Vec3<double>(0, 0.05, 0)).norm(), 1e-9) << link;
    EXPECT_LT(state.position[5].y(), -0.05) << "the rest of the beam falls";
    EXPECT_EQ(scene.simulation.constraint_report().rows, 3);
  }
}

TEST(LagrangianScene, LcpSolverWarnsThatItSolvesRowsAsContacts) {
  // SOFA's LCPConstraintSolver ignores the constraints' resolutions: a fixed point's three rows are
  // one frictional contact to it (x the normal). Run, with the warning that says so.
  const std::string fixed = kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>";
  LoadedScene scene = build_scene_text(
      "<FreeMotionAnimationLoop/><LCPConstraintSolver mu=\"0.3\" maxIt=\"50\" tolerance=\"1e-6\"/>" + beam("beam", 0, fixed), kRoot);
  bool warned = false;
  for (const auto& line : scene.warnings) warned = warned || line.find("solves every row as a contact") != std::string::npos;
  EXPECT_TRUE(warned);
  scene.simulation.step();
  const ConstraintReport& report = scene.simulation.constraint_report();
  EXPECT_EQ(report.rows, 12);
  EXPECT_DOUBLE_EQ(report.tolerance, 1e-6 * (4 + 1)) << "SOFA's LCP tolerance: tol × (contacts + 1)";
  EXPECT_EQ(scene.simulation.constraints->solver_name(), std::string("LCPConstraintSolver"));
  EXPECT_NE(scene_error("<FreeMotionAnimationLoop/><LCPConstraintSolver mu=\"-1\"/>" + beam("beam", 0, fixed)).find("mu = -1"),
            std::string::npos);
}

TEST(LagrangianScene, ImprovedJacobiHoldsAFixedPointAsGaussSeidelDoes) {
  // One held point: one block, which Jacobi solves as Gauss–Seidel does.
  LoadedScene jacobi = build_scene_text(
      "<FreeMotionAnimationLoop/><ImprovedJacobiConstraintSolver maxIterations=\"100\" tolerance=\"1e-14\"/>" +
          beam("beam", 0, "<FixedLagrangianConstraint indices=\"0\"/><LinearSolverConstraintCorrection/>"),
      kRoot);
  LoadedScene projective = build_scene_text(beam("beam", 0, "<FixedProjectiveConstraint indices=\"0\"/>"), kRoot);
  for (int step = 1; step <= 20; ++step) {
    jacobi.simulation.step();
    projective.simulation.step();
    ASSERT_LT(max_difference(jacobi.simulation.objects[0].system.state.position, projective.simulation.objects[0].system.state.position), 1e-9)
        << "step " << step;
  }
  EXPECT_TRUE(jacobi.simulation.constraint_report().converged);
  // Four neighbouring points: their blocks are coupled more than Jacobi tolerates; the run stops
  // naming the solver rather than carrying infinities.
  LoadedScene coupled = build_scene_text(
      "<FreeMotionAnimationLoop/><ImprovedJacobiConstraintSolver maxIterations=\"20000\" tolerance=\"1e-14\"/>" +
          beam("beam", 0, kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>"),
      kRoot);
  try {
    coupled.simulation.step();
    FAIL() << "Jacobi diverges on these blocks";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ImprovedJacobiConstraintSolver: the constraint impulses are not finite"), std::string::npos) << e.what();
  }
}

TEST(LagrangianScene, CheckpointsAreRefusedWithTheReason) {
  LoadedScene scene = build_scene_text(
      "<FreeMotionAnimationLoop/>" + beam("beam", 0, kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>"),
      kRoot);
  scene.simulation.step();
  const auto path = std::filesystem::temp_directory_path() / ("fastcorot_lagrangian_checkpoint_" + std::to_string(::getpid()) + ".bin");
  try {
    write_checkpoint(path, scene.simulation, "test.scn");
    FAIL() << "written";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("Lagrangian constraints"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(LagrangianScene, WithoutTheLoopLagrangianComponentsAreReportedUnused) {
  LoadedScene scene = build_scene_text(beam("beam", 0, kLeftEnd + "<FixedLagrangianConstraint indices=\"@box.indices\"/><LinearSolverConstraintCorrection/>"), kRoot);
  EXPECT_FALSE(scene.simulation.constraints);
  bool said = false;
  for (const auto& line : scene.info) said = said || line.find("no FreeMotionAnimationLoop") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace fastcorot
