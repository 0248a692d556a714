// ImprovedJacobiConstraintSolver and LCPConstraintSolver on small problems: bilateral blocks reach
// λ = -W⁻¹ δ_free (Eigen's LU), unilateral rows and frictionless contacts reach the complementarity
// solution (active sets enumerated), a frictional contact sticks inside Coulomb's disk and slides on
// its edge (closed forms), and each solver's iterations against a straightforward loop written
// here from SOFA's description (sofa-constraints.md §2.4).
#include "fastcorot/constraint/constraint_solvers.h"
#include "fastcorot/constraint/lcp_constraint_solver.h"
#include "fastcorot/core/error.h"
#include "support/constraint_problems.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <memory>

namespace fastcorot {
namespace {

using testing::bilateral_problem;
using testing::random_vector;
using testing::spd;

ConstraintSolverParameters<double> tight(double tolerance = 1e-13, int iterations = 100000) {
  ConstraintSolverParameters<double> p;
  p.tolerance = tolerance;
  p.max_iterations = iterations;
  return p;
}

// ---- ImprovedJacobiConstraintSolver ----

TEST(ImprovedJacobiSolver, BilateralBlocksReachTheLinearSolution) {
  const int n = 9;
  const DenseMatrix<double> w = spd(n, 21);
  const DenseVector<double> dfree = random_vector(n, 22);
  const Eigen::VectorXd expected = -Eigen::MatrixXd(w).lu().solve(Eigen::VectorXd(dfree));
  for (bool momentum : {false, true}) {
    std::vector<Vec3<double>> previous;
    ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
    typename ImprovedJacobiSolver<double>::Options o;
    o.conjugate_residue = momentum;
    const ConstraintSolveReport report = ImprovedJacobiSolver<double>(tight(), o).solve(problem);
    EXPECT_TRUE(report.converged) << momentum;
    EXPECT_LT((Eigen::VectorXd(problem.f) - expected).norm(), 1e-10 * expected.norm()) << momentum;
  }
}

TEST(ImprovedJacobiSolver, UnilateralRowsReachTheComplementaritySolution) {
  DenseMatrix<double> w(3, 3);
  w << 2.0, 0.5, 0.2, 0.5, 1.5, 0.3, 0.2, 0.3, 1.0;
  DenseVector<double> dfree(3);
  dfree << -1.0, 0.4, -0.3;
  const auto expected = testing::complementarity_solution(w, dfree);
  ASSERT_TRUE(expected);
  ConstraintProblem<double> problem;
  problem.clear(3);
  problem.w = w;
  problem.dfree = dfree;
  for (int i = 0; i < 3; ++i) problem.add_block(std::make_unique<UnilateralResolution<double>>());
  EXPECT_TRUE(ImprovedJacobiSolver<double>(tight(), {}).solve(problem).converged);
  EXPECT_LT((Eigen::VectorXd(problem.f) - *expected).norm(), 1e-12);
}

// SOFA's iteration as its description reads, for bilateral 3-blocks: every block against the
// violations of the previous iteration scaled by ρ, a momentum step β Δλ, the summed block errors
// with the changes known so far.
struct JacobiReference {
  Eigen::VectorXd f;
  int iterations = 0;
};
JacobiReference reference_jacobi(const Eigen::MatrixXd& w, const Eigen::VectorXd& dfree, double tolerance, int max_iterations,
                                 double rho, bool momentum, double speed) {
  const int n = static_cast<int>(dfree.size());
  JacobiReference r{Eigen::VectorXd::Zero(n), 0};
  Eigen::VectorXd d = dfree, last = Eigen::VectorXd::Zero(n), change = Eigen::VectorXd::Zero(n);
  for (int it = 0; it < max_iterations; ++it) {
    r.iterations = it + 1;
    const double beta = momentum ? std::min(1.0, std::pow(double(float(it) / float(max_iterations)), speed)) : 0.0;
    d += w * change;
    const Eigen::VectorXd scaled = rho * d;
    double error = 0;
    for (int j = 0; j < n; j += 3) {
      r.f.segment<3>(j) -= w.block<3, 3>(j, j).inverse() * scaled.segment<3>(j);
      r.f.segment<3>(j) += beta * change.segment<3>(j);
      change.segment<3>(j) = r.f.segment<3>(j) - last.segment<3>(j);
      last.segment<3>(j) = r.f.segment<3>(j);
      double block = 0;
      for (int l = j; l < j + 3; ++l) {
        for (int k = 0; k < n; ++k) block += (w(l, k) * change[k]) * (w(l, k) * change[k]);
      }
      error += std::sqrt(block);
    }
    if (error < tolerance * n && it > 0) break;
  }
  return r;
}

TEST(ImprovedJacobiSolver, IteratesAsSofaDescribesIt) {
  const int n = 12;
  const DenseMatrix<double> w = spd(n, 23) * 0.5;
  const DenseVector<double> dfree = random_vector(n, 24);
  // SOFA's spectral measure: the largest squared eigenvalue of W (symmetric here).
  const double largest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(w)).eigenvalues().maxCoeff();
  for (bool spectral : {false, true}) {
    for (bool momentum : {false, true}) {
      for (double tolerance : {1e-3, 1e-8}) {
        std::vector<Vec3<double>> previous;
        ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
        typename ImprovedJacobiSolver<double>::Options o;
        o.spectral_correction = spectral;
        o.spectral_factor = 0.8;
        o.conjugate_residue = momentum;
        o.conjugate_residue_speed = 2;
        const ConstraintSolveReport report = ImprovedJacobiSolver<double>(tight(tolerance, 300), o).solve(problem);
        const double rho = spectral ? 0.8 * std::min(1.0, 0.9 * 2 / (largest * largest)) : 1.0;
        const JacobiReference expected = reference_jacobi(w, dfree, tolerance, 300, rho, momentum, 2);
        EXPECT_EQ(report.iterations, expected.iterations) << spectral << momentum << tolerance;
        EXPECT_LT((Eigen::VectorXd(problem.f) - expected.f).norm(), 1e-11 * (1 + expected.f.norm())) << spectral << momentum << tolerance;
      }
    }
  }
}

TEST(ImprovedJacobiSolver, NeverStopsAfterItsFirstIteration) {
  // W the identity: the first iteration is exact, yet SOFA's rule asks for a second.
  const DenseMatrix<double> w = DenseMatrix<double>::Identity(3, 3);
  DenseVector<double> dfree(3);
  dfree << 0.5, -0.25, 2.0;
  std::vector<Vec3<double>> previous;
  ConstraintProblem<double> problem = bilateral_problem(w, dfree, previous);
  const ConstraintSolveReport report = ImprovedJacobiSolver<double>(tight(1e-3), {}).solve(problem);
  EXPECT_EQ(report.iterations, 2);
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(Eigen::VectorXd(problem.f), Eigen::VectorXd(-dfree));
}

TEST(ImprovedJacobiSolver, RefusesBadOptions) {
  typename ImprovedJacobiSolver<double>::Options o;
  o.spectral_factor = 0;
  EXPECT_THROW((ImprovedJacobiSolver<double>({}, o)), Error);
  o = {};
  o.conjugate_residue_speed = std::nan("");
  EXPECT_THROW((ImprovedJacobiSolver<double>({}, o)), Error);
}

// ---- LCPConstraintSolver ----

ConstraintProblem<double> lcp_problem(const DenseMatrix<double>& w, const DenseVector<double>& dfree) {
  ConstraintProblem<double> problem;
  problem.clear(static_cast<int>(dfree.size()));
  problem.w = w;
  problem.dfree = dfree;
  // The LCP solver ignores the resolutions; the rows still come in blocks.
  for (int i = 0; i < problem.size(); ++i) problem.add_block(std::make_unique<UnilateralResolution<double>>());
  return problem;
}

typename LCPConstraintSolver<double>::Options friction(double mu) {
  typename LCPConstraintSolver<double>::Options o;
  o.mu = mu;
  return o;
}

TEST(LCPConstraintSolver, FrictionlessContactsReachTheComplementaritySolution) {
  for (unsigned seed : {31u, 32u, 33u}) {
    const int n = 6;
    const DenseMatrix<double> w = spd(n, seed);
    const DenseVector<double> dfree = random_vector(n, seed + 100);
    const auto expected = testing::complementarity_solution(w, dfree);
    ASSERT_TRUE(expected);
    ConstraintProblem<double> problem = lcp_problem(w, dfree);
    const ConstraintSolveReport report = LCPConstraintSolver<double>(tight(1e-14), friction(0)).solve(problem);
    EXPECT_TRUE(report.converged);
    EXPECT_DOUBLE_EQ(report.tolerance, 1e-14) << "mu = 0: SOFA does not scale the tolerance";
    EXPECT_LT((Eigen::VectorXd(problem.f) - *expected).norm(), 1e-12) << seed;
  }
}

TEST(LCPConstraintSolver, FrictionlessIterationsAsSofaDescribesThem) {
  const int n = 8;
  const DenseMatrix<double> w = spd(n, 41) + 2.0 * spd(n, 42);
  const DenseVector<double> dfree = random_vector(n, 43);
  for (double tolerance : {1e-2, 1e-6, 1e-10}) {
    // Row by row: λ_i = max(0, -(δ_i + Σ_{k≠i} W_ik λ_k) / W_ii), error Σ |W_ii Δλ_i|, stop below tol.
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    int iterations = 0;
    for (int it = 0; it < 1000; ++it) {
      iterations = it + 1;
      double error = 0;
      for (int i = 0; i < n; ++i) {
        const double violation = dfree[i] + w.row(i).dot(f) - w(i, i) * f[i];
        const double before = f[i];
        f[i] = std::max(0.0, -violation / w(i, i));
        error += std::fabs(w(i, i) * (f[i] - before));
      }
      if (error < tolerance) break;
    }
    ConstraintProblem<double> problem = lcp_problem(w, dfree);
    const ConstraintSolveReport report = LCPConstraintSolver<double>(tight(tolerance, 1000), friction(0)).solve(problem);
    EXPECT_EQ(report.iterations, iterations) << tolerance;
    EXPECT_LT((Eigen::VectorXd(problem.f) - f).norm(), 1e-13) << tolerance;
  }
}

// One contact with W = c I (normal row first, then two tangents).
Eigen::Vector3d one_contact(const Eigen::Vector3d& dfree, double mu, double c = 0.5) {
  ConstraintProblem<double> problem = lcp_problem(c * DenseMatrix<double>::Identity(3, 3), dfree);
  EXPECT_TRUE(LCPConstraintSolver<double>(tight(1e-14), friction(mu)).solve(problem).converged);
  return problem.f;
}

TEST(LCPConstraintSolver, AContactSticksInsideCoulombsDiskAndSlidesOnItsEdge) {
  const double c = 0.5, mu = 0.6;
  // Pressed in, no tangential motion: λ_n = -δ_n / c.
  EXPECT_LT((one_contact({-0.1, 0, 0}, mu) - Eigen::Vector3d(0.2, 0, 0)).norm(), 1e-14);
  // Small tangential motion: held (λ_t = -δ_t / c, inside the disk |λ_t| <= mu λ_n).
  const Eigen::Vector3d stick = one_contact({-0.1, 0.02, -0.01}, mu);
  EXPECT_LT((stick - Eigen::Vector3d(0.2, -0.04, 0.02)).norm(), 1e-14);
  EXPECT_LT(stick.tail<2>().norm(), mu * stick[0]);
  // Large tangential motion: slides, λ_t on the disk's edge against the motion.
  const Eigen::Vector3d slip = one_contact({-0.1, 0.3, -0.4}, mu, c);
  EXPECT_NEAR(slip[0], 0.2, 1e-14);
  const Eigen::Vector2d expected_tangent = -mu * 0.2 * Eigen::Vector2d(0.3, -0.4).normalized();
  EXPECT_LT((slip.tail<2>() - expected_tangent).norm(), 1e-14);
  // Separating: no force at all.
  EXPECT_EQ(one_contact({0.1, 0.3, 0.2}, mu), Eigen::Vector3d::Zero());
}

TEST(LCPConstraintSolver, CoupledFrictionalContactsEndOnCoulombsLaw) {
  const int contacts = 4, n = 3 * contacts;
  const DenseMatrix<double> w = spd(n, 51);
  DenseVector<double> dfree = random_vector(n, 52);
  for (int c = 0; c < contacts; ++c) dfree[3 * c] = -std::fabs(dfree[3 * c]) - 0.2;  // all pressed in
  const double mu = 0.4;
  ConstraintProblem<double> problem = lcp_problem(w, dfree);
  const ConstraintSolveReport report = LCPConstraintSolver<double>(tight(1e-13), friction(mu)).solve(problem);
  EXPECT_TRUE(report.converged);
  EXPECT_DOUBLE_EQ(report.tolerance, 1e-13 * (contacts + 1)) << "SOFA's tolerance: tol × (contacts + 1)";
  const Eigen::VectorXd d = Eigen::VectorXd(dfree) + Eigen::MatrixXd(w) * Eigen::VectorXd(problem.f);
  int sliding = 0;
  for (int c = 0; c < contacts; ++c) {
    const double fn = problem.f[3 * c];
    const Eigen::Vector2d ft(problem.f[3 * c + 1], problem.f[3 * c + 2]);
    ASSERT_GE(fn, 0);
    EXPECT_LE(ft.norm(), mu * fn * (1 + 1e-12));
    if (fn > 0) EXPECT_NEAR(d[3 * c], 0, 1e-11) << c;  // in contact: no penetration left
    if (ft.norm() < mu * fn * (1 - 1e-9)) {
      EXPECT_LT(Eigen::Vector2d(d[3 * c + 1], d[3 * c + 2]).norm(), 1e-10) << c;  // sticking: no slip
    } else {
      ++sliding;
    }
  }
  EXPECT_GT(sliding, 0) << "the case should exercise sliding too";
}

TEST(LCPConstraintSolver, ContactsTooSoftOrTooStrongAreDropped) {
  DenseMatrix<double> w = 0.5 * DenseMatrix<double>::Identity(6, 6);
  w(3, 3) = 1e-9;  // the second contact's normal compliance
  DenseVector<double> dfree(6);
  dfree << -0.1, 0, 0, -0.1, 0, 0;
  typename LCPConstraintSolver<double>::Options o = friction(0.5);
  o.min_w = 1e-6;
  ConstraintProblem<double> problem = lcp_problem(w, dfree);
  LCPConstraintSolver<double>(tight(1e-12), o).solve(problem);
  EXPECT_NEAR(problem.f[0], 0.2, 1e-14);
  EXPECT_EQ(problem.f[3], 0.0) << "W_nn below minW: no force";
  o = friction(0.5);
  o.max_f = 0.15;
  w(3, 3) = 0.5;
  dfree[3] = -0.05;
  ConstraintProblem<double> strong = lcp_problem(w, dfree);
  LCPConstraintSolver<double>(tight(1e-12), o).solve(strong);
  EXPECT_EQ(strong.f[0], 0.0) << "λ_n = 0.2 >= maxF: dropped";
  EXPECT_NEAR(strong.f[3], 0.1, 1e-14);
}

TEST(LCPConstraintSolver, RefusesRowsThatAreNotContactsWithFriction) {
  ConstraintProblem<double> problem = lcp_problem(DenseMatrix<double>::Identity(4, 4), DenseVector<double>::Constant(4, -1.0));
  try {
    LCPConstraintSolver<double>({}, friction(0.6)).solve(problem);
    FAIL() << "4 rows are not contacts";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("4 rows"), std::string::npos) << e.what();
  }
  EXPECT_THROW((LCPConstraintSolver<double>({}, friction(-1))), Error);
}

}  // namespace
}  // namespace fastcorot
