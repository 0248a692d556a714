// Constraint corrections against dense linear algebra: W = h H A⁻¹ Hᵀ with A the free motion's
// matrix (written column by column from the matrix-free product, inverted by Eigen's LU), through a
// direct solver's sparse triangular solves and through an iterative solver; the correction dx =
// A⁻¹ Hᵀλ; UncoupledConstraintCorrection's W = Hᵀ C H; the projection of H's columns.
#include "fastcorot/constraint/constraint_corrections.h"
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/sim/sparse_direct_solver.h"

#include "support/solver_systems.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

namespace fastcorot {
namespace {

using testing::grid_system;

constexpr double kDt = 0.05;

// The 4 × 3 × 3 grid (fixed at x = 0) after one implicit Euler step, with `linear` as its solver.
SimulatedObject<double> stepped_grid(std::unique_ptr<LinearSolver<double>> linear) {
  SimulatedObject<double> object;
  object.path = "grid";
  object.system = grid_system(3, 0.1);
  object.system.gravity = Vec3<double>(0, -9.81, 0);
  ImplicitEulerSolver<double>::Parameters p;
  p.rayleigh_mass = 0.1;
  p.rayleigh_stiffness = 0.1;
  object.ode_solver = std::make_unique<ImplicitEulerSolver<double>>(p);
  object.linear_solver = std::move(linear);
  object.ode_solver->step(object.system, *object.linear_solver, kDt);
  return object;
}

// Five rows of H on points of the grid, one of them also on a fixed point (its entry projected away).
Eigen::SparseMatrix<double> rows_transposed(Index points) {
  std::vector<Eigen::Triplet<double>> t;
  const auto add = [&](int row, Index point, const Vec3<double>& c) {
    for (int k = 0; k < 3; ++k) t.emplace_back(3 * point + k, row, c[k]);
  };
  add(0, 35, Vec3<double>(1, 0, 0));
  add(1, 35, Vec3<double>(0, 0.6, 0.8));
  add(2, 20, Vec3<double>(-1, 0, 0));
  add(2, 23, Vec3<double>(1, 0, 0));
  add(3, 10, Vec3<double>(0.3, -0.4, 0.5));
  add(3, 0, Vec3<double>(1, 1, 1));  // point 0 is fixed
  add(4, 17, Vec3<double>(0, 0, 1));
  Eigen::SparseMatrix<double> ht(3 * points, 5);
  ht.setFromTriplets(t.begin(), t.end());
  return ht;
}

Eigen::MatrixXd expected_compliance(const SimulatedObject<double>& object, const Eigen::SparseMatrix<double>& ht) {
  const auto factors = object.ode_solver->integration_factors(kDt);
  const Eigen::MatrixXd a = testing::dense_system_matrix(object.system, factors->matrix);
  const Eigen::MatrixXd h = Eigen::MatrixXd(ht);
  return kDt * h.transpose() * a.lu().solve(h);
}

TEST(LinearSolverConstraintCorrection, ComplianceThroughADirectSolverIsDenseHAinvHt) {
  SimulatedObject<double> object = stepped_grid(std::make_unique<SparseDirectSolver<double>>());
  ASSERT_NE(object.linear_solver->factorisation(), nullptr);
  const Eigen::SparseMatrix<double> ht = projection_matrix(object.system) * rows_transposed(object.system.size());
  EXPECT_EQ(Eigen::VectorXd(ht.col(3)).segment<3>(0).norm(), 0.0) << "the fixed point's entry is projected away";
  const Eigen::MatrixXd expected = expected_compliance(object, ht);
  LinearSolverConstraintCorrection<double> correction("test", 0);
  DenseMatrix<double> w = DenseMatrix<double>::Zero(5, 5);
  correction.add_compliance(object, ht, ConstraintOrder::position_and_velocity, kDt, w);
  EXPECT_LT((Eigen::MatrixXd(w) - expected).norm(), 1e-12 * expected.norm());
  // Velocity order: the velocity factor (1) instead of h.
  DenseMatrix<double> wv = DenseMatrix<double>::Zero(5, 5);
  correction.add_compliance(object, ht, ConstraintOrder::velocity, kDt, wv);
  EXPECT_LT((Eigen::MatrixXd(wv) - expected / kDt).norm(), 1e-12 * expected.norm() / kDt);
}

TEST(LinearSolverConstraintCorrection, ComplianceThroughAnIterativeSolverMatchesToItsTolerance) {
  ConjugateGradientSolver<double>::Parameters p;
  p.iterations = 2000;
  p.tolerance = 1e-30;
  p.threshold = 1e-30;
  SimulatedObject<double> object = stepped_grid(std::make_unique<ConjugateGradientSolver<double>>(p));
  EXPECT_EQ(object.linear_solver->factorisation(), nullptr);
  const Eigen::SparseMatrix<double> ht = projection_matrix(object.system) * rows_transposed(object.system.size());
  const Eigen::MatrixXd expected = expected_compliance(object, ht);
  LinearSolverConstraintCorrection<double> correction("test", 0, 0.25);
  DenseMatrix<double> w = DenseMatrix<double>::Zero(5, 5);
  correction.add_compliance(object, ht, ConstraintOrder::position_and_velocity, kDt, w);
  const Eigen::MatrixXd regularised = expected + 0.25 * Eigen::MatrixXd::Identity(5, 5);
  EXPECT_LT((Eigen::MatrixXd(w) - regularised).norm(), 1e-9 * regularised.norm());
}

TEST(LinearSolverConstraintCorrection, CorrectsByTheImpulseThroughA) {
  SimulatedObject<double> object = stepped_grid(std::make_unique<SparseDirectSolver<double>>());
  const auto x_free = object.system.state.position;
  const auto v_free = object.system.state.velocity;
  const Eigen::SparseMatrix<double> ht = projection_matrix(object.system) * rows_transposed(object.system.size());
  Eigen::VectorXd lambda(5);
  lambda << 0.3, -0.2, 0.5, 0.1, -0.4;
  const Eigen::VectorXd impulse = ht * lambda;
  const auto factors = object.ode_solver->integration_factors(kDt);
  const Eigen::VectorXd dx = testing::dense_system_matrix(object.system, factors->matrix).lu().solve(impulse);
  LinearSolverConstraintCorrection<double>("test", 0).correct(object, testing::points_of(impulse),
                                                              ConstraintOrder::position_and_velocity, kDt);
  const Eigen::VectorXd x = testing::flat_vector(object.system.state.position);
  const Eigen::VectorXd v = testing::flat_vector(object.system.state.velocity);
  EXPECT_LT((x - testing::flat_vector(x_free) - kDt * dx).norm(), 1e-13);
  EXPECT_LT((v - testing::flat_vector(v_free) - dx).norm(), 1e-12);
}

TEST(UncoupledConstraintCorrection, ComplianceIsHtCH) {
  SimulatedObject<double> object = stepped_grid(std::make_unique<SparseDirectSolver<double>>());
  const Index n = object.system.size();
  const Eigen::SparseMatrix<double> ht = rows_transposed(n);
  // Points 10..35 (the range), compliance 1e-3 (1 + i/100).
  UncoupledConstraintCorrection<double>::Parameters p;
  p.offset = 10;
  Eigen::VectorXd c = Eigen::VectorXd::Zero(3 * n);
  for (Index i = 10; i < n; ++i) {
    const double value = 1e-3 * (1 + i / 100.0);
    p.compliance.push_back(value * Mat3<double>::Identity());
    c.segment<3>(3 * i).setConstant(value);
  }
  UncoupledConstraintCorrection<double> correction("test", 0, p);
  DenseMatrix<double> w = DenseMatrix<double>::Zero(5, 5);
  correction.add_compliance(object, ht, ConstraintOrder::position_and_velocity, kDt, w);
  const Eigen::MatrixXd h = Eigen::MatrixXd(ht);
  const Eigen::MatrixXd expected = kDt * h.transpose() * c.asDiagonal() * h;  // point 0 (outside the range) adds nothing
  EXPECT_LT((Eigen::MatrixXd(w) - expected).norm(), 1e-15);
  // The correction without the ODE factors: x += dx, v += dx / dt.
  p.use_ode_factors = false;
  const auto x_free = object.system.state.position;
  Eigen::VectorXd lambda = Eigen::VectorXd::Ones(5);
  const Eigen::VectorXd impulse = ht * lambda;
  UncoupledConstraintCorrection<double>("test", 0, p).correct(object, testing::points_of(impulse),
                                                              ConstraintOrder::position_and_velocity, kDt);
  const Eigen::VectorXd moved = testing::flat_vector(object.system.state.position) - testing::flat_vector(x_free);
  EXPECT_LT((moved - c.asDiagonal() * impulse).norm(), 1e-15);
}

TEST(ProjectionMatrix, ZeroesHeldPointsAndAppliesPartialProjectors) {
  MechanicalSystem<double> system = grid_system(1, 0);
  system.projections.push_back({5, Vec3<double>(1, 0, 1).asDiagonal()});
  system.moving.push_back(7);
  const Eigen::MatrixXd p = Eigen::MatrixXd(projection_matrix(system));
  const auto block = [&](Index i) { return Eigen::Matrix3d(p.block(3 * i, 3 * i, 3, 3)); };
  EXPECT_EQ(block(0).norm(), 0.0);  // fixed
  EXPECT_EQ(block(7).norm(), 0.0);  // moving
  EXPECT_EQ(block(5), Eigen::Matrix3d(Vec3<double>(1, 0, 1).asDiagonal()));
  EXPECT_EQ(block(10), Eigen::Matrix3d::Identity());
  system.couplings.push_back({1, 2});
  EXPECT_THROW(projection_matrix(system), Error);
}

}  // namespace
}  // namespace fastcorot
