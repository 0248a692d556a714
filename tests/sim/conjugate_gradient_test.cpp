// ConjugateGradientSolver: SOFA's CGLinearSolver (docs/sofa-solvers.md §2). The small systems are
// built from masses alone (A = m M is then diagonal with known eigenvalues, so every CG iterate can
// be worked out by hand) and from one tetrahedron with a mass (compared with a dense direct solve).
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/conjugate_gradient.h"

#include "fastcorot/core/error.h"
#include "support/deformations.h"
#include "support/mass_system.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using CG = ConjugateGradientSolver<double>;
using testing::flatten;

using testing::mass_system;

constexpr MatrixFactors<double> kMassOnly{1.0, 0.0, 0.0};

CG::Parameters parameters(int iterations, double tolerance, double threshold) {
  CG::Parameters p;
  p.iterations = iterations;
  p.tolerance = tolerance;
  p.threshold = threshold;
  return p;
}

Points random_points(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  return testing::perturbed(Points(n, Vec3<double>::Zero()), 1.0, rng);
}

// The 2×2 example used for the stopping rules: points 0 and 1 with masses 1 and 3, b = (e_x, e_x).
// Along x, A = diag(1, 3) and b = (1, 1). CG by hand (docs/sofa-solvers.md §2.3):
//   it 1: rho = 2, err = 1, p = (1, 1), q = (1, 3), den = 4, alpha = 1/2,
//         x = (1/2, 1/2), r = (1/2, -1/2)
//   it 2: rho = 1/2, err = sqrt(1/2)/sqrt(2) = 1/2 (exactly, in floating point too),
//         beta = 1/4, p = (3/4, -1/4), q = (3/4, -3/4), den = 3/4, alpha = 2/3,
//         x = (1, 1/3), r = 0
//   it 3: err = 0.
struct TwoByTwo {
  MechanicalSystem<double> system = mass_system({1.0, 3.0});
  Points b{Vec3<double>(1, 0, 0), Vec3<double>(1, 0, 0)};
  Points x{Vec3<double>(9, 9, 9), Vec3<double>(9, 9, 9)};  // overwritten by every solve
};

TEST(ConjugateGradient, DefaultsAreSofas) {
  // docs/sofa-solvers.md §2.1: iterations 25, tolerance 1e-5, threshold 1e-5.
  const CG solver;
  EXPECT_EQ(solver.parameters().iterations, 25);
  EXPECT_EQ(solver.parameters().tolerance, 1e-5);
  EXPECT_EQ(solver.parameters().threshold, 1e-5);
}

TEST(ConjugateGradient, ConstructorRejectsBadParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(CG(parameters(0, 1e-5, 1e-5)), Error);
  EXPECT_THROW(CG(parameters(-3, 1e-5, 1e-5)), Error);
  EXPECT_THROW(CG(parameters(10, -1e-5, 1e-5)), Error);
  EXPECT_THROW(CG(parameters(10, nan, 1e-5)), Error);
  EXPECT_THROW(CG(parameters(10, inf, 1e-5)), Error);
  EXPECT_THROW(CG(parameters(10, 1e-5, -1e-5)), Error);
  EXPECT_THROW(CG(parameters(10, 1e-5, nan)), Error);
  EXPECT_THROW(CG(parameters(10, 1e-5, inf)), Error);
  EXPECT_NO_THROW(CG(parameters(1, 0.0, 0.0)));
}

TEST(ConjugateGradient, ScaledIdentityConvergesInOneIteration) {
  // A = 2 I: the first step gives x = b/2 exactly and r = 0; iteration 2 stops on tolerance.
  auto system = mass_system({2.0, 2.0, 2.0, 2.0});
  const Points b = random_points(4, 1);
  Points x(4);
  CG solver(parameters(25, 1e-10, 1e-12));
  for (int solve = 0; solve < 2; ++solve) {  // the same on the first and on later solves
    const auto report = solver.solve(system, kMassOnly, b, x);
    EXPECT_EQ(report.iterations, 1);
    EXPECT_LE(report.relative_residual, 1e-15);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((x[i] - b[i] / 2).norm(), 1e-15);
  }
}

TEST(ConjugateGradient, DiagonalWithKDistinctEigenvaluesConvergesInKIterations) {
  // CG ends in at most k steps when A has k distinct eigenvalues and not before when b has a
  // component along each eigenspace (any random b does).
  const std::vector<std::vector<double>> cases = {{1, 1, 2, 2, 5, 5, 5}, {1, 2, 2, 4, 8}, {3, 3, 3, 3, 7}};
  const std::vector<int> distinct = {3, 4, 2};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    auto system = mass_system(cases[c]);
    const Points b = random_points(cases[c].size(), 2 + static_cast<unsigned>(c));
    Points x(cases[c].size());
    CG solver(parameters(25, 1e-10, 1e-12));
    const auto report = solver.solve(system, kMassOnly, b, x);
    EXPECT_EQ(report.iterations, distinct[c]) << "case " << c;
    EXPECT_LE(report.relative_residual, 1e-10);
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_LT((x[i] - b[i] / cases[c][i]).norm(), 1e-12);
  }
}

TEST(ConjugateGradient, IteratesOfTheTwoByTwoExample) {
  TwoByTwo t;
  CG one(parameters(1, 0.0, 0.0));  // stops after the first update
  auto report = one.solve(t.system, kMassOnly, t.b, t.x);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_EQ(report.relative_residual, 0.5);
  EXPECT_EQ(t.x[0], Vec3<double>(0.5, 0, 0));
  EXPECT_EQ(t.x[1], Vec3<double>(0.5, 0, 0));

  CG two(parameters(25, 0.0, 0.0));
  report = two.solve(t.system, kMassOnly, t.b, t.x);
  EXPECT_EQ(report.iterations, 2);
  EXPECT_LT((t.x[0] - Vec3<double>(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((t.x[1] - Vec3<double>(1.0 / 3, 0, 0)).norm(), 1e-15);
}

TEST(ConjugateGradient, ToleranceIsOnTheNormRatioAndInclusive) {
  // After iteration 1, |r|/|b| = 1/2 exactly (|r|²/|b|² would be 1/4).
  {
    TwoByTwo t;
    CG solver(parameters(25, 0.5, 0.0));  // err <= tolerance: stops at the start of iteration 2
    const auto report = solver.solve(t.system, kMassOnly, t.b, t.x);
    EXPECT_EQ(report.iterations, 1);
    EXPECT_EQ(report.relative_residual, 0.5);
    EXPECT_EQ(t.x[1], Vec3<double>(0.5, 0, 0));
  }
  {
    TwoByTwo t;
    CG solver(parameters(25, 0.3, 0.0));  // 0.25 <= 0.3 < 0.5: a squared ratio would stop here
    const auto report = solver.solve(t.system, kMassOnly, t.b, t.x);
    EXPECT_EQ(report.iterations, 2);
    EXPECT_LT((t.x[1] - Vec3<double>(1.0 / 3, 0, 0)).norm(), 1e-15);
  }
}

TEST(ConjugateGradient, OnlyTheFirstSolveIgnoresToleranceAtIterationOne) {
  // tolerance = 1: at iteration 1 err = 1 <= 1. The first solve of the instance goes on anyway
  // (SOFA warns), every later solve stops there with x = 0.
  TwoByTwo t;
  CG solver(parameters(25, 1.0, 0.0));
  auto report = solver.solve(t.system, kMassOnly, t.b, t.x);
  EXPECT_EQ(report.iterations, 1);  // stops at iteration 2 (err = 1/2 <= 1)
  EXPECT_EQ(t.x[0], Vec3<double>(0.5, 0, 0));
  for (int solve = 0; solve < 2; ++solve) {
    report = solver.solve(t.system, kMassOnly, t.b, t.x);
    EXPECT_EQ(report.iterations, 0);
    EXPECT_EQ(report.relative_residual, 1.0);
    EXPECT_EQ(t.x[0], Vec3<double>::Zero());
    EXPECT_EQ(t.x[1], Vec3<double>::Zero());
  }
  // A new instance is exempt again.
  CG fresh(parameters(25, 1.0, 0.0));
  EXPECT_EQ(fresh.solve(t.system, kMassOnly, t.b, t.x).iterations, 1);
}

TEST(ConjugateGradient, CarriedStateIsTheSolveCountAndRestoresTheFirstSolveRule) {
  // The only thing a CG instance carries between solves is whether it has solved before (the
  // example above): a checkpoint saves it so that a resumed run's next solve stops as it would
  // have.
  TwoByTwo t;
  CG used(parameters(25, 1.0, 0.0));
  EXPECT_EQ(used.carried_state(), std::vector<std::int64_t>{0});
  used.solve(t.system, kMassOnly, t.b, t.x);
  used.solve(t.system, kMassOnly, t.b, t.x);
  EXPECT_EQ(used.carried_state(), std::vector<std::int64_t>{2});
  CG restored(parameters(25, 1.0, 0.0));
  restored.restore_carried_state(used.carried_state());
  EXPECT_EQ(restored.solve(t.system, kMassOnly, t.b, t.x).iterations,
            0);  // as a third solve: stops at once
  EXPECT_EQ(t.x[0], Vec3<double>::Zero());
  EXPECT_THROW(restored.restore_carried_state({}), Error);
  EXPECT_THROW(restored.restore_carried_state({1, 2}), Error);
  EXPECT_THROW(restored.restore_carried_state({-1}), Error);
}

TEST(ConjugateGradient, ThresholdIsAbsoluteOnCurvatureAndSparesOnlyTheFirstSolve) {
  // A = I, b = 1e-4 e_x at one point: p^T A p = 1e-8 <= threshold 1e-5.
  auto system = mass_system({1.0});
  const Points tiny = {Vec3<double>(1e-4, 0, 0)};
  Points x = {Vec3<double>(5, 5, 5)};
  CG solver(parameters(25, 1e-12, 1e-5));
  // First solve: iteration 1 does not stop on the threshold; x = b, then r = 0 stops iteration 2.
  auto report = solver.solve(system, kMassOnly, tiny, x);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_EQ(x[0], tiny[0]);
  // Second solve: stops at iteration 1 before updating x.
  report = solver.solve(system, kMassOnly, tiny, x);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(x[0], Vec3<double>::Zero());
  EXPECT_EQ(report.relative_residual, 1.0);
  // The threshold is absolute: the same rhs with a heavier point (den = 1e6 · 1e-8 = 1e-2) solves.
  auto heavy = mass_system({1e6});
  report = solver.solve(heavy, kMassOnly, tiny, x);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_LT((x[0] - tiny[0] / 1e6).norm(), 1e-25);
  // A large rhs on the light point solves too.
  const Points large = {Vec3<double>(0, 2, 0)};
  report = solver.solve(system, kMassOnly, large, x);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_EQ(x[0], large[0]);
}

TEST(ConjugateGradient, ThresholdStopsLaterIterationsEvenOnTheFirstSolve) {
  // Two-by-two example: den = 4 at iteration 1, 3/4 at iteration 2.
  {
    TwoByTwo t;
    CG solver(parameters(25, 0.0, 1.0));  // 3/4 <= 1: stop at iteration 2 without updating x
    const auto report = solver.solve(t.system, kMassOnly, t.b, t.x);
    EXPECT_EQ(report.iterations, 1);
    EXPECT_EQ(t.x[0], Vec3<double>(0.5, 0, 0));
    EXPECT_EQ(t.x[1], Vec3<double>(0.5, 0, 0));
    EXPECT_EQ(report.relative_residual, 0.5);
  }
  {
    TwoByTwo t;
    CG solver(parameters(25, 0.0, 0.74));  // 3/4 > 0.74: goes on to the exact solution
    const auto report = solver.solve(t.system, kMassOnly, t.b, t.x);
    EXPECT_EQ(report.iterations, 2);
    EXPECT_LT((t.x[1] - Vec3<double>(1.0 / 3, 0, 0)).norm(), 1e-15);
  }
}

TEST(ConjugateGradient, MaximumIterationsAreRespected) {
  // Three distinct eigenvalues need three iterations; two are allowed.
  auto system = mass_system({1, 1, 2, 2, 5, 5, 5});
  const Points b = random_points(7, 3);
  Points x(7);
  CG solver(parameters(2, 1e-12, 1e-12));
  const auto report = solver.solve(system, kMassOnly, b, x);
  EXPECT_EQ(report.iterations, 2);
  EXPECT_GT(report.relative_residual, 1e-6);
  // The reported residual is |b - A x| / |b| of the returned x.
  Points ax(7);
  system.multiply(kMassOnly, x, ax);
  double r2 = 0, b2 = 0;
  for (std::size_t i = 0; i < 7; ++i) {
    r2 += (b[i] - ax[i]).squaredNorm();
    b2 += b[i].squaredNorm();
  }
  EXPECT_NEAR(report.relative_residual, std::sqrt(r2 / b2), 1e-12);
}

TEST(ConjugateGradient, ZeroRhsReturnsZeroAndCountsAsASolve) {
  auto system = mass_system({1.0, 3.0});
  const Points zero(2, Vec3<double>::Zero());
  Points x(2, Vec3<double>(4, 4, 4));
  CG solver(parameters(25, 1.0, 0.0));
  const auto report = solver.solve(system, kMassOnly, zero, x);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(report.relative_residual, 0.0);
  EXPECT_EQ(x[0], Vec3<double>::Zero());
  EXPECT_EQ(x[1], Vec3<double>::Zero());
  // SOFA increments its solve counter after a null rhs too (CGLinearSolver.inl, timeStepCount++ after
  // the "null norm of vector b" branch), so the next solve is no longer the first one.
  TwoByTwo t;
  EXPECT_EQ(solver.solve(t.system, kMassOnly, t.b, t.x).iterations, 0);
}

TEST(ConjugateGradient, ZeroCurvatureStopsEvenOnTheFirstSolve) {
  // m = 0: A = 0, den = 0 -> stop before updating x (the den == 0 test has no first-solve exemption).
  TwoByTwo t;
  CG solver(parameters(25, 1e-5, 1e-5));
  const auto report = solver.solve(t.system, {0.0, 0.0, 0.0}, t.b, t.x);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(t.x[0], Vec3<double>::Zero());
  EXPECT_EQ(t.x[1], Vec3<double>::Zero());
}

// One tetrahedron with a lumped mass, deformed, with point 0 fixed; A = M - h (h + rs) K.
struct OneTetrahedron {
  MechanicalSystem<double> system;
  MatrixFactors<double> factors{1.0, -0.1, -0.1 * (0.1 + 0.05)};  // implicit Euler, h = 0.1, rs = 0.05
  Points b;
  Eigen::MatrixXd dense;  // assembled independently from the field's stiffness and the masses
};

OneTetrahedron one_tetrahedron() {
  OneTetrahedron t;
  const Points rest = {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1)};
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  CorotationalForceField<double>::Parameters p;
  p.young_modulus = {1000.0};
  p.poisson_ratio = {0.3};
  auto field = std::make_shared<CorotationalForceField<double>>(mesh, rest, p);
  std::mt19937 rng(7);
  const Points x = testing::perturbed(rest, 0.1, rng);
  Points f(4, Vec3<double>::Zero());
  field->add_force(x, f);  // linearise at x
  t.system.state.position = x;
  t.system.state.rest_position = rest;
  t.system.force_fields.push_back(field);
  // density 6: 6 · (1/6) / 4 = 0.25 per vertex.
  t.system.mass = Mass<double>::lumped({0.25, 0.25, 0.25, 0.25});
  t.system.fixed = {0};
  t.system.finalize();
  t.b = random_points(4, 8);
  t.b[0].setZero();  // solvers receive projected right-hand sides
  const Eigen::MatrixXd k(field->stiffness_matrix(1.0));
  t.dense = t.factors.m * 0.25 * Eigen::MatrixXd::Identity(12, 12) + (t.factors.k) * k;
  return t;
}

// Solves the free block of `dense` (fixed point 0 removed: rows and columns 0..2).
Eigen::VectorXd dense_free_solve(const Eigen::MatrixXd& dense, const Eigen::VectorXd& b) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(12);
  x.tail(9) = dense.bottomRightCorner(9, 9).llt().solve(b.tail(9));
  return x;
}

TEST(ConjugateGradient, SolvesAnSpdFemSystemLikeADirectSolve) {
  auto t = one_tetrahedron();
  const Eigen::VectorXd expected = dense_free_solve(t.dense, flatten(t.b));
  Points x(4, Vec3<double>(1, 1, 1));
  CG solver(parameters(100, 1e-14, 1e-30));
  const auto report = solver.solve(t.system, t.factors, t.b, x);
  EXPECT_LE(report.iterations, 9 + 3);  // 9 unknowns: n steps in exact arithmetic, a few more in rounding
  EXPECT_LT(testing::relative_error(flatten(x), expected), 1e-10);
  EXPECT_EQ(x[0], Vec3<double>::Zero());  // stays in the constrained space
}

TEST(ConjugateGradient, ProjectedOperatorKeepsFixedPointsAtZero) {
  // With a projected b every p, q and x stays zero at the fixed points (docs/sofa-solvers.md §2.3 notes).
  auto system = mass_system({1.0, 2.0, 3.0});
  system.fixed = {1};
  system.finalize();
  Points b = random_points(3, 9);
  system.project(b);
  Points x(3);
  CG solver(parameters(25, 1e-12, 1e-20));
  solver.solve(system, kMassOnly, b, x);
  EXPECT_EQ(x[1], Vec3<double>::Zero());
  EXPECT_LT((x[0] - b[0]).norm(), 1e-14);
  EXPECT_LT((x[2] - b[2] / 3).norm(), 1e-14);
}

TEST(ConjugateGradient, FloatInstantiation) {
  MechanicalSystem<float> system;
  system.state.position.assign(2, Vec3<float>::Zero());
  system.mass = Mass<float>::lumped({1.0f, 3.0f});
  system.finalize();
  const std::vector<Vec3<float>> b = {Vec3<float>(1, 0, 0), Vec3<float>(1, 0, 0)};
  std::vector<Vec3<float>> x(2);
  ConjugateGradientSolver<float> solver;
  const auto report = solver.solve(system, {1.0f, 0.0f, 0.0f}, b, x);
  EXPECT_EQ(report.iterations, 2);
  EXPECT_NEAR(x[1].x(), 1.0f / 3, 1e-6f);
}

}  // namespace
}  // namespace fastcorot
