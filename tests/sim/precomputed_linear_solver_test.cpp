// PrecomputedLinearSolver: SOFA's PrecomputedLinearSolver (PrecomputedLinearSolver.inl, 2a278d891f):
// x = A0^-1 b with A0 the matrix of the first solve. Reference: Eigen's dense solve of A0, taken
// column by column from the matrix-free product.
#include "fastcorot/sim/precomputed_linear_solver.h"

#include "fastcorot/core/error.h"
#include "support/random_rhs.h"
#include "support/solver_systems.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using testing::dense_system_matrix;
using testing::flat_vector;

TEST(PrecomputedLinearSolver, EverySolveUsesTheFirstMatrix) {
  auto system = testing::grid_system(3);
  PrecomputedLinearSolver<double> solver;
  const Eigen::MatrixXd a0 = dense_system_matrix(system, testing::kEulerFactors);
  Points x(static_cast<std::size_t>(system.size()));
  const Points b1 = testing::projected_rhs(system, 1);
  solver.solve(system, testing::kEulerFactors, b1, x);
  const Eigen::VectorXd first = a0.ldlt().solve(flat_vector(b1));
  EXPECT_LT((flat_vector(x) - first).norm() / first.norm(), 1e-12);
  // Other factors (another step's matrix): still A0.
  const Points b2 = testing::projected_rhs(system, 2);
  const MatrixFactors<double> later{3.0, -0.1, -0.2};
  solver.solve(system, later, b2, x);
  const Eigen::VectorXd with_a0 = a0.ldlt().solve(flat_vector(b2));
  const Eigen::VectorXd with_a1 = dense_system_matrix(system, later).ldlt().solve(flat_vector(b2));
  EXPECT_LT((flat_vector(x) - with_a0).norm() / with_a0.norm(), 1e-12);
  EXPECT_GT((flat_vector(x) - with_a1).norm() / with_a1.norm(), 1e-3);
}

TEST(PrecomputedLinearSolver, CarriesTheFirstMatrix) {
  auto system = testing::grid_system(4);
  PrecomputedLinearSolver<double> solver, resumed;
  Points x(static_cast<std::size_t>(system.size())), y(x.size());
  EXPECT_EQ(solver.carried_state(), (std::vector<std::int64_t>{0, 0}));
  solver.solve(system, testing::kEulerFactors, testing::projected_rhs(system, 1), x);
  resumed.restore_carried_state(solver.carried_state());
  const Points b = testing::projected_rhs(system, 3);
  solver.solve(system, {2.0, 0.0, -1.0}, b, x);
  resumed.solve(system, {2.0, 0.0, -1.0}, b, y);
  EXPECT_EQ(x, y);
  EXPECT_THROW(resumed.restore_carried_state({12, 5, 1}), Error);
  // A system of another size than A0's.
  auto small = testing::grid_system(4);
  small.state.position.pop_back();
  EXPECT_THROW(solver.solve(small, testing::kEulerFactors, b, x), Error);
}

}  // namespace
}  // namespace fastcorot
