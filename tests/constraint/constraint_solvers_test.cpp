// Constraint solvers on small problems with known solutions: bilateral blocks reach λ = -W⁻¹ δ_free
// (Eigen's LU as the reference), unilateral rows reach the complementarity solution (worked out by
// enumeration of the active sets), SOFA's stopping rule (tolerance × rows) and warm start, against a
// straightforward Gauss–Seidel written here from SOFA's description.
#include "fastcorot/constraint/constraint_solvers.h"
#include "fastcorot/core/error.h"
#include "support/constraint_problems.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <memory>

namespace fastcorot {
namespace {

using testing::bilateral_problem;
using testing::random_vector;
using testing::spd;

TEST(BlockGaussSeidelSolver, BilateralBlocksReachTheLinearSolution) {
  const int n = 9;
  const DenseMatrix<double> w = spd(n, 1);
  const DenseVector<double> dfree = random_vector(n, 2);
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
  ConstraintSolverParameters<double> p;
  p.tolerance = 1e-14;
  p.max_iterations = 10000;
  BlockGaussSeidelSolver<double> solver(p);
  const ConstraintSolveReport report = solver.solve(problem);
  EXPECT_TRUE(report.converged);
  const Eigen::VectorXd expected = -Eigen::MatrixXd(w).lu().solve(Eigen::VectorXd(dfree));
  EXPECT_LT((Eigen::VectorXd(problem.f) - expected).norm(), 1e-11 * expected.norm());
  // Stored as the next step's warm start: the same problem again converges in one sweep.
  ConstraintProblem<double> again = bilateral_problem(w, dfree, previous);
  EXPECT_EQ(solver.solve(again).iterations, 1);
  EXPECT_LT((Eigen::VectorXd(again.f) - expected).norm(), 1e-11 * expected.norm());
}

// A straightforward projected block Gauss–Seidel as SOFA describes it (bilateral 3-blocks and
// the summed block error), for the iteration count and the values.
struct Reference {
  Eigen::VectorXd f;
  int iterations = 0;
};
Reference reference_gauss_seidel(const Eigen::MatrixXd& w, const Eigen::VectorXd& dfree, double tolerance, int max_iterations) {
  const int n = static_cast<int>(dfree.size());
  Reference r{Eigen::VectorXd::Zero(n), 0};
  for (int it = 0; it < max_iterations; ++it) {
    r.iterations = it + 1;
    double error = 0;
    for (int j = 0; j < n; j += 3) {
      const Eigen::Vector3d old = r.f.segment<3>(j);
      const Eigen::Vector3d d = dfree.segment<3>(j) + w.middleRows(j, 3) * r.f;
      r.f.segment<3>(j) -= w.block<3, 3>(j, j).inverse() * d;
      // SOFA's block error: for each row l, the length of (W_lm Δλ_m)_m.
      const Eigen::Matrix3d terms = w.block<3, 3>(j, j) * (r.f.segment<3>(j) - old).asDiagonal();
      error += terms.rowwise().norm().sum();
    }
    if (error < tolerance * n) break;
  }
  return r;
}

TEST(BlockGaussSeidelSolver, StopsBySofasRuleScaledByTheRowCount) {
  const int n = 12;
  const DenseMatrix<double> w = spd(n, 3) + 3.0 * spd(n, 5);  // more coupling: more iterations
  const DenseVector<double> dfree = random_vector(n, 4);
  for (double tolerance : {1e-2, 1e-4, 1e-7}) {
    std::vector<Vec3<double>> previous;
    ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
    ConstraintSolverParameters<double> p;
    p.tolerance = tolerance;
    BlockGaussSeidelSolver<double> solver(p);
    const ConstraintSolveReport report = solver.solve(problem);
    const Reference expected = reference_gauss_seidel(w, dfree, tolerance, 1000);
    EXPECT_EQ(report.iterations, expected.iterations) << tolerance;
    EXPECT_DOUBLE_EQ(report.tolerance, tolerance * n);
    EXPECT_LT((Eigen::VectorXd(problem.f) - expected.f).norm(), 1e-12) << tolerance;
  }
}

// W as contacts on separate objects make it: rows couple only within their group, zero elsewhere
// (groups interleaved, so that each block's columns fall in several spans, with a short gap).
TEST(BlockGaussSeidelSolver, SkipsWsZeroColumnsAndGivesTheFullRowsResult) {
  const int blocks = 12, n = 3 * blocks;
  const auto group_of = [](int block) { return block < 3 ? 0 : (block < 9 ? 1 + block % 2 : 0); };
  const DenseMatrix<double> full = spd(n, 7) + 2.0 * spd(n, 8);
  DenseMatrix<double> w = DenseMatrix<double>::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (group_of(i / 3) == group_of(j / 3)) w(i, j) = full(i, j);  // a principal submatrix per group: still SPD
    }
  }
  const DenseVector<double> dfree = random_vector(n, 9);
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
  problem.find_column_spans();
  // Block 3 (group 2: blocks 3, 5, 7) reaches columns 9..12, 15..18 and 21..24: gaps of 3 columns
  // are kept inside one span.
  ASSERT_EQ(problem.span_begin.size(), static_cast<std::size_t>(blocks + 1));
  ASSERT_EQ(problem.span_begin[4] - problem.span_begin[3], 1);
  EXPECT_EQ(problem.spans[static_cast<std::size_t>(problem.span_begin[3])], (std::array<int, 2>{9, 24}));
  // Block 0 (group 0: blocks 0-2 and 9-11): two spans, the gap between them longer than the
  // shortest one skipped.
  ASSERT_EQ(problem.span_begin[1] - problem.span_begin[0], 2);
  EXPECT_EQ(problem.spans[0], (std::array<int, 2>{0, 9}));
  EXPECT_EQ(problem.spans[1], (std::array<int, 2>{27, 36}));
  for (int row = 0; row < n; ++row) {
    problem.f = random_vector(n, 10 + row);
    const double expected = w.row(row).dot(problem.f);
    EXPECT_NEAR(problem.row_times_lambda(row, static_cast<std::size_t>(row / 3)), expected, 1e-13 * (1 + std::abs(expected)));
  }
  problem.f.setZero();
  ConstraintSolverParameters<double> p;
  p.tolerance = 1e-6;
  BlockGaussSeidelSolver<double> solver(p);
  const ConstraintSolveReport report = solver.solve(problem);
  const Reference expected = reference_gauss_seidel(Eigen::MatrixXd(w), Eigen::VectorXd(dfree), p.tolerance, 1000);
  EXPECT_EQ(report.iterations, expected.iterations);
  EXPECT_LT((Eigen::VectorXd(problem.f) - expected.f).norm(), 1e-12 * expected.f.norm());
}

TEST(BlockGaussSeidelSolver, ReportsAnUnconvergedSolve) {
  const int n = 12;
  const DenseMatrix<double> w = spd(n, 3) + 3.0 * spd(n, 5);
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, random_vector(n, 4), previous);
  ConstraintSolverParameters<double> p;
  p.tolerance = 1e-12;
  p.max_iterations = 2;
  const ConstraintSolveReport report = BlockGaussSeidelSolver<double>(p).solve(problem);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 2);
  EXPECT_GT(report.error, report.tolerance);
}

TEST(BlockGaussSeidelSolver, UnilateralRowsReachTheComplementaritySolution) {
  // Three coupled rows: λ >= 0, d = δ + W λ >= 0, λ·d = 0 (the reference enumerates active sets).
  DenseMatrix<double> w(3, 3);
  w << 2.0, 0.5, 0.2, 0.5, 1.5, 0.3, 0.2, 0.3, 1.0;
  DenseVector<double> dfree(3);
  dfree << -1.0, 0.4, -0.3;
  const auto solution = testing::complementarity_solution(w, dfree);
  ASSERT_TRUE(solution);
  const Eigen::Vector3d expected = *solution;
  ConstraintProblem<double> problem;
  problem.clear(3);
  problem.w = w;
  problem.dfree = dfree;
  for (int i = 0; i < 3; ++i) problem.add_block(std::make_unique<UnilateralResolution<double>>());
  ConstraintSolverParameters<double> p;
  p.tolerance = 1e-15;
  BlockGaussSeidelSolver<double>(p).solve(problem);
  EXPECT_LT((Eigen::Vector3d(problem.f) - expected).norm(), 1e-12);
  EXPECT_EQ(problem.f[1], 0.0) << "the row pushed apart stays free";
}

TEST(UnbuiltGaussSeidelSolver, StartsFromZeroEveryStep) {
  const int n = 6;
  const DenseMatrix<double> w = spd(n, 7) + spd(n, 8);
  const DenseVector<double> dfree = random_vector(n, 9);
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
  ConstraintSolverParameters<double> p;
  p.tolerance = 1e-10;
  UnbuiltGaussSeidelSolver<double> solver(p);
  const int first = solver.solve(problem).iterations;
  ConstraintProblem<double> again = bilateral_problem(w, dfree, previous);
  EXPECT_EQ(solver.solve(again).iterations, first) << "no warm start";
  EXPECT_GT(first, 1);
}

TEST(NNCGSolver, BilateralBlocksReachTheLinearSolution) {
  const int n = 12;
  const DenseMatrix<double> w = spd(n, 3) + 3.0 * spd(n, 5);
  const DenseVector<double> dfree = random_vector(n, 4);
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
  ConstraintSolverParameters<double> p;
  p.tolerance = 1e-14;
  const ConstraintSolveReport report = NNCGSolver<double>(p).solve(problem);
  EXPECT_TRUE(report.converged);
  const Eigen::VectorXd expected = -Eigen::MatrixXd(w).lu().solve(Eigen::VectorXd(dfree));
  EXPECT_LT((Eigen::VectorXd(problem.f) - expected).norm(), 1e-10 * expected.norm());
}

TEST(PreconditionedConjugateResidualSolver, ReachesTheLinearSolutionInAtMostTheRowCount) {
  // Conjugate residuals on an SPD system end at the solution after n iterations (round-off
  // aside); with a zero tolerance SOFA's measure never stops it earlier.
  const int n = 9;
  const DenseMatrix<double> w = spd(n, 11);
  const DenseVector<double> dfree = random_vector(n, 12);
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
  ConstraintSolverParameters<double> p;
  p.tolerance = 0;
  p.max_iterations = 1000;
  const ConstraintSolveReport report = PreconditionedConjugateResidualSolver<double>(p).solve(problem);
  EXPECT_EQ(report.iterations, n);
  const Eigen::VectorXd expected = -Eigen::MatrixXd(w).lu().solve(Eigen::VectorXd(dfree));
  EXPECT_LT((Eigen::VectorXd(problem.f) - expected).norm(), 1e-10 * expected.norm());
  // Fewer iterations than rows: an approximation, reported as unconverged.
  ConstraintProblem<double> again = bilateral_problem(w, dfree, previous);
  p.max_iterations = 3;
  p.tolerance = 1e-12;
  const ConstraintSolveReport short_report = PreconditionedConjugateResidualSolver<double>(p).solve(again);
  EXPECT_EQ(short_report.iterations, 3);
  EXPECT_FALSE(short_report.converged);
}

TEST(PreconditionedConjugateResidualSolver, StopsAtAZeroResidualWithoutDividingByZero) {
  // W the identity: the first iteration lands on the solution (residual exactly zero).
  const DenseMatrix<double> w = DenseMatrix<double>::Identity(3, 3);
  DenseVector<double> dfree(3);
  dfree << 0.5, -0.25, 2.0;
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
  ConstraintSolverParameters<double> p;
  p.tolerance = 0;
  const ConstraintSolveReport report = PreconditionedConjugateResidualSolver<double>(p).solve(problem);
  EXPECT_TRUE(problem.f.allFinite());
  EXPECT_EQ(Eigen::VectorXd(problem.f), Eigen::VectorXd(-dfree));
  EXPECT_TRUE(report.converged);
  // Nothing to do at all.
  ConstraintProblem<double> zero = bilateral_problem(w, DenseVector<double>::Zero(3), previous);
  PreconditionedConjugateResidualSolver<double>(p).solve(zero);
  EXPECT_EQ(Eigen::VectorXd(zero.f), Eigen::VectorXd::Zero(3));
}

TEST(ConstraintSolver, SvdRegularizationReachesOnlyTheRowsOfWsNullSpace) {
  // Rows 0 and 1 are the same constraint twice (W singular along (1, -1, 0, 0)); rows 2 and 3 are
  // independent. SOFA's SVD rule regularises rows 0 and 1 only; the plain rule every row.
  DenseMatrix<double> w(4, 4);
  w << 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 3;
  for (bool svd : {true, false}) {
    ConstraintProblem<double> problem;
    problem.clear(4);
    problem.w = w;
    problem.dfree << -1, -1, -1, -1;
    for (int i = 0; i < 4; ++i) problem.add_block(std::make_unique<UnilateralResolution<double>>());
    ConstraintSolverParameters<double> p;
    p.regularization = 0.5;
    p.svd_regularization = svd;
    p.tolerance = 1e-12;
    EXPECT_TRUE(BlockGaussSeidelSolver<double>(p).solve(problem).converged);
    Eigen::Vector4d diagonal(1.5, 1.5, svd ? 2.0 : 2.5, svd ? 3.0 : 3.5);
    EXPECT_EQ(Eigen::Vector4d(problem.w.diagonal()), diagonal) << svd;
    EXPECT_EQ(problem.w(0, 1), 1.0);
    // The regularised duplicate rows share the push: 1.5 λ0 + λ1 = 1 = λ0 + 1.5 λ1.
    EXPECT_NEAR(problem.f[0], 0.4, 1e-11);
    EXPECT_NEAR(problem.f[1], 0.4, 1e-11);
  }
}

TEST(ConstraintSolver, RefusesBadParameters) {
  ConstraintSolverParameters<double> p;
  p.max_iterations = 0;
  EXPECT_THROW(BlockGaussSeidelSolver<double>{p}, Error);
  p = {};
  p.tolerance = std::nan("");
  EXPECT_THROW(BlockGaussSeidelSolver<double>{p}, Error);
  p = {};
  p.sor = 2.5;
  EXPECT_THROW(BlockGaussSeidelSolver<double>{p}, Error);
}

}  // namespace
}  // namespace fastcorot
