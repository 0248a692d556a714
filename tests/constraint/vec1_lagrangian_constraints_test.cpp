// UniformLagrangianConstraint and StopperLagrangianConstraint on a Vec1 state (edge extensions of a
// DistanceMapping) against rows and violations written by hand, and their resolutions on small
// problems with known solutions.
#include "fastcorot/constraint/vec1_lagrangian_constraints.h"
#include "fastcorot/core/error.h"
#include "fastcorot/mapping/distance_mapping.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace fastcorot {
namespace {

// Three points of object 0 joined by edges (0, 1) and (1, 2); at the step's start they sit at
// `start` moving with velocity `v`, after the free motion their velocity is `free_v`.
struct Wire {
  std::vector<Vec3<double>> start = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}};
  std::vector<Vec3<double>> v = {{0, 0, 0}, {0.1, 0, 0}, {0, 0, 0}};
  std::vector<Vec3<double>> free_v = {{0, 0, 0}, {0.3, 0.2, 0}, {0, 0.5, 0.1}};
  std::vector<Edge> edges = {{0, 1}, {1, 2}};
  std::vector<double> rest_lengths = {0.9, 2.0};

  ConstraintPoints<double> points() const {
    ConstraintPoints<double> p;
    p.mapping = std::make_shared<DistanceMapping<double>>(edges, start, rest_lengths);
    p.rest_position.assign(2, Vec3<double>::Zero());
    p.constraint_force = std::make_shared<std::vector<Vec3<double>>>(2, Vec3<double>::Zero());
    MechanicalState<double> begin{start, v, start}, free{start, free_v, start};
    p.prepare(begin, free, 0.1);
    return p;
  }
};

TEST(UniformLagrangianConstraint, OneRowPerEdgeOnItsEndsAndSofasViolations) {
  const Wire wire;
  UniformLagrangianConstraint<double> uniform("test", wire.points(), {1, true, false});
  ConstraintRows<double> rows(1);
  uniform.build(rows);
  ASSERT_EQ(rows.size(), 2);
  const Eigen::MatrixXd ht(rows.transposed(0, 3));
  // Edge 0 along x, edge 1 along y: -u on the first end, +u on the second.
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(9, 2);
  expected(0, 0) = -1, expected(3, 0) = 1;
  expected(4, 1) = -1, expected(7, 1) = 1;
  EXPECT_LT((ht - expected).norm(), 1e-15) << ht;
  // Extensions at the start 0.1 and 0; J v_free: 0.3 and 0.5 - 0.2.
  double dfree[2];
  uniform.violation(ConstraintOrder::position_and_velocity, 0.1, dfree);
  EXPECT_NEAR(dfree[0], 0.1 + 0.1 * 0.3, 1e-15);
  EXPECT_NEAR(dfree[1], 0.0 + 0.1 * 0.3, 1e-15);
  uniform.violation(ConstraintOrder::velocity, 0.1, dfree);
  EXPECT_NEAR(dfree[0], 0.3 + 0.1 / 0.1, 1e-14);
  EXPECT_NEAR(dfree[1], 0.3, 1e-15);
  // Held at the rest values instead (here zero, as SOFA's mapped state keeps them).
  UniformLagrangianConstraint<double> to_rest("test", wire.points(), {1, true, true});
  ConstraintRows<double> rows2(1);
  to_rest.build(rows2);
  to_rest.violation(ConstraintOrder::position_and_velocity, 0.1, dfree);
  EXPECT_NEAR(dfree[0], 0.13, 1e-15);
}

TEST(UniformLagrangianConstraint, BlockOrRowResolutionsSolveTheSameSystem) {
  const Wire wire;
  DenseMatrix<double> w(2, 2);
  w << 2.0, 0.5, 0.5, 1.0;
  for (const bool iterative : {true, false}) {
    UniformLagrangianConstraint<double> uniform("test", wire.points(), {1, iterative, false});
    ConstraintRows<double> rows(1);
    uniform.build(rows);
    ConstraintProblem<double> problem;
    problem.clear(2);
    problem.w = w;
    problem.dfree << 0.3, -0.2;
    uniform.add_resolutions(problem);
    problem.check_blocks();
    EXPECT_EQ(problem.resolutions.size(), iterative ? 2u : 1u);
    // Gauss–Seidel sweeps over the blocks: the block solves W λ = -δ at once, the rows converge to it.
    for (std::size_t b = 0; b < problem.resolutions.size(); ++b) problem.resolutions[b]->init(problem.first_line[b], w, problem.f.data());
    for (int sweep = 0; sweep < 200; ++sweep) {
      for (std::size_t b = 0; b < problem.resolutions.size(); ++b) {
        problem.d = problem.dfree + w * problem.f;
        problem.resolutions[b]->resolve(problem.first_line[b], w, problem.d.data(), problem.f.data(), problem.dfree.data());
      }
    }
    const Eigen::Vector2d exact = -Eigen::Matrix2d(w).inverse() * Eigen::Vector2d(0.3, -0.2);
    EXPECT_LT((problem.f - exact).norm(), 1e-12) << (iterative ? "rows" : "block");
  }
}

TEST(UniformLagrangianConstraint, RefusesBadCoordinates) {
  const Wire wire;
  EXPECT_THROW(UniformLagrangianConstraint<double>("test", wire.points(), {0, true, false}), Error);
  EXPECT_THROW(UniformLagrangianConstraint<double>("test", wire.points(), {4, true, false}), Error);
}

TEST(StopperLagrangianConstraint, RowOnOneValueAndItsFreeValue) {
  const Wire wire;
  StopperLagrangianConstraint<double> stopper("test", wire.points(), {1, -0.5, 0.02});
  ConstraintRows<double> rows(1);
  stopper.build(rows);
  ASSERT_EQ(rows.size(), 1);
  const Eigen::MatrixXd ht(rows.transposed(0, 3));
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(9);
  expected(4) = -1, expected(7) = 1;
  EXPECT_LT((ht.col(0) - expected).norm(), 1e-15);
  double dfree = 0;
  // Edge 1's free extension 0 + 0.1 · 0.3, in either order (SOFA reads positions in both).
  stopper.violation(ConstraintOrder::velocity, 0.1, &dfree);
  EXPECT_NEAR(dfree, 0.03, 1e-15);
  EXPECT_THROW(StopperLagrangianConstraint<double>("test", wire.points(), {2, -1, 1}), Error);
  EXPECT_THROW(StopperLagrangianConstraint<double>("test", wire.points(), {0, 1, -1}), Error);
}

TEST(StopperResolution, ClampsTheValueIntoItsBounds) {
  DenseMatrix<double> w(1, 1);
  w << 4.0;
  StopperResolution<double> stopper(-0.1, 0.2);
  const auto solve = [&](double free_value) {
    double f = 7;  // overwritten by init, as SOFA starts from 0
    stopper.init(0, w, &f);
    EXPECT_EQ(f, 0.0);
    for (int k = 0; k < 3; ++k) {
      const double d = free_value + 4.0 * f;
      stopper.resolve(0, w, &d, &f, &free_value);
    }
    return f;
  };
  EXPECT_NEAR(solve(0.5), (0.2 - 0.5) / 4.0, 1e-16);   // above max: brought back to max
  EXPECT_NEAR(solve(-0.3), (-0.1 + 0.3) / 4.0, 1e-16);  // below min: up to min
  EXPECT_EQ(solve(0.05), 0.0);                          // inside: no force
}

}  // namespace
}  // namespace fastcorot
