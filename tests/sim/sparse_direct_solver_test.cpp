// SparseDirectSolver: LDL^T of the assembled system with SOFA's Dirichlet treatment of fixed points
// (docs/sofa-solvers.md §4.1, §4.2): rows and columns of fixed DOFs cleared, 1 on the diagonal, so a
// projected right-hand side gives exactly 0 there. The symbolic analysis is reused while the pattern
// is unchanged (§4.2); these tests change values and patterns between solves.
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/sparse_direct_solver.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/topology/regular_grid.h"
#include "support/deformations.h"
#include "support/finite_difference.h"
#include "support/random_rhs.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using Field = CorotationalForceField<double>;
using testing::flatten;
using testing::relative_error;

// A 2×2×3-point grid (2 cells, 12 tetrahedra) with lumped masses, linearised at a deformed state.
struct Beam {
  MechanicalSystem<double> system;
  std::shared_ptr<Field> field;
};

Beam beam(std::vector<Index> fixed, unsigned seed) {
  RegularGrid grid;
  grid.n = {2, 2, 3};
  grid.min = Vec3<double>(0, 0, 0);
  grid.max = Vec3<double>(1, 1, 2);
  auto mesh = std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true));
  const Points rest = grid_points<double>(grid);
  Field::Parameters p;
  p.young_modulus = {5000.0};
  p.poisson_ratio = {0.4};
  Beam b;
  b.field = std::make_shared<Field>(mesh, rest, p);
  std::mt19937 rng(seed);
  b.system.state.position = testing::perturbed(rest, 0.1, rng);
  b.system.state.rest_position = rest;
  b.system.force_fields.push_back(b.field);
  b.system.mass = Mass<double>::lumped(tetrahedral_lumped_masses<double>(*mesh, rest, 2.0));
  b.system.gravity = Vec3<double>(0, -9.81, 0);
  b.system.fixed = std::move(fixed);
  b.system.finalize();
  Points f(rest.size());
  b.system.compute_force(b.system.state.position, f);  // linearise at the deformed state
  return b;
}

// Implicit Euler's factors for h = 0.05, rs = 0.1, rm = 0.1 (docs/sofa-solvers.md §1.2 step 3).
constexpr double kH = 0.05;
constexpr MatrixFactors<double> kFactors{1 + kH * 0.1, -kH, -kH * (kH + 0.1)};

// |A x - b| / |b| with the solver's own assembled matrix, and with the matrix-free product.
void expect_solves(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors, const Points& b,
                   const Points& x) {
  const Eigen::VectorXd ax = system.assemble(factors) * flatten(x);
  EXPECT_LT((ax - flatten(b)).norm() / flatten(b).norm(), 1e-12);
  Points q(b.size());
  system.multiply(factors, x, q);
  EXPECT_LT((flatten(q) - flatten(b)).norm() / flatten(b).norm(), 1e-12);
  for (Index i : system.fixed) EXPECT_EQ(x[static_cast<std::size_t>(i)], Vec3<double>::Zero()) << "point " << i;
}

TEST(SparseDirectSolver, MatchesConjugateGradientAndSatisfiesTheSystem) {
  auto b = beam({0, 1, 2, 3}, 1);  // the z = 0 face
  const Points rhs = testing::projected_rhs(b.system, 2);
  Points direct(rhs.size(), Vec3<double>(3, 3, 3));
  SparseDirectSolver<double> solver;
  const auto report = solver.solve(b.system, kFactors, rhs, direct);
  EXPECT_EQ(report.iterations, 0);
  expect_solves(b.system, kFactors, rhs, direct);

  ConjugateGradientSolver<double>::Parameters p;
  p.iterations = 1000;
  p.tolerance = 1e-15;
  p.threshold = 1e-40;
  ConjugateGradientSolver<double> cg(p);
  Points iterative(rhs.size());
  cg.solve(b.system, kFactors, rhs, iterative);
  EXPECT_LT(relative_error(flatten(direct), flatten(iterative)), 1e-10);
}

TEST(SparseDirectSolver, StaticSystemWithoutMass) {
  // Factors (0, 0, -1): A = -K, as the static solver poses it (docs/sofa-solvers.md §3.1).
  auto b = beam({0, 1, 2, 3}, 3);
  const Points rhs = testing::projected_rhs(b.system, 4);
  Points x(rhs.size());
  SparseDirectSolver<double> solver;
  solver.solve(b.system, {0.0, 0.0, -1.0}, rhs, x);
  expect_solves(b.system, {0.0, 0.0, -1.0}, rhs, x);
}

TEST(SparseDirectSolver, ReusesTheAnalysisWhenOnlyValuesChange) {
  auto b = beam({0, 1, 2, 3}, 5);
  SparseDirectSolver<double> solver;
  const Points rhs = testing::projected_rhs(b.system, 6);
  Points first(rhs.size());
  solver.solve(b.system, kFactors, rhs, first);
  expect_solves(b.system, kFactors, rhs, first);

  // New linearisation (same pattern, new values) and new factors.
  std::mt19937 rng(7);
  const Points x2 = testing::perturbed(b.system.state.rest_position, 0.2, rng);
  Points f(x2.size());
  b.system.compute_force(x2, f);
  const MatrixFactors<double> other{2.0, -0.1, -0.3};
  Points second(rhs.size());
  solver.solve(b.system, other, rhs, second);
  expect_solves(b.system, other, rhs, second);
  EXPECT_GT(relative_error(flatten(second), flatten(first)), 1e-3);  // the values did change

  // A fresh solver gives the same answer.
  SparseDirectSolver<double> fresh;
  Points reference(rhs.size());
  fresh.solve(b.system, other, rhs, reference);
  EXPECT_LT(relative_error(flatten(second), flatten(reference)), 1e-13);
}

TEST(SparseDirectSolver, RedoesTheAnalysisWhenTheFixedSetChanges) {
  auto b = beam({0, 1, 2, 3}, 8);
  SparseDirectSolver<double> solver;
  for (const auto& fixed : std::vector<std::vector<Index>>{{0, 1, 2, 3}, {8, 9, 10, 11}, {0, 5, 10}, {0, 1, 2, 3}}) {
    b.system.fixed = fixed;
    b.system.finalize();
    const Points rhs = testing::projected_rhs(b.system, 9);
    Points x(rhs.size(), Vec3<double>(1, 1, 1));
    solver.solve(b.system, kFactors, rhs, x);
    expect_solves(b.system, kFactors, rhs, x);
  }
}

TEST(SparseDirectSolver, NoFixedPointsWithMass) {
  // The mass alone makes the system definite; nothing is fixed.
  auto b = beam({}, 10);
  const Points rhs = testing::projected_rhs(b.system, 11);
  Points x(rhs.size());
  SparseDirectSolver<double> solver;
  solver.solve(b.system, kFactors, rhs, x);
  expect_solves(b.system, kFactors, rhs, x);
}

TEST(SparseDirectSolver, SingularSystemThrows) {
  // Points with no mass and no element give zero rows: the factorisation fails.
  MechanicalSystem<double> system;
  system.state.position.assign(2, Vec3<double>::Zero());
  system.mass = Mass<double>::lumped({1.0, 0.0});
  system.finalize();
  const Points rhs = {Vec3<double>(1, 0, 0), Vec3<double>(0, 0, 0)};
  Points x(2);
  SparseDirectSolver<double> solver;
  EXPECT_THROW(solver.solve(system, {1.0, 0.0, 0.0}, rhs, x), Error);
}

TEST(SparseDirectSolver, DiagonalSystemByHand) {
  // Masses 2 and 4, factors m = 0.5: A = diag(1, 1, 1, 2, 2, 2); b = (1, 2, 3, 4, 6, 8)
  // gives x = (1, 2, 3, 2, 3, 4).
  MechanicalSystem<double> system;
  system.state.position.assign(2, Vec3<double>::Zero());
  system.mass = Mass<double>::lumped({2.0, 4.0});
  system.finalize();
  const Points rhs = {Vec3<double>(1, 2, 3), Vec3<double>(4, 6, 8)};
  Points x(2);
  SparseDirectSolver<double> solver;
  solver.solve(system, {0.5, 0.0, 0.0}, rhs, x);
  EXPECT_EQ(x[0], Vec3<double>(1, 2, 3));
  EXPECT_EQ(x[1], Vec3<double>(2, 3, 4));
}

TEST(SparseDirectSolver, FloatInstantiation) {
  MechanicalSystem<float> system;
  system.state.position.assign(2, Vec3<float>::Zero());
  system.mass = Mass<float>::lumped({2.0f, 4.0f});
  system.fixed = {0};
  system.finalize();
  const std::vector<Vec3<float>> rhs = {Vec3<float>(0, 0, 0), Vec3<float>(4, 6, 8)};
  std::vector<Vec3<float>> x(2);
  SparseDirectSolver<float> solver;
  solver.solve(system, {0.5f, 0.0f, 0.0f}, rhs, x);
  EXPECT_EQ(x[0], Vec3<float>::Zero());
  EXPECT_EQ(x[1], Vec3<float>(2, 3, 4));
}

}  // namespace
}  // namespace fastcorot
