// Scenes with SOFA's PCGLinearSolver and its Jacobi / block-Jacobi preconditioners, through the real
// parser and builder.
#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace fastcorot {
namespace {

using PCG = PreconditionedConjugateGradientSolver<double>;

// Two hexahedral cells along x split into 12 tetrahedra, fixed at x = 0; `solvers` in place of
// the linear solver.
std::string beam(const std::string& solvers) {
  return R"(<Node name="root" dt="0.02" gravity="0 0 -5"><Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>)" +
         solvers + R"(
    <RegularGridTopology name="grid" n="3 2 2" min="0 0 0" max="2 1 1"/>
    <MechanicalObject name="state"/>
    <TetrahedronSetTopologyContainer name="tets"/>
    <Hexa2TetraTopologicalMapping input="@grid" output="@tets" swapping="true"/>
    <DiagonalMass massDensity="2"/>
    <FastTetrahedralCorotationalForceField youngModulus="1000" poissonRatio="0.3" method="large"/>
    <BoxROI name="roi" box="-0.5 -1 -1 0.5 2 2"/>
    <FixedProjectiveConstraint indices="@roi.indices"/>
  </Node></Node>)";
}

LoadedScene build(const std::string& solvers) { return build_scene(parse_scene_text(beam(solvers), "pcg.scn")); }

const PCG& pcg_of(const LoadedScene& scene) {
  const auto* solver = dynamic_cast<const PCG*>(scene.simulation.objects.at(0).linear_solver.get());
  if (!solver) throw make_error("not a PCG");
  return *solver;
}

std::string error_of(const std::string& solvers) {
  try {
    build(solvers);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(PcgScene, AttributesAndTheLinkedPreconditioner) {
  // The preconditioner may come first: only the PCG is the ODE solver's linear solver.
  const LoadedScene scene = build(R"(<BlockJacobiPreconditioner name="P"/>
    <PCGLinearSolver iterations="40" tolerance="1e-9" preconditioner="@P" update_step="3"/>)");
  const auto& p = pcg_of(scene).parameters();
  EXPECT_EQ(p.preconditioner, Preconditioner::block_jacobi);
  EXPECT_EQ(p.iterations, 40);
  EXPECT_EQ(p.tolerance, 1e-9);
  EXPECT_EQ(p.update_step, 3);
}

TEST(PcgScene, DefaultsOlderLinkFormAndSwitches) {
  auto p = pcg_of(build("<PCGLinearSolver/>")).parameters();
  EXPECT_EQ(p.preconditioner, Preconditioner::none);
  EXPECT_EQ(p.iterations, 25);
  EXPECT_EQ(p.tolerance, 1e-5);
  EXPECT_EQ(p.update_step, 1);
  p = pcg_of(build(R"(<PCGLinearSolver preconditioners="J"/><JacobiPreconditioner name="J"/>)")).parameters();
  EXPECT_EQ(p.preconditioner, Preconditioner::jacobi);
  p = pcg_of(build(R"(<PCGLinearSolver preconditioner="@J" use_precond="false"/><JacobiPreconditioner name="J"/>)")).parameters();
  EXPECT_EQ(p.preconditioner, Preconditioner::none);
  p = pcg_of(build(R"(<PCGLinearSolver preconditioner="@J" build_precond="false"/><JacobiPreconditioner name="J"/>)")).parameters();
  EXPECT_EQ(p.update_step, std::numeric_limits<int>::max());
}

TEST(PcgScene, UnsupportedOrMissingPreconditionersAreNamed) {
  const std::string unsupported =
      error_of(R"(<PCGLinearSolver preconditioner="@L"/><EigenSimplicialLDLT name="L"/>)");
  EXPECT_NE(unsupported.find("pcg.scn:2: PCGLinearSolver: preconditioner pcg.scn:2: EigenSimplicialLDLT 'L' is not supported"),
            std::string::npos) << unsupported;
  EXPECT_NE(unsupported.find("supported: BlockJacobiPreconditioner, JacobiPreconditioner"), std::string::npos) << unsupported;
  const std::string missing = error_of(R"(<PCGLinearSolver preconditioner="@nothing"/>)");
  EXPECT_NE(missing.find("broken link '@nothing'"), std::string::npos) << missing;
  const std::string bad = error_of(R"(<PCGLinearSolver iterations="0"/>)");
  EXPECT_NE(bad.find("iterations = 0"), std::string::npos) << bad;
  // Counts are whole numbers that fit (no silent truncation or overflow).
  const std::string huge = error_of(R"(<PCGLinearSolver iterations="1e20"/>)");
  EXPECT_NE(huge.find("pcg.scn:2: PCGLinearSolver: iterations = 1e+20: expected a whole number"), std::string::npos) << huge;
  const std::string fraction = error_of(R"(<PCGLinearSolver update_step="2.5"/>)");
  EXPECT_NE(fraction.find("update_step = 2.5: expected a whole number"), std::string::npos) << fraction;
}

TEST(PcgScene, ConvergedStepsMatchTheDirectSolver) {
  LoadedScene direct = build("<EigenSimplicialLDLT/>");
  LoadedScene pcg = build(R"(<PCGLinearSolver iterations="200" tolerance="1e-26" preconditioner="@P"/>
    <BlockJacobiPreconditioner name="P"/>)");
  for (int step = 0; step < 5; ++step) {
    direct.simulation.step();
    pcg.simulation.step();
  }
  const auto& a = direct.simulation.objects[0].system.state.position;
  const auto& b = pcg.simulation.objects[0].system.state.position;
  double moved = 0, difference = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    moved = std::max(moved, (a[i] - direct.simulation.objects[0].system.state.rest_position[i]).norm());
    difference = std::max(difference, (a[i] - b[i]).norm());
  }
  EXPECT_GT(moved, 1e-4);
  EXPECT_LT(difference, 1e-9 * moved);
}

}  // namespace
}  // namespace fastcorot
