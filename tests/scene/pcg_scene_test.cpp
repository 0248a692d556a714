// Scenes with SOFA's PCGLinearSolver, its Jacobi / block-Jacobi preconditioners and SOFA master's
// linear systems around them, and how an ODE solver picks its linear solver, through the real parser
// and builder.
#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"
#include "fastcorot/sim/sparse_direct_solver.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <limits>
#include <string>

namespace fastcorot {
namespace {

using PCG = PreconditionedConjugateGradientSolver<double>;

const std::string kEuler = R"(<EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>)";

// Two hexahedral cells along x split into 12 tetrahedra, fixed at x = 0; `solvers` in place of
// the linear solver.
std::string beam(const std::string& solvers, const std::string& integrator = kEuler) {
  return R"(<Node name="root" dt="0.02" gravity="0 0 -5"><Node name="beam">
    )" + integrator + solvers + R"(
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

LoadedScene build(const std::string& solvers, const std::string& integrator = kEuler) {
  return build_scene(parse_scene_text(beam(solvers, integrator), "pcg.scn"));
}

const PCG& pcg_of(const LoadedScene& scene) {
  const auto* solver = dynamic_cast<const PCG*>(scene.simulation.objects.at(0).linear_solver.get());
  if (!solver) throw make_error("not a PCG");
  return *solver;
}

std::string error_of(const std::string& solvers, const std::string& integrator = kEuler) {
  try {
    build(solvers, integrator);
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

TEST(PcgScene, SparseDirectSolversPreconditionWithTheirFactorisation) {
  // SOFA's common form: the direct solver first would be the ODE solver's linear solver (the first
  // one found), so scenes link the PCG or list it first.
  for (const std::string direct : {"SparseLDLSolver", "EigenSimplicialLDLT", "SparseCholeskySolver"}) {
    const auto p = pcg_of(build(R"(<PCGLinearSolver iterations="5" preconditioner="@L" update_step="10"/>
      <)" + direct + R"( name="L" template="CompressedRowSparseMatrixMat3x3d"/>)"))
                       .parameters();
    EXPECT_EQ(p.preconditioner, Preconditioner::sparse_ldlt) << direct;
    EXPECT_EQ(p.update_step, 10);
  }
  // SOFA master's form, as in its examples: the PCG linked by the ODE solver, a MatrixLinearSystem
  // for the direct solver, the rate on the PreconditionedMatrixFreeSystem.
  const LoadedScene master = build(R"(<MatrixLinearSystem name="PS" template="CompressedRowSparseMatrixMat3x3d"/>
    <SparseLDLSolver name="L" linearSystem="@PS"/>
    <PreconditionedMatrixFreeSystem name="S" preconditionerSystem="@PS" assemblingRate="4"/>
    <PCGLinearSolver name="pcg" linearSystem="@S" preconditioner="@L"/>)",
                                   R"(<EulerImplicitSolver linearSolver="@pcg"/>)");
  EXPECT_EQ(pcg_of(master).parameters().preconditioner, Preconditioner::sparse_ldlt);
  EXPECT_EQ(pcg_of(master).parameters().update_step, 4);
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
      error_of(R"(<PCGLinearSolver preconditioner="@C"/><CGLinearSolver name="C"/>)");
  EXPECT_NE(unsupported.find("pcg.scn:2: PCGLinearSolver: preconditioner pcg.scn:2: CGLinearSolver 'C' is not supported"),
            std::string::npos) << unsupported;
  EXPECT_NE(unsupported.find("supported: BlockJacobiPreconditioner, JacobiPreconditioner, SSORPreconditioner, WarpPreconditioner, "
                                 "PrecomputedWarpPreconditioner, a sparse direct solver"),
            std::string::npos)
      << unsupported;
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

TEST(PcgScene, PrecomputedWarpPreconditionerIsBuiltAndConverges) {
  const std::string warp = R"(<PCGLinearSolver iterations="200" tolerance="1e-26" preconditioner="@W"/>
    <PrecomputedMatrixSystem name="PS"/><MatrixLinearSystem name="LS"/><NaturalOrderingMethod/>
    <SparseLDLSolver name="init" linearSystem="@LS"/>
    <PrecomputedWarpPreconditioner name="W" linearSystem="@PS" linearSolver="@init")";
  LoadedScene pcg = build(warp + "/>");
  EXPECT_EQ(pcg_of(pcg).parameters().preconditioner, Preconditioner::precomputed_warp);
  EXPECT_TRUE(pcg_of(pcg).parameters().warp_rotations);
  // Without a TetrahedronFEMForceField, R is the identity, and the info line says so.
  EXPECT_NE(std::find_if(pcg.info.begin(), pcg.info.end(), [](const std::string& line) {
              return line.find("R is the identity") != std::string::npos;
            }), pcg.info.end());
  EXPECT_FALSE(pcg_of(build(warp + " use_rotations=\"false\"/>")).parameters().warp_rotations);
  LoadedScene direct = build("<EigenSimplicialLDLT/>");
  for (int step = 0; step < 5; ++step) {
    direct.simulation.step();
    pcg.simulation.step();
  }
  double difference = 0;
  for (std::size_t i = 0; i < 12; ++i) {
    difference = std::max(difference, (direct.simulation.objects[0].system.state.position[i] -
                                       pcg.simulation.objects[0].system.state.position[i]).norm());
  }
  EXPECT_LT(difference, 1e-10);
  const std::string wrong = error_of(R"(<PCGLinearSolver preconditioner="@W"/><CGLinearSolver name="C"/>
    <PrecomputedWarpPreconditioner name="W" linearSolver="@C"/>)");
  EXPECT_NE(wrong.find("linearSolver must link a sparse direct solver"), std::string::npos) << wrong;
}

// SOFA master moves the rebuild period to the PCG's linear system, a PreconditionedMatrixFreeSystem
// (assemblingRate, alias update_step), and gives the preconditioner a MatrixLinearSystem.
TEST(PcgScene, MasterLinearSystemsGiveTheRebuildPeriod) {
  const std::string preconditioner = R"(<MatrixLinearSystem name="PS" template="CompressedRowSparseMatrixMat3x3d"/>
    <BlockJacobiPreconditioner name="P" linearSystem="@PS"/>)";
  auto p = pcg_of(build(preconditioner + R"(<PreconditionedMatrixFreeSystem name="S" template="GraphScattered"
      preconditionerSystem="@PS" assemblingRate="3"/>
    <PCGLinearSolver iterations="4" linearSystem="@S" preconditioner="@P"/>)")).parameters();
  EXPECT_EQ(p.preconditioner, Preconditioner::block_jacobi);
  EXPECT_EQ(p.iterations, 4);
  EXPECT_EQ(p.update_step, 3);
  // Found without a link; the older attribute name on the system.
  p = pcg_of(build(preconditioner + R"(<PreconditionedMatrixFreeSystem update_step="5"/>
    <PCGLinearSolver preconditioner="@P"/>)")).parameters();
  EXPECT_EQ(p.update_step, 5);
  // A system without a rate keeps the PCG's own (older scenes), or SOFA's default of 1.
  EXPECT_EQ(pcg_of(build(R"(<PreconditionedMatrixFreeSystem/><PCGLinearSolver update_step="4"/>)")).parameters().update_step, 4);
  EXPECT_EQ(pcg_of(build(R"(<PreconditionedMatrixFreeSystem/><PCGLinearSolver/>)")).parameters().update_step, 1);
  // The same period given twice, consistently.
  EXPECT_EQ(pcg_of(build(R"(<PreconditionedMatrixFreeSystem assemblingRate="2"/><PCGLinearSolver update_step="2"/>)"))
                .parameters()
                .update_step,
            2);
}

TEST(PcgScene, MisplacedLinearSystemsAreNamed) {
  const std::string not_preconditioned =
      error_of(R"(<MatrixLinearSystem name="M"/><PCGLinearSolver linearSystem="@M"/>)");
  EXPECT_NE(not_preconditioned.find("pcg.scn:2: PCGLinearSolver: linearSystem must link a PreconditionedMatrixFreeSystem, "
                                    "not pcg.scn:2: MatrixLinearSystem 'M'"),
            std::string::npos)
      << not_preconditioned;
  const std::string wrong_system = error_of(
      R"(<PreconditionedMatrixFreeSystem name="S"/><JacobiPreconditioner name="J" linearSystem="@S"/><PCGLinearSolver preconditioner="@J"/>)");
  EXPECT_NE(wrong_system.find("JacobiPreconditioner 'J': linearSystem must link a MatrixLinearSystem, not "
                              "pcg.scn:2: PreconditionedMatrixFreeSystem 'S'"),
            std::string::npos)
      << wrong_system;
  const std::string wrong_preconditioner_system =
      error_of(R"(<PreconditionedMatrixFreeSystem name="S" preconditionerSystem="@S"/><PCGLinearSolver/>)");
  EXPECT_NE(wrong_preconditioner_system.find("preconditionerSystem must link a MatrixLinearSystem"), std::string::npos)
      << wrong_preconditioner_system;
  const std::string disagree =
      error_of(R"(<PreconditionedMatrixFreeSystem name="S" assemblingRate="3"/><PCGLinearSolver update_step="2"/>)");
  EXPECT_NE(disagree.find("PCGLinearSolver: update_step = 2 disagrees with pcg.scn:2: PreconditionedMatrixFreeSystem 'S''s "
                          "assemblingRate = 3"),
            std::string::npos)
      << disagree;
  const std::string twice =
      error_of(R"(<PreconditionedMatrixFreeSystem assemblingRate="3" update_step="3"/><PCGLinearSolver/>)");
  EXPECT_NE(twice.find("assemblingRate and update_step name the same value"), std::string::npos) << twice;
  const std::string rate = error_of(R"(<PreconditionedMatrixFreeSystem assemblingRate="0"/><PCGLinearSolver/>)");
  EXPECT_NE(rate.find("pcg.scn:2: PreconditionedMatrixFreeSystem: assemblingRate = 0: must be >= 1"), std::string::npos)
      << rate;
}

// SOFA's LinearSolverAccessor: the linearSolver link, else the first linear solver found.
TEST(LinearSolverChoice, TheLinkOtherwiseTheFirstWithAnInfoLine) {
  const std::string two = R"(<EigenSimplicialLDLT name="L"/><CGLinearSolver name="C" iterations="7"/>)";
  const LoadedScene first = build(two);
  EXPECT_NE(dynamic_cast<const SparseDirectSolver<double>*>(first.simulation.objects.at(0).linear_solver.get()), nullptr);
  bool told = false;
  for (const auto& line : first.info) {
    told = told || line.find("EulerImplicitSolver: uses the first linear solver, pcg.scn:2: EigenSimplicialLDLT 'L'; "
                             "not used: pcg.scn:2: CGLinearSolver 'C'") != std::string::npos;
  }
  EXPECT_TRUE(told);
  const LoadedScene linked =
      build(two, R"(<EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1" linearSolver="@C"/>)");
  const auto* cg = dynamic_cast<const ConjugateGradientSolver<double>*>(linked.simulation.objects.at(0).linear_solver.get());
  ASSERT_NE(cg, nullptr);
  EXPECT_EQ(cg->parameters().iterations, 7);
  // A StaticSolver takes the link from itself or from the NewtonRaphsonSolver it drives (SOFA master).
  const auto takes_cg = [&](const std::string& integrator) {
    const LoadedScene scene = build(two, integrator);
    return dynamic_cast<const ConjugateGradientSolver<double>*>(scene.simulation.objects.at(0).linear_solver.get()) != nullptr;
  };
  EXPECT_TRUE(takes_cg(R"(<StaticSolver linearSolver="@C"/>)"));
  EXPECT_TRUE(takes_cg(R"(<StaticSolver newtonSolver="@N"/><NewtonRaphsonSolver name="N" linearSolver="@C"/>)"));
  EXPECT_FALSE(takes_cg(R"(<StaticSolver/><NewtonRaphsonSolver name="N"/>)"));
}

TEST(LinearSolverChoice, ALinkToSomethingElseIsNamed) {
  const std::string not_a_solver = error_of(R"(<BlockJacobiPreconditioner name="P"/><CGLinearSolver/>)",
                                            R"(<EulerImplicitSolver linearSolver="@P"/>)");
  EXPECT_NE(not_a_solver.find("pcg.scn:2: EulerImplicitSolver: linearSolver must link a linear solver (CGLinearSolver, "
                              "PCGLinearSolver, EigenSimplicialLDLT, ...), not pcg.scn:2: BlockJacobiPreconditioner 'P'"),
            std::string::npos)
      << not_a_solver;
  const std::string broken = error_of("<CGLinearSolver/>", R"(<EulerImplicitSolver linearSolver="@nothing"/>)");
  EXPECT_NE(broken.find("broken link '@nothing'"), std::string::npos) << broken;
}

}  // namespace
}  // namespace fastcorot
