// Scenes with SOFA's MinResLinearSolver, PrecomputedLinearSolver, SSORPreconditioner,
// WarpPreconditioner (with RotationMatrixSystem) and GlobalSystemMatrixImage, through the real
// parser and builder: their attributes, their errors, and trajectories against the sparse direct
// solver's (SOFA's FEMBAR regression scenes compare at 1e-8).
#include "fastcorot/core/error.h"
#include "fastcorot/scene/scene_builder.h"
#include "fastcorot/sim/minres_solver.h"
#include "fastcorot/sim/precomputed_linear_solver.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"
#include "fastcorot/sim/sparse_direct_solver.h"
#include "fastcorot/sim/ssor_preconditioner.h"
#include "fastcorot/sim/warp_preconditioner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace fastcorot {
namespace {

// SOFA's FEMBAR beam, shortened: a 3 × 3 × 6 grid of HexahedronFEMForceField cells fixed at z = 0.
std::string beam(const std::string& solvers, const std::string& field = "HexahedronFEMForceField") {
  return R"(<Node name="root" dt="0.02" gravity="0 -10 0">
    <EulerImplicitSolver name="odesolver" rayleighStiffness="0.1" rayleighMass="0.1"/>
    <MechanicalObject name="DoFs"/>
    <UniformMass name="mass" totalMass="100"/>
    <RegularGridTopology name="grid" nx="3" ny="3" nz="6" xmin="-9" xmax="-6" ymin="0" ymax="3" zmin="0" zmax="8"/>
    <BoxROI name="box" box="-10 -1 -0.0001  -5 4 0.0001"/>
    <FixedProjectiveConstraint indices="@box.indices"/>
    )" + solvers + R"(
    <)" + field + R"( name="FEM" youngModulus="4000" poissonRatio="0.3" method="large"/>
  </Node>)";
}

LoadedScene build(const std::string& solvers, const std::string& field = "HexahedronFEMForceField") {
  return build_scene(parse_scene_text(beam(solvers, field), "solvers.scn"));
}

std::string error_of(const std::string& solvers) {
  try {
    build(solvers);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

bool has_line(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; });
}

// The largest distance between the two scenes' points over `steps` steps.
double trajectory_difference(LoadedScene& a, LoadedScene& b, int steps) {
  double difference = 0;
  for (int step = 0; step < steps; ++step) {
    a.simulation.step();
    b.simulation.step();
    const auto& x = a.simulation.objects[0].system.state.position;
    const auto& y = b.simulation.objects[0].system.state.position;
    for (std::size_t i = 0; i < x.size(); ++i) difference = std::max(difference, (x[i] - y[i]).norm());
  }
  return difference;
}

template <class Solver>
const Solver& linear_solver(const LoadedScene& scene) {
  const auto* solver = dynamic_cast<const Solver*>(scene.simulation.objects.at(0).linear_solver.get());
  if (!solver) throw make_error("not the expected linear solver");
  return *solver;
}

TEST(LinearSolversScene, MinResAttributesErrorsAndTrajectory) {
  const auto p = linear_solver<MinResSolver<double>>(build(R"(<MinResLinearSolver template="GraphScattered" iterations="40" tolerance="1e-7"/>)")).parameters();
  EXPECT_EQ(p.iterations, 40);
  EXPECT_EQ(p.tolerance, 1e-7);
  const std::string error = error_of(R"(<MinResLinearSolver iterations="0"/>)");
  EXPECT_NE(error.find("MinResLinearSolver"), std::string::npos) << error;
  EXPECT_NE(error.find("iterations"), std::string::npos) << error;
  LoadedScene direct = build("<SparseLDLSolver/>");
  LoadedScene minres = build(R"(<MinResLinearSolver iterations="1000" tolerance="1e-16"/>)");
  EXPECT_LT(trajectory_difference(direct, minres, 30), 1e-8);
}

TEST(LinearSolversScene, SsorPreconditionerAttributesErrorsAndTrajectory) {
  const LoadedScene scene = build(R"(<PCGLinearSolver iterations="1000" preconditioner="@P"/>
    <SSORPreconditioner name="P" omega="1.3"/>)");
  const auto& p = linear_solver<PreconditionedConjugateGradientSolver<double>>(scene).parameters();
  ASSERT_EQ(p.preconditioner, Preconditioner::solver);
  const auto* ssor = dynamic_cast<const SSORPreconditioner<double>*>(p.solver.get());
  ASSERT_NE(ssor, nullptr);
  EXPECT_EQ(ssor->parameters().omega, 1.3);
  EXPECT_TRUE(ssor->parameters().scale_by_two_minus_omega);
  const LoadedScene block_scene =
      build(R"(<PCGLinearSolver preconditioner="@P"/><SSORPreconditioner name="P" template="CompressedRowSparseMatrixMat3x3d"/>)");
  const auto& block = linear_solver<PreconditionedConjugateGradientSolver<double>>(block_scene);
  EXPECT_FALSE(dynamic_cast<const SSORPreconditioner<double>&>(*block.parameters().solver).parameters().scale_by_two_minus_omega);
  const std::string error = error_of(R"(<PCGLinearSolver preconditioner="@P"/><SSORPreconditioner name="P" omega="2"/>)");
  EXPECT_NE(error.find("SSORPreconditioner"), std::string::npos) << error;
  EXPECT_NE(error.find("omega"), std::string::npos) << error;
  LoadedScene direct = build("<SparseLDLSolver/>");
  LoadedScene pcg = build(R"(<PCGLinearSolver iterations="1000" tolerance="1e-30" preconditioner="@P"/>
    <SSORPreconditioner name="P" omega="1.3"/>)");
  EXPECT_LT(trajectory_difference(direct, pcg, 30), 1e-8);
}

TEST(LinearSolversScene, WarpPreconditionerWithItsRotationMatrixSystem) {
  // SOFA's FEMBAR_PCG_WarpPreconditioner.scn form: rate 1, the exact inverse, one iteration a solve.
  const std::string warp = R"(<PreconditionedMatrixFreeSystem name="matrixFreeSystem" assemblingRate="1"/>
    <PCGLinearSolver name="PCG" iterations="1000" linearSystem="@matrixFreeSystem" preconditioner="@preconditioner"/>
    <RotationMatrixSystem name="rotationMatrix" assemblingRate="RATE"/>
    <WarpPreconditioner name="preconditioner" linearSystem="@rotationMatrix" linearSolver="@initSolver"/>
    <MatrixLinearSystem template="CompressedRowSparseMatrixMat3x3" name="system"/>
    <SparseLDLSolver name="initSolver" template="CompressedRowSparseMatrixMat3x3" linearSystem="@system"/>)";
  const auto with_rate = [&](const std::string& rate) {
    std::string text = warp;
    text.replace(text.find("RATE"), 4, rate);
    return text;
  };
  const LoadedScene scene = build(with_rate("4"));
  const auto& p = linear_solver<PreconditionedConjugateGradientSolver<double>>(scene).parameters();
  ASSERT_EQ(p.preconditioner, Preconditioner::solver);
  EXPECT_EQ(dynamic_cast<const WarpPreconditioner<double>&>(*p.solver).parameters().assembling_rate, 4);
  const std::string zero = error_of(with_rate("0"));
  EXPECT_NE(zero.find("RotationMatrixSystem"), std::string::npos) << zero;
  EXPECT_NE(zero.find("assemblingRate"), std::string::npos) << zero;
  const std::string not_direct = error_of(R"(<PCGLinearSolver preconditioner="@W"/><WarpPreconditioner name="W" linearSolver="@cg"/>
    <CGLinearSolver name="cg"/>)");
  EXPECT_NE(not_direct.find("linearSolver"), std::string::npos) << not_direct;
  LoadedScene direct = build("<SparseLDLSolver/>");
  LoadedScene pcg = build(with_rate("1"));
  EXPECT_LT(trajectory_difference(direct, pcg, 30), 1e-8);
  // Rate 5 with TetrahedronFEMForceField: rotated old factorisations, converged by the iterations.
  LoadedScene direct_tets = build("<SparseLDLSolver/>", "TetrahedronFEMForceField");
  std::string tight = with_rate("5");
  tight.replace(tight.find(R"(iterations="1000")"), 17, R"(iterations="1000" tolerance="1e-30")");
  LoadedScene warped = build(tight, "TetrahedronFEMForceField");
  EXPECT_LT(trajectory_difference(direct_tets, warped, 30), 1e-8);
}

TEST(LinearSolversScene, EigenSimplicialLLTSolvesAsTheDirectSolver) {
  // SOFA's EigenSimplicialLLT (InextensiblePendulum.scn writes it with its block template) is the
  // block LDL^T here: the trajectory of an independent converged CG to 1e-8, and that of
  // EigenSimplicialLDLT exactly.
  const LoadedScene block = build(R"(<EigenSimplicialLLT template="CompressedRowSparseMatrixMat3x3"/>)");
  EXPECT_NE(dynamic_cast<const SparseDirectSolver<double>*>(block.simulation.objects.at(0).linear_solver.get()), nullptr);
  EXPECT_NO_THROW(build(R"(<EigenSimplicialLLT template="CompressedRowSparseMatrixd"/>)"));
  LoadedScene llt = build(R"(<EigenSimplicialLLT template="CompressedRowSparseMatrixMat3x3"/>)");
  LoadedScene ldlt = build("<EigenSimplicialLDLT/>");
  LoadedScene cg = build(R"(<CGLinearSolver iterations="1000" tolerance="1e-30" threshold="1e-30"/>)");
  EXPECT_EQ(trajectory_difference(llt, ldlt, 10), 0.0);
  LoadedScene llt_again = build(R"(<EigenSimplicialLLT template="CompressedRowSparseMatrixMat3x3"/>)");
  EXPECT_LT(trajectory_difference(llt_again, cg, 10), 1e-8);
}

TEST(LinearSolversScene, PrecomputedLinearSolverAndMatrixImage) {
  const LoadedScene scene = build(R"(<PrecomputedLinearSolver/><GlobalSystemMatrixImage linearSystem="@s"/>)");
  linear_solver<PrecomputedLinearSolver<double>>(scene);
  EXPECT_TRUE(has_line(scene.info, "use_file")) << "use_file is true by default: no file is written, said once";
  EXPECT_TRUE(has_line(scene.info, "GlobalSystemMatrixImage"));
  EXPECT_FALSE(has_line(build(R"(<PrecomputedLinearSolver use_file="false"/>)").info, "use_file"));
  // One step from rest: A0 is that step's matrix, so the first step is the direct solver's.
  LoadedScene direct = build("<SparseLDLSolver/>");
  LoadedScene precomputed = build(R"(<PrecomputedLinearSolver use_file="false"/>)");
  EXPECT_LT(trajectory_difference(direct, precomputed, 1), 1e-12);
  EXPECT_GT(trajectory_difference(direct, precomputed, 20), 1e-9);  // later steps keep A0
}

}  // namespace
}  // namespace fastcorot
