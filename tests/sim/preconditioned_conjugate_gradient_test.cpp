// PreconditionedConjugateGradientSolver: SOFA's PCGLinearSolver with Jacobi, block-Jacobi and sparse
// direct preconditioners (docs/sofa-solvers.md §2.4). The reference is a plain dense implementation
// of the same iteration written here, on the matrix obtained column by column from the matrix-free
// product, with P inverted from that matrix's own diagonal (or the whole matrix, densely).
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"

#include "fastcorot/core/error.h"
#include "support/deformations.h"
#include "support/mass_system.h"
#include "support/random_rhs.h"
#include "support/solver_systems.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using PCG = PreconditionedConjugateGradientSolver<double>;
using testing::flatten;

PCG::Parameters parameters(Preconditioner preconditioner, int iterations, double tolerance, int update_step = 1) {
  PCG::Parameters p;
  p.preconditioner = preconditioner;
  p.iterations = iterations;
  p.tolerance = tolerance;
  p.update_step = update_step;
  return p;
}

using testing::mass_system;

constexpr MatrixFactors<double> kMassOnly{1.0, 0.0, 0.0};

// A 4 x 3 x 3 grid of points (72 tetrahedra), deformed and linearised there, lumped masses, the
// points of the face x = 0 fixed (testing::grid_system); with `turn`, TetrahedronFEMForceField
// (large) instead of ours and the deformed positions turned by that rotation, else ours with its
// Rayleigh damping 0.1.
MechanicalSystem<double> small_beam(unsigned seed, const Mat3<double>* turn = nullptr) {
  return turn ? testing::grid_system(seed, 0.15, *turn, true) : testing::grid_system(seed, 0.15, Mat3<double>::Identity(), false, 0.1);
}

constexpr MatrixFactors<double> kEuler = testing::kEulerFactors;

// The system matrix, column by column from the matrix-free product.
Eigen::MatrixXd dense_matrix(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors) {
  const auto n = static_cast<std::size_t>(system.size());
  Eigen::MatrixXd a(3 * n, 3 * n);
  Points e(n, Vec3<double>::Zero()), column(n);
  for (std::size_t j = 0; j < 3 * n; ++j) {
    e[j / 3][static_cast<Eigen::Index>(j % 3)] = 1;
    system.multiply(factors, e, column);
    a.col(static_cast<Eigen::Index>(j)) = flatten(column);
    e[j / 3].setZero();
  }
  // The product zeroes fixed rows; assembled, their diagonal is 1 (as SOFA's projection does).
  for (Index i : system.fixed) a.block<3, 3>(3 * i, 3 * i).setIdentity();
  return a;
}

Eigen::MatrixXd dense_preconditioner(const Eigen::MatrixXd& a, Preconditioner preconditioner) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(a.rows(), a.cols());
  for (Eigen::Index i = 0; i < a.rows(); i += 3) {
    const Eigen::Matrix3d block = a.block<3, 3>(i, i);
    if (preconditioner == Preconditioner::block_jacobi) p.block<3, 3>(i, i) = block.inverse();
    if (preconditioner == Preconditioner::jacobi) p.block<3, 3>(i, i) = block.diagonal().cwiseInverse().asDiagonal();
    if (preconditioner == Preconditioner::none) p.block<3, 3>(i, i).setIdentity();
  }
  return p;
}

// SOFA's PCGLinearSolver::solve, plainly: x is the start and the result; returns the iterations.
int dense_pcg(const Eigen::MatrixXd& a, const Eigen::MatrixXd& p, const Eigen::VectorXd& b, Eigen::VectorXd& x,
              int iterations, double tolerance) {
  Eigen::VectorXd r = b - a * x;
  Eigen::VectorXd w = p * r;
  double rho = r.dot(w);
  const double tol = tolerance * b.dot(b);
  int done = 0;
  for (int it = 1; it <= iterations && rho > tol; ++it) {
    const Eigen::VectorXd q = a * w;
    const double alpha = rho / w.dot(q);
    x += alpha * w;
    r -= alpha * q;
    const Eigen::VectorXd s = p * r;
    const double rho_new = r.dot(s);
    w = s + (rho_new / rho) * w;
    rho = rho_new;
    done = it;
  }
  return done;
}

TEST(PreconditionedConjugateGradient, DefaultsAreSofas) {
  // PCGLinearSolver: iterations 25, tolerance 1e-5, update_step 1.
  const PCG::Parameters p;
  EXPECT_EQ(p.iterations, 25);
  EXPECT_EQ(p.tolerance, 1e-5);
  EXPECT_EQ(p.update_step, 1);
}

TEST(PreconditionedConjugateGradient, ConstructorRejectsBadParameters) {
  EXPECT_THROW(PCG(parameters(Preconditioner::none, 0, 1e-5), 3), Error);
  EXPECT_THROW(PCG(parameters(Preconditioner::none, 5, -1.0), 3), Error);
  EXPECT_THROW(PCG(parameters(Preconditioner::none, 5, std::nan("")), 3), Error);
  EXPECT_THROW(PCG(parameters(Preconditioner::none, 5, 1e-5, 0), 3), Error);
  EXPECT_THROW(PCG(parameters(Preconditioner::none, 5, 1e-5), -1), Error);
  EXPECT_NO_THROW(PCG(parameters(Preconditioner::none, 1, 0.0), 0));
}

TEST(PreconditionedConjugateGradient, MatchesThePlainDenseIterationForEachPreconditioner) {
  // Three solves in a row with a changing right-hand side and matrix: each starts from the
  // previous solution, as SOFA's does.
  for (const auto preconditioner : {Preconditioner::none, Preconditioner::jacobi, Preconditioner::block_jacobi}) {
    auto system = small_beam(3);
    PCG solver(parameters(preconditioner, 6, 0.0), system.size());
    Eigen::VectorXd x_reference = Eigen::VectorXd::Zero(3 * system.size());
    Points x(static_cast<std::size_t>(system.size()), Vec3<double>(7, 7, 7));  // not a start: overwritten
    for (int solve = 0; solve < 3; ++solve) {
      const MatrixFactors<double> factors{kEuler.m + 0.1 * solve, kEuler.b, kEuler.k * (1 + solve)};
      const Points b = testing::projected_rhs(system, 10 + static_cast<unsigned>(solve));
      const auto report = solver.solve(system, factors, b, x);
      const Eigen::MatrixXd a = dense_matrix(system, factors);
      const int iterations = dense_pcg(a, dense_preconditioner(a, preconditioner), flatten(b), x_reference, 6, 0.0);
      EXPECT_EQ(report.iterations, iterations);
      const double error = (flatten(x) - x_reference).norm() / x_reference.norm();
      EXPECT_LT(error, 1e-12) << preconditioner_name(preconditioner) << " solve " << solve;
    }
  }
}

TEST(PreconditionedConjugateGradient, ConvergesToTheSolutionAndFasterWithBlockJacobi) {
  auto system = small_beam(4);
  const Points b = testing::projected_rhs(system, 5);
  const Eigen::MatrixXd a = dense_matrix(system, kEuler);
  const Eigen::VectorXd exact = a.partialPivLu().solve(flatten(b));
  int iterations[3] = {};
  for (const auto preconditioner : {Preconditioner::none, Preconditioner::jacobi, Preconditioner::block_jacobi}) {
    PCG solver(parameters(preconditioner, 500, 1e-24), system.size());
    Points x(static_cast<std::size_t>(system.size()));
    const auto report = solver.solve(system, kEuler, b, x);
    EXPECT_LT((flatten(x) - exact).norm() / exact.norm(), 1e-10) << preconditioner_name(preconditioner);
    iterations[static_cast<int>(preconditioner)] = report.iterations;
  }
  EXPECT_LT(iterations[2], iterations[0]);
  EXPECT_LT(iterations[1], iterations[0]);
}

TEST(PreconditionedConjugateGradient, BlockJacobiSolvesABlockDiagonalSystemInOneIteration) {
  auto system = mass_system({1.0, 3.0});
  const Points b = {Vec3<double>(1, 2, 3), Vec3<double>(3, 0, -3)};
  Points x(2);
  PCG solver(parameters(Preconditioner::block_jacobi, 25, 1e-20), 2);
  const auto report = solver.solve(system, kMassOnly, b, x);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_EQ(x[0], Vec3<double>(1, 2, 3));
  EXPECT_EQ(x[1], Vec3<double>(1, 0, -1));
}

TEST(PreconditionedConjugateGradient, ToleranceIsOnRTimesPrAgainstTheSquaredNormOfB) {
  // A = diag(1, 3) along x, b = (1, 1), no preconditioner: b . b = 2; after iteration 1
  // x = (1/2, 1/2), r = (1/2, -1/2), r . r = 1/2, so r . r / b . b = 1/4 (CGLinearSolver's |r|/|b|
  // would be 1/2). The loop goes on while r . P r > tolerance · b . b.
  auto system = mass_system({1.0, 3.0});
  const Points b = {Vec3<double>(1, 0, 0), Vec3<double>(1, 0, 0)};
  for (const auto& [tolerance, expected] : std::vector<std::pair<double, int>>{{0.25, 1}, {0.3, 1}, {0.24, 2}}) {
    PCG solver(parameters(Preconditioner::none, 25, tolerance), 2);
    Points x(2);
    const auto report = solver.solve(system, kMassOnly, b, x);
    EXPECT_EQ(report.iterations, expected) << tolerance;
    if (expected == 1) {
      EXPECT_EQ(x[0], Vec3<double>(0.5, 0, 0));
      EXPECT_EQ(report.relative_residual, 0.5);  // sqrt(r . P r / b . b)
    }
  }
}

TEST(PreconditionedConjugateGradient, StartsFromItsPreviousSolution) {
  auto system = mass_system({1.0, 3.0});
  const Points b = {Vec3<double>(1, 0, 0), Vec3<double>(1, 0, 0)};
  PCG solver(parameters(Preconditioner::none, 25, 1e-20), 2);
  Points x = {Vec3<double>(5, 5, 5), Vec3<double>(5, 5, 5)};  // ignored: the first start is zero
  EXPECT_EQ(solver.solve(system, kMassOnly, b, x).iterations, 2);
  EXPECT_LT((x[1] - Vec3<double>(1.0 / 3, 0, 0)).norm(), 1e-15);
  // The same system again: r = b - A x is (nearly) zero at the start.
  const Points solved = x;
  EXPECT_LE(solver.solve(system, kMassOnly, b, x).iterations, 1);
  EXPECT_LT((x[1] - solved[1]).norm(), 1e-15);
  // A changed right-hand side starts from there too: b = A x_prev + (0, 0, 1) at point 0 along z.
  const Points shifted = {Vec3<double>(1, 0, 1), Vec3<double>(1, 0, 0)};
  EXPECT_EQ(solver.solve(system, kMassOnly, shifted, x).iterations, 1);
  EXPECT_LT((x[0] - Vec3<double>(1, 0, 1)).norm(), 1e-15);
}

TEST(PreconditionedConjugateGradient, PreconditionerIsRebuiltEveryUpdateStepSolves) {
  auto system = mass_system({2.0, 4.0});
  const Points b = {Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0)};
  Points x(2);
  PCG solver(parameters(Preconditioner::jacobi, 25, 1e-20, 2), 2);
  solver.solve(system, {1.0, 0.0, 0.0}, b, x);  // built: diag(1/2, 1/4)
  EXPECT_EQ(solver.preconditioner_blocks()[1], Mat3<double>::Identity() / 4);
  solver.solve(system, {2.0, 0.0, 0.0}, b, x);  // kept from the first matrix
  EXPECT_EQ(solver.preconditioner_blocks()[1], Mat3<double>::Identity() / 4);
  EXPECT_LT((x[1] - Vec3<double>(0, 0.125, 0)).norm(), 1e-15);  // still solves the new system
  solver.solve(system, {2.0, 0.0, 0.0}, b, x);  // third solve: rebuilt
  EXPECT_EQ(solver.preconditioner_blocks()[1], Mat3<double>::Identity() / 8);
}

TEST(PreconditionedConjugateGradient, SparseDirectPreconditionerIsTheInverseOfTheMatrixItWasBuiltFrom) {
  auto system = small_beam(8);
  const Points b = testing::projected_rhs(system, 4);
  const Eigen::MatrixXd a = dense_matrix(system, kEuler);
  const Eigen::VectorXd exact = a.partialPivLu().solve(flatten(b));
  // Built from this step's matrix: P = A^-1, one iteration solves it.
  PCG solver(parameters(Preconditioner::sparse_ldlt, 25, 1e-20, 2), system.size());
  EXPECT_TRUE(solver.preconditioner_blocks().empty());
  Points x(static_cast<std::size_t>(system.size()));
  EXPECT_EQ(solver.solve(system, kEuler, b, x).iterations, 1);
  EXPECT_LT((flatten(x) - exact).norm() / exact.norm(), 1e-12);
  // The next solve keeps the factorisation of that matrix for a different one (update_step 2): the
  // plain dense iteration with P = the first matrix's inverse, from the previous solution.
  const MatrixFactors<double> later{1.3, -0.05, -0.03};
  const Points b2 = testing::projected_rhs(system, 5);
  const Eigen::MatrixXd a2 = dense_matrix(system, later);
  Eigen::VectorXd x_reference = flatten(x);
  PCG two_iterations(parameters(Preconditioner::sparse_ldlt, 2, 0.0, 2), system.size());
  Points y(x.size());
  two_iterations.solve(system, kEuler, b, y);
  x_reference = flatten(y);
  const auto report = two_iterations.solve(system, later, b2, y);
  EXPECT_EQ(dense_pcg(a2, a.inverse(), flatten(b2), x_reference, 2, 0.0), 2);
  EXPECT_EQ(report.iterations, 2);
  EXPECT_LT((flatten(y) - x_reference).norm() / x_reference.norm(), 1e-11);
  // The second solve with the first factorisation needs several iterations; the third, rebuilt
  // from the new matrix, one again (a new right-hand side, so that it has something to do).
  EXPECT_GT(solver.solve(system, later, b2, x).iterations, 2);
  const Points b3 = testing::projected_rhs(system, 6);
  EXPECT_EQ(solver.solve(system, later, b3, x).iterations, 1);
  const Eigen::VectorXd exact3 = a2.partialPivLu().solve(flatten(b3));
  EXPECT_LT((flatten(x) - exact3).norm() / exact3.norm(), 1e-12);
}

// The warp preconditioner's R, written here from the elements: per point, the mean of
// rotation * initial_rotation^T over its tetrahedra.
Eigen::MatrixXd dense_rotations(const MechanicalSystem<double>& system) {
  const auto& field = dynamic_cast<const TetrahedronFEMForceField<double>&>(*system.force_fields[0]);
  const auto n = static_cast<std::size_t>(system.size());
  std::vector<Mat3<double>> sum(n, Mat3<double>::Zero());
  std::vector<int> count(n, 0);
  for (Index t = 0; t < field.mesh().num_tetrahedra(); ++t) {
    const auto& e = field.element(t);
    for (Index v : field.mesh().tetrahedra()[static_cast<std::size_t>(t)]) {
      sum[static_cast<std::size_t>(v)] += e.rotation * e.initial_rotation.transpose();
      ++count[static_cast<std::size_t>(v)];
    }
  }
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(3 * n), static_cast<Eigen::Index>(3 * n));
  for (std::size_t i = 0; i < n; ++i) r.block<3, 3>(static_cast<Eigen::Index>(3 * i), static_cast<Eigen::Index>(3 * i)) = sum[i] / count[i];
  return r;
}

TEST(PreconditionedConjugateGradient, PrecomputedWarpIsRTimesTheFirstInverseTimesRTransposed) {
  const Mat3<double> turn = Eigen::AngleAxisd(0.6, Vec3<double>(1, 1, 0).normalized()).toRotationMatrix();
  auto system = small_beam(9, &turn);
  const Points b = testing::projected_rhs(system, 4);
  const Eigen::MatrixXd a0 = dense_matrix(system, kEuler);
  const Eigen::MatrixXd r1 = dense_rotations(system);
  PCG solver(parameters(Preconditioner::precomputed_warp, 3, 0.0), system.size());
  Points x(static_cast<std::size_t>(system.size()));
  EXPECT_EQ(solver.solve(system, kEuler, b, x).iterations, 3);
  Eigen::VectorXd reference = Eigen::VectorXd::Zero(3 * system.size());
  EXPECT_EQ(dense_pcg(a0, r1 * a0.inverse() * r1.transpose(), flatten(b), reference, 3, 0.0), 3);
  EXPECT_LT((flatten(x) - reference).norm() / reference.norm(), 1e-10);
  // Moved and linearised elsewhere, with other factors: still A0's inverse, turned by the new R.
  const Mat3<double> more = Eigen::AngleAxisd(-0.9, Vec3<double>(0, 0.3, 1).normalized()).toRotationMatrix();
  for (auto& point : system.state.position) point = (more * point).eval();
  Points f(x.size(), Vec3<double>::Zero());
  system.compute_force(system.state.position, f);
  const MatrixFactors<double> later{1.3, -0.05, -0.03};
  const Points b2 = testing::projected_rhs(system, 5);
  const Eigen::MatrixXd r2 = dense_rotations(system);
  ASSERT_GT((r2 - r1).norm(), 1.0);
  solver.solve(system, later, b2, x);
  EXPECT_EQ(dense_pcg(dense_matrix(system, later), r2 * a0.inverse() * r2.transpose(), flatten(b2), reference, 3, 0.0), 3);
  EXPECT_LT((flatten(x) - reference).norm() / reference.norm(), 1e-10);
  // use_rotations false: A0^-1 alone.
  auto plain_parameters = parameters(Preconditioner::precomputed_warp, 3, 0.0);
  plain_parameters.warp_rotations = false;
  auto turned = small_beam(9, &turn);
  PCG plain(plain_parameters, turned.size());
  Points y(x.size());
  plain.solve(turned, kEuler, b, y);
  reference.setZero();
  dense_pcg(a0, a0.inverse(), flatten(b), reference, 3, 0.0);
  EXPECT_LT((flatten(y) - reference).norm() / reference.norm(), 1e-10);
}

TEST(PreconditionedConjugateGradient, CarriedStateResumesBitwise) {
  const Mat3<double> turn = Eigen::AngleAxisd(0.3, Vec3<double>(0, 0, 1)).toRotationMatrix();
  for (const auto& [preconditioner, update_step] : std::vector<std::pair<Preconditioner, int>>{
           {Preconditioner::block_jacobi, 1}, {Preconditioner::block_jacobi, 3}, {Preconditioner::sparse_ldlt, 1},
           {Preconditioner::sparse_ldlt, 3}, {Preconditioner::precomputed_warp, 1}, {Preconditioner::precomputed_warp, 3}}) {
    auto system = small_beam(6, preconditioner == Preconditioner::precomputed_warp ? &turn : nullptr);
    const auto p = parameters(preconditioner, 4, 1e-12, update_step);
    PCG first(p, system.size());
    Points x(static_cast<std::size_t>(system.size()));
    first.solve(system, kEuler, testing::projected_rhs(system, 1), x);
    first.solve(system, {1.2, -0.05, -0.02}, testing::projected_rhs(system, 2), x);
    const auto state = first.carried_state();
    const std::size_t matrix_values =
        1 + (3 * x.size() + 1) + 2 * static_cast<std::size_t>(system.assemble(kEuler).nonZeros());
    const bool warp = preconditioner == Preconditioner::precomputed_warp;
    const std::size_t kept = preconditioner == Preconditioner::sparse_ldlt ? matrix_values
                             : warp                                        ? matrix_values + 9 * x.size()
                                                                           : 9 * x.size();
    EXPECT_EQ(state.size(), 1 + 3 * x.size() + (update_step > 1 ? kept : warp ? matrix_values : 0));
    PCG resumed(p, system.size());
    resumed.restore_carried_state(state);
    Points y(x.size());
    const MatrixFactors<double> later{0.9, -0.05, -0.01};
    first.solve(system, later, testing::projected_rhs(system, 3), x);
    resumed.solve(system, later, testing::projected_rhs(system, 3), y);
    EXPECT_TRUE(x == y) << preconditioner_name(preconditioner) << " update_step " << update_step;
    // Without the state, the third solve starts elsewhere (and, with update_step 3, builds anew).
    PCG fresh(p, system.size());
    fresh.solve(system, later, testing::projected_rhs(system, 3), y);
    EXPECT_FALSE(x == y);
    EXPECT_THROW(resumed.restore_carried_state({}), Error);
    EXPECT_THROW(resumed.restore_carried_state(std::vector<std::int64_t>(state.size() + 1, 0)), Error);
    if (preconditioner == Preconditioner::sparse_ldlt && update_step > 1) {
      // A damaged matrix is named, not factorised: a row index out of range, a truncated list.
      auto damaged = state;
      damaged[1 + 3 * x.size() + 1 + (3 * x.size() + 1)] = -5;
      EXPECT_THROW(resumed.restore_carried_state(damaged), Error);
      damaged = state;
      damaged.pop_back();
      EXPECT_THROW(resumed.restore_carried_state(damaged), Error);
    }
  }
}

TEST(PreconditionedConjugateGradient, PointsWithoutMassOrElementsAreLeftAlone) {
  // Point 1 has no mass (a mesh file's unused vertex): its row of A is zero and so is its
  // right-hand side; P is the identity there and the others solve as usual.
  auto system = mass_system({1.0, 0.0, 2.0});
  const Points b = {Vec3<double>(1, 2, 3), Vec3<double>::Zero(), Vec3<double>(2, 2, 2)};
  for (const auto preconditioner : {Preconditioner::jacobi, Preconditioner::block_jacobi}) {
    PCG solver(parameters(preconditioner, 5, 1e-20), 3);
    Points x(3);
    EXPECT_EQ(solver.solve(system, kMassOnly, b, x).iterations, 1) << preconditioner_name(preconditioner);
    EXPECT_EQ(solver.preconditioner_blocks()[1], Mat3<double>::Identity());
    EXPECT_EQ(x[0], b[0]);
    EXPECT_EQ(x[1], Vec3<double>::Zero());
    EXPECT_EQ(x[2], Vec3<double>(1, 1, 1));
  }
}

TEST(PreconditionedConjugateGradient, NonFiniteDiagonalIsNamedAndWrongSizesRejected) {
  auto system = mass_system({1.0, 2.0, 3.0});
  const Points b(3, Vec3<double>(1, 1, 1));
  Points x(3);
  const MatrixFactors<double> infinite{std::numeric_limits<double>::infinity(), 0.0, 0.0};
  PCG block(parameters(Preconditioner::block_jacobi, 5, 1e-10), 3);
  try {
    block.solve(system, infinite, b, x);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("diagonal block of point 0"), std::string::npos) << error.what();
  }
  PCG jacobi(parameters(Preconditioner::jacobi, 5, 1e-10), 3);
  try {
    jacobi.solve(system, infinite, b, x);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("point 0, axis x is inf"), std::string::npos) << error.what();
  }
  PCG other_size(parameters(Preconditioner::none, 5, 1e-10), 4);
  EXPECT_THROW(other_size.solve(system, kMassOnly, b, x), Error);
}

TEST(PreconditionedConjugateGradient, FixedPointsStayZero) {
  auto system = small_beam(8);
  const Points b = testing::projected_rhs(system, 9);
  PCG solver(parameters(Preconditioner::block_jacobi, 10, 1e-14), system.size());
  Points x(b.size());
  solver.solve(system, kEuler, b, x);
  for (Index i : system.fixed) EXPECT_EQ(x[static_cast<std::size_t>(i)], Vec3<double>::Zero());
}

TEST(PreconditionedConjugateGradient, FloatInstantiation) {
  MechanicalSystem<float> system;
  system.state.position.assign(2, Vec3<float>::Zero());
  system.mass = Mass<float>::lumped({1.0f, 4.0f});
  system.finalize();
  PreconditionedConjugateGradientSolver<float> solver({}, 2);
  const std::vector<Vec3<float>> b = {Vec3<float>(1, 2, 3), Vec3<float>(4, 8, 12)};
  std::vector<Vec3<float>> x(2);
  solver.solve(system, {1.0f, 0.0f, 0.0f}, b, x);
  EXPECT_EQ(x[1], Vec3<float>(1, 2, 3));
  PreconditionedConjugateGradientSolver<float> restored({}, 2);
  restored.restore_carried_state(solver.carried_state());
  EXPECT_EQ(restored.carried_state(), solver.carried_state());
}

}  // namespace
}  // namespace fastcorot
