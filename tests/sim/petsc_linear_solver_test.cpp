// PetscLinearSolver against the sparse direct solve of the same assembled system (docs/scaling.md):
// CG + GAMG with the rigid-body modes at a tight tolerance gives the direct solution; the pattern
// (and GAMG's hierarchy with it) is built once and rebuilt only when the pattern changes; partial
// projections go through the general assembly; bad types and non-convergence are clear errors.
// A build without PETSc has the component and refuses it.
#include "fastcorot/sim/petsc_linear_solver.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/petsc_runtime.h"
#include "fastcorot/sim/sparse_direct_solver.h"
#include "fastcorot/topology/regular_grid.h"
#include "support/deformations.h"
#include "support/finite_difference.h"
#include "support/random_rhs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using Field = CorotationalForceField<double>;
using testing::flatten;
using testing::relative_error;

constexpr double kH = 0.01;
constexpr MatrixFactors<double> kFactors{1 + kH * 0.1, -kH, -kH * (kH + 0.1)};

// An 8×3×3-point beam clamped at x = 0, linearised at a deformed state.
struct Beam {
  std::shared_ptr<TetMesh> mesh;
  MechanicalSystem<double> system;
};

Beam beam(unsigned seed) {
  RegularGrid grid;
  grid.n = {8, 3, 3};
  grid.min = Vec3<double>(0, 0, 0);
  grid.max = Vec3<double>(7, 2, 2);
  Beam b;
  b.mesh = std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true));
  const Points rest = grid_points<double>(grid);
  Field::Parameters p;
  p.young_modulus = {5000.0};
  p.poisson_ratio = {0.35};
  std::mt19937 rng(seed);
  b.system.state.position = testing::perturbed(rest, 0.05, rng);
  b.system.state.rest_position = rest;
  b.system.force_fields.push_back(std::make_shared<Field>(b.mesh, rest, p));
  b.system.mass = Mass<double>::lumped(tetrahedral_lumped_masses<double>(*b.mesh, rest, 1.0));
  b.system.mass.follow_tetrahedra(b.mesh, 1.0);
  for (Index i = 0; i < static_cast<Index>(rest.size()); ++i) {
    if (rest[static_cast<std::size_t>(i)].x() == 0) b.system.fixed.push_back(i);
  }
  b.system.finalize();
  Points f(rest.size());
  b.system.compute_force(b.system.state.position, f);
  return b;
}

Points direct_solve(const MechanicalSystem<double>& system, const Points& rhs,
                    const MatrixFactors<double>& factors = kFactors) {
  SparseDirectSolver<double> direct;
  Points x(rhs.size());
  direct.solve(system, factors, rhs, x);
  return x;
}

PetscLinearSolver::Parameters tight() {
  PetscLinearSolver::Parameters p;
  p.tolerance = 1e-12;
  return p;
}

#ifdef FASTCOROT_WITH_PETSC

TEST(PetscLinearSolver, MatchesTheSparseDirectSolve) {
  auto b = beam(1);
  const Points rhs = testing::projected_rhs(b.system, 2);
  for (const bool matrix_free : {true, false}) {
    PetscLinearSolver::Parameters p = tight();
    p.matrix_free = matrix_free;
    PetscLinearSolver solver(p);
    Points x(rhs.size(), Vec3<double>(7, 7, 7));
    const LinearSolveReport report = solver.solve(b.system, kFactors, rhs, x);
    EXPECT_EQ(solver.matrix_free(), matrix_free);
    EXPECT_GT(report.iterations, 0);
    EXPECT_LE(report.relative_residual, 1e-12);
    EXPECT_LT(relative_error(flatten(x), flatten(direct_solve(b.system, rhs))), 1e-10) << matrix_free;
    for (Index i : b.system.fixed) EXPECT_EQ(x[static_cast<std::size_t>(i)], Vec3<double>::Zero()) << "point " << i;
  }
}

// The preconditioner of an earlier linearisation still gives the current system's solution, in
// both operators; with preonly (the preconditioner is the solve) it is rebuilt every solve.
TEST(PetscLinearSolver, AnOlderPreconditionerStillSolvesTheCurrentSystem) {
  auto b = beam(12);
  const Points rhs = testing::projected_rhs(b.system, 13);
  std::mt19937 rng(14);
  const Points other = testing::perturbed(b.system.state.rest_position, 0.15, rng);
  for (const auto& [ksp, pc, matrix_free] : {std::tuple{"cg", "gamg", true}, std::tuple{"cg", "gamg", false},
                                             std::tuple{"cg", "cholesky", true}, std::tuple{"preonly", "cholesky", true},
                                             std::tuple{"preonly", "cholesky", false}}) {
    auto system = beam(12).system;
    PetscLinearSolver::Parameters p = tight();
    p.ksp = ksp;
    p.pc = pc;
    p.matrix_free = matrix_free;
    p.rebuild_growth = 0;  // never on growth: the second solve uses the first one's preconditioner
    PetscLinearSolver solver(p);
    Points x(rhs.size()), f(rhs.size());
    solver.solve(system, kFactors, rhs, x);
    system.compute_force(other, f);  // another linearisation
    solver.solve(system, kFactors, rhs, x);
    const std::string what = std::string(ksp) + " " + pc + (matrix_free ? " matrix-free" : " assembled");
    EXPECT_LT(relative_error(flatten(x), flatten(direct_solve(system, rhs))), 1e-10) << what;
    EXPECT_EQ(solver.preconditioner_builds(), std::string(ksp) == "preonly" ? 2 : 1) << what;
    EXPECT_EQ(solver.matrix_free(), matrix_free && std::string(ksp) != "preonly") << what;
  }
}

// Rebuilds on a schedule, and after a solve whose iterations grew: the matrix changed under a
// Jacobi preconditioner (mass-dominated, then stiffness-dominated).
TEST(PetscLinearSolver, RebuildsOnItsScheduleAndWhenIterationsGrow) {
  auto b = beam(15);
  const Points rhs = testing::projected_rhs(b.system, 16);
  Points x(rhs.size());
  PetscLinearSolver::Parameters scheduled = tight();
  scheduled.rebuild_every = 2;
  scheduled.rebuild_growth = 0;
  PetscLinearSolver every_two(scheduled);
  for (int solve = 1; solve <= 5; ++solve) {
    every_two.solve(b.system, kFactors, rhs, x);
    EXPECT_EQ(every_two.preconditioner_builds(), (solve + 1) / 2) << solve;
  }
  EXPECT_EQ(every_two.carried_state()[0], 1);  // the 5th solve was the first with its preconditioner

  PetscLinearSolver::Parameters grown = tight();
  grown.pc = "jacobi";
  PetscLinearSolver solver(grown);
  const MatrixFactors<double> soft{1.0, 0.0, -1e-4}, stiff{1e-4, 0.0, -1.0};
  const LinearSolveReport first = solver.solve(b.system, soft, rhs, x);
  const LinearSolveReport second = solver.solve(b.system, stiff, rhs, x);
  ASSERT_GT(second.iterations, 1.5 * first.iterations + 3) << "the test's matrices no longer slow Jacobi down";
  EXPECT_EQ(solver.preconditioner_builds(), 1);
  EXPECT_EQ(solver.carried_state(), (std::vector<std::int64_t>{2, first.iterations, 1}));
  // A checkpoint carries the due rebuild: a solver restored from it rebuilds at its next solve.
  PetscLinearSolver restored(grown);
  restored.restore_carried_state(solver.carried_state());
  solver.solve(b.system, stiff, rhs, x);
  EXPECT_EQ(solver.preconditioner_builds(), 2);
  EXPECT_EQ(solver.carried_state()[0], 1);
  restored.solve(b.system, stiff, rhs, x);
  EXPECT_EQ(restored.carried_state(), solver.carried_state());
  EXPECT_LT(relative_error(flatten(x), flatten(direct_solve(b.system, rhs, stiff))), 1e-10);
  EXPECT_THROW(restored.restore_carried_state({1, 2}), Error);
  EXPECT_THROW(restored.restore_carried_state({1, 2, 3}), Error);
}

TEST(PetscLinearSolver, EveryPreconditionerGivesTheSameSolution) {
  auto b = beam(3);
  const Points rhs = testing::projected_rhs(b.system, 4);
  const Points reference = direct_solve(b.system, rhs);
  for (const char* pc : {"gamg", "jacobi", "none", "cholesky"}) {
    PetscLinearSolver::Parameters p = tight();
    p.pc = pc;
    PetscLinearSolver solver(p);
    Points x(rhs.size());
    solver.solve(b.system, kFactors, rhs, x);
    EXPECT_LT(relative_error(flatten(x), flatten(reference)), 1e-9) << pc;
  }
}

TEST(PetscLinearSolver, BuildsThePatternOnceAndAgainWhenTheTopologyChanges) {
  auto b = beam(5);
  PetscLinearSolver solver(tight());
  const Points rhs = testing::projected_rhs(b.system, 6);
  Points x(rhs.size());
  solver.solve(b.system, kFactors, rhs, x);
  // New values (another linearisation), same pattern: reused.
  std::mt19937 rng(7);
  Points f(rhs.size());
  b.system.compute_force(testing::perturbed(b.system.state.rest_position, 0.1, rng), f);
  solver.solve(b.system, kFactors, rhs, x);
  EXPECT_EQ(solver.pattern_builds(), 1);
  EXPECT_LT(relative_error(flatten(x), flatten(direct_solve(b.system, rhs))), 1e-10);
  EXPECT_GT(solver.memory_bytes(), 0u);
  // A cut: new pattern.
  const std::vector<Index> cut{0, 5, 17};
  b.system.remove_tetrahedra(*b.mesh, cut);
  solver.solve(b.system, kFactors, rhs, x);
  EXPECT_EQ(solver.pattern_builds(), 2);
  EXPECT_LT(relative_error(flatten(x), flatten(direct_solve(b.system, rhs))), 1e-10);
}

TEST(PetscLinearSolver, PartialProjectionsGoThroughTheGeneralAssembly) {
  auto b = beam(8);
  PointProjection<double> plane;  // the last point slides in the plane z = const
  plane.point = b.system.size() - 1;
  plane.projector = Vec3<double>(1, 1, 0).asDiagonal();
  b.system.projections.push_back(plane);
  const Points rhs = testing::projected_rhs(b.system, 9);
  PetscLinearSolver solver(tight());
  Points x(rhs.size());
  solver.solve(b.system, kFactors, rhs, x);
  EXPECT_LT(relative_error(flatten(x), flatten(direct_solve(b.system, rhs))), 1e-10);
  EXPECT_LT(std::abs(x.back().z()), 1e-10 * flatten(x).norm());  // to the solver's tolerance
}

TEST(PetscLinearSolver, NotConvergingIsAnErrorNamingPetscsReason) {
  auto b = beam(10);
  PetscLinearSolver::Parameters p = tight();
  p.pc = "none";
  p.max_iterations = 2;
  PetscLinearSolver solver(p);
  const Points rhs = testing::projected_rhs(b.system, 11);
  Points x(rhs.size());
  try {
    solver.solve(b.system, kFactors, rhs, x);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("did not converge: DIVERGED_ITS after 2 iterations"), std::string::npos) << message;
  }
}

TEST(PetscLinearSolver, UnknownTypesAndBadParametersAreErrors) {
  PetscLinearSolver::Parameters p;
  p.ksp = "no_such_ksp";
  EXPECT_THROW({ PetscLinearSolver solver(p); }, Error);
  p = {};
  p.pc = "no_such_pc";
  try {
    PetscLinearSolver solver(p);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("unknown pc \"no_such_pc\""), std::string::npos) << error.what();
  }
  p = {};
  p.tolerance = 0;
  EXPECT_THROW({ PetscLinearSolver solver(p); }, Error);
  p = {};
  p.max_iterations = 0;
  EXPECT_THROW({ PetscLinearSolver solver(p); }, Error);
  p = {};
  p.rebuild_every = -1;
  EXPECT_THROW({ PetscLinearSolver solver(p); }, Error);
  p = {};
  p.rebuild_growth = 0.5;
  EXPECT_THROW({ PetscLinearSolver solver(p); }, Error);
}

#else

TEST(PetscLinearSolver, IsAClearErrorWithoutPetsc) {
  EXPECT_FALSE(petsc_available());
  try {
    PetscLinearSolver solver(tight());
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("without PETSc"), std::string::npos) << error.what();
  }
  EXPECT_THROW(initialise_petsc({"-ksp_type", "cg"}), Error);
}

#endif

TEST(PetscOptions, TakesPetscsOptionsAndLeavesOurs) {
  std::vector<std::string> arguments{"fastcorot", "run", "beam.scn", "--steps", "10", "-ksp_type", "cg", "-ksp_monitor",
                                     "--quiet", "-ksp_rtol", "1e-10", "-pc_gamg_threshold", "-1", "-o"};
  const std::vector<std::string> petsc = take_petsc_options(arguments);
  EXPECT_EQ(petsc, (std::vector<std::string>{"-ksp_type", "cg", "-ksp_monitor", "-ksp_rtol", "1e-10", "-pc_gamg_threshold", "-1"}));
  EXPECT_EQ(arguments, (std::vector<std::string>{"fastcorot", "run", "beam.scn", "--steps", "10", "--quiet", "-o"}));
}

}  // namespace
}  // namespace fastcorot
