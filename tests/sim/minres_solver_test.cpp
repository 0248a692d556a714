// MinResSolver: SOFA's MinResLinearSolver (MinResLinearSolver.inl, SOFA 2a278d891f). References:
// Eigen's dense solves of the same matrix (taken column by column from the matrix-free product),
// and MINRES's exact behaviour on A = c I, worked out by hand.
#include "fastcorot/sim/minres_solver.h"

#include "fastcorot/core/error.h"
#include "support/mass_system.h"
#include "support/random_rhs.h"
#include "support/solver_systems.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using MinRes = MinResSolver<double>;
using testing::dense_system_matrix;
using testing::flat_vector;

MinRes::Parameters parameters(int iterations, double tolerance) {
  MinRes::Parameters p;
  p.iterations = iterations;
  p.tolerance = tolerance;
  return p;
}

TEST(MinResSolver, DefaultsAreSofas) {
  // MinResLinearSolver: iterations 25, tolerance 1e-5.
  const MinRes::Parameters p;
  EXPECT_EQ(p.iterations, 25);
  EXPECT_EQ(p.tolerance, 1e-5);
}

TEST(MinResSolver, RejectsBadParameters) {
  EXPECT_THROW(MinRes(parameters(0, 1e-5), 3), Error);
  EXPECT_THROW(MinRes(parameters(-2, 1e-5), 3), Error);
  EXPECT_THROW(MinRes(parameters(5, -1.0), 3), Error);
  EXPECT_THROW(MinRes(parameters(5, std::nan("")), 3), Error);
  EXPECT_THROW(MinRes(parameters(5, 1e-5), -1), Error);
  try {
    MinRes(parameters(0, 1e-5), 3);
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("iterations"), std::string::npos) << error.what();
  }
  auto system = testing::mass_system({1.0, 2.0});
  MinRes solver(parameters(5, 1e-5), 3);
  Points b(2), x(2);
  EXPECT_THROW(solver.solve(system, {1, 0, 0}, b, x), Error);  // made for 3 points
}

TEST(MinResSolver, SolvesASymmetricPositiveDefiniteSystemAsEigen) {
  auto system = testing::grid_system(3);
  const Points b = testing::projected_rhs(system, 5);
  const Eigen::MatrixXd a = dense_system_matrix(system, testing::kEulerFactors);
  const Eigen::VectorXd exact = a.ldlt().solve(flat_vector(b));
  MinRes solver(parameters(1000, 1e-14), system.size());
  Points x(static_cast<std::size_t>(system.size()));
  const auto report = solver.solve(system, testing::kEulerFactors, b, x);
  EXPECT_GT(report.iterations, 5);
  EXPECT_LT(report.iterations, 1000);
  EXPECT_LT((flat_vector(x) - exact).norm() / exact.norm(), 1e-9);
  EXPECT_LT((a * flat_vector(x) - flat_vector(b)).norm() / flat_vector(b).norm(), 1e-9);
}

TEST(MinResSolver, SolvesAnIndefiniteSystemAsEigen) {
  // m M + k K with m < 0 and k = -1: the stiffness (positive semi-definite as -K) minus a thousand times the
  // mass has eigenvalues of both signs (here -709 .. 14317, none within 1 of zero).
  auto system = testing::grid_system(7);
  const MatrixFactors<double> factors{-1000.0, 0.0, -1.0};
  const Eigen::MatrixXd a = dense_system_matrix(system, factors);
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues();
  ASSERT_LT(eigenvalues.minCoeff(), -1.0);
  ASSERT_GT(eigenvalues.maxCoeff(), 1.0);
  const Points b = testing::projected_rhs(system, 8);
  const Eigen::VectorXd exact = a.partialPivLu().solve(flat_vector(b));
  MinRes solver(parameters(2000, 1e-15), system.size());
  Points x(static_cast<std::size_t>(system.size()));
  solver.solve(system, factors, b, x);
  EXPECT_LT((flat_vector(x) - exact).norm() / exact.norm(), 1e-8);
}

TEST(MinResSolver, StopsAfterOneIterationWhenTheLanczosVectorsBreakDown) {
  // A = 2 I: v1 = b / |b|, A v1 = 2 v1, so alpha = 2 and the next Lanczos vector is 0 (beta2 = 0):
  // SOFA stops after the first iteration (beta2 / beta1 < 10 eps) with x = phi w = b / 2.
  auto system = testing::mass_system({2.0, 2.0});
  const Points b = {Vec3<double>(1, 2, 3), Vec3<double>(-4, 0, 0.5)};
  MinRes solver(parameters(25, 0.0), 2);
  Points x(2);
  const auto report = solver.solve(system, {1, 0, 0}, b, x);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_LT((x[0] - Vec3<double>(0.5, 1, 1.5)).norm(), 1e-15);
  EXPECT_LT((x[1] - Vec3<double>(-2, 0, 0.25)).norm(), 1e-15);
}

TEST(MinResSolver, StartsFromItsPreviousSolution) {
  // A = diag(1, 3) along x: from zero, b = (1, 1) takes two iterations (two eigenvalues).
  auto system = testing::mass_system({1.0, 3.0});
  MinRes solver(parameters(25, 1e-14), 2);
  Points x = {Vec3<double>(9, 9, 9), Vec3<double>(9, 9, 9)};  // not a start: overwritten
  const Points b = {Vec3<double>(1, 0, 0), Vec3<double>(1, 0, 0)};
  EXPECT_EQ(solver.solve(system, {1, 0, 0}, b, x).iterations, 2);
  EXPECT_LT((x[1] - Vec3<double>(1.0 / 3, 0, 0)).norm(), 1e-14);
  // b = A x_prev + (0, 0, 1) at point 0: from x_prev the residual (0, 0, 1) is an eigenvector, one
  // iteration solves it (from zero it would take two again).
  const Points shifted = {Vec3<double>(1, 0, 1), Vec3<double>(1, 0, 0)};
  EXPECT_EQ(solver.solve(system, {1, 0, 0}, shifted, x).iterations, 1);
  EXPECT_LT((x[0] - Vec3<double>(1, 0, 1)).norm(), 1e-14);
  EXPECT_LT((x[1] - Vec3<double>(1.0 / 3, 0, 0)).norm(), 1e-14);
}

TEST(MinResSolver, StopsAtItsIterationsAndItsTolerance) {
  auto system = testing::grid_system(4);
  const Points b = testing::projected_rhs(system, 9);
  Points x(static_cast<std::size_t>(system.size()));
  MinRes three(parameters(3, 0.0), system.size());
  EXPECT_EQ(three.solve(system, testing::kEulerFactors, b, x).iterations, 3);
  MinRes loose(parameters(1000, 1e-3), system.size());
  MinRes tight(parameters(1000, 1e-10), system.size());
  const int loose_iterations = loose.solve(system, testing::kEulerFactors, b, x).iterations;
  const int tight_iterations = tight.solve(system, testing::kEulerFactors, b, x).iterations;
  EXPECT_LT(loose_iterations, tight_iterations);
  EXPECT_LT(tight_iterations, 1000);
}

TEST(MinResSolver, CarriesItsPreviousSolution) {
  auto system = testing::grid_system(5);
  const Points b = testing::projected_rhs(system, 2);
  MinRes first(parameters(4, 0.0), system.size()), resumed(parameters(4, 0.0), system.size());
  Points x(static_cast<std::size_t>(system.size())), y(x.size());
  first.solve(system, testing::kEulerFactors, b, x);
  resumed.restore_carried_state(first.carried_state());
  first.solve(system, testing::kEulerFactors, b, x);
  resumed.solve(system, testing::kEulerFactors, b, y);
  EXPECT_EQ(x, y);
  EXPECT_THROW(resumed.restore_carried_state({1, 2}), Error);
}

}  // namespace
}  // namespace fastcorot
