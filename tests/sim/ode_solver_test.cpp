// ODE solvers (docs/sofa-solvers.md §1 EulerImplicitSolver, §3 StaticSolver / NewtonRaphsonSolver).
// Each step is compared with a reference computed here, densely, straight from the formulas of the
// notes (§1.2, §1.4, §1.5, §3.1, §3.2) and from independently built M and K: a second force field
// with the same parameters (its stiffness_matrix at x_n) and the masses written by hand.
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/ode_solver.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/conjugate_gradient.h"
#include "fastcorot/sim/sparse_direct_solver.h"
#include "support/deformations.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

using Field = CorotationalForceField<double>;
using Points = std::vector<Vec3<double>>;
using testing::flatten;
using testing::relative_error;
using testing::unflatten;

// Two tetrahedra sharing the face (0, 1, 2) (see mass_test.cpp); lumped masses at density 6.
std::shared_ptr<TetMesh> two_tets_mesh() {
  return std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{{0, 1, 2, 3}, {0, 2, 1, 4}});
}
Points two_tets_rest() {
  return {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1),
          Vec3<double>(0, 0, -2)};
}
const std::vector<double> kMasses = {0.75, 0.75, 0.75, 0.25, 0.5};
const Vec3<double> kGravity(0.0, -9.81, 0.3);
const Vec3<double> kConstantForce(2.0, 0.0, -1.0);  // on point 4

Field::Parameters field_parameters(RotationMethod method, double rayleigh = 0) {
  Field::Parameters p;
  p.young_modulus = {1000.0};
  p.poisson_ratio = {0.3};
  p.method = method;
  p.rayleigh_stiffness = rayleigh;
  return p;
}

Points random_points(std::size_t n, unsigned seed, double amplitude) {
  std::mt19937 rng(seed);
  return testing::perturbed(Points(n, Vec3<double>::Zero()), amplitude, rng);
}

MechanicalSystem<double> make_system(const Field::Parameters& parameters, const Points& x, const Points& v,
                                     std::vector<Index> fixed) {
  MechanicalSystem<double> system;
  system.state.position = x;
  system.state.velocity = v;
  system.state.rest_position = two_tets_rest();
  system.force_fields.push_back(std::make_shared<Field>(two_tets_mesh(), two_tets_rest(), parameters));
  system.mass = Mass<double>::lumped(kMasses);
  system.gravity = kGravity;
  system.constant_forces.push_back({{4}, {kConstantForce}});
  system.fixed = std::move(fixed);
  system.finalize();
  return system;
}

// The dense pieces of the reference, independent of MechanicalSystem.
struct Dense {
  Eigen::VectorXd f;  // total force at x (field + weight + constant force)
  Eigen::MatrixXd k;  // df/dx of the field at x
  Eigen::MatrixXd m;  // kron(diag(masses), I3)
  Eigen::MatrixXd p;  // projection: identity with the fixed rows zeroed
};

Dense dense_reference(const Field::Parameters& parameters, const Points& x, const std::vector<Index>& fixed) {
  Field field(two_tets_mesh(), two_tets_rest(), parameters);
  Points f(5, Vec3<double>::Zero());
  field.add_force(x, f);
  for (std::size_t i = 0; i < 5; ++i) f[i] += kMasses[i] * kGravity;
  f[4] += kConstantForce;
  Dense d;
  d.f = flatten(f);
  d.k = Eigen::MatrixXd(field.stiffness_matrix(1.0));
  d.m = Eigen::MatrixXd::Zero(15, 15);
  for (Eigen::Index i = 0; i < 15; ++i) d.m(i, i) = kMasses[static_cast<std::size_t>(i / 3)];
  d.p = Eigen::MatrixXd::Identity(15, 15);
  for (Index i : fixed) d.p.block<3, 3>(3 * i, 3 * i).setZero();
  return d;
}

// Solves A y = b on the free DOFs (fixed DOFs get 0): what both the Dirichlet-assembled direct solve
// and CG in the projected space compute (docs/sofa-solvers.md §2.3 notes, §4.1).
Eigen::VectorXd free_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const std::vector<Index>& fixed) {
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    if (std::find(fixed.begin(), fixed.end(), static_cast<Index>(i / 3)) == fixed.end()) free.push_back(i);
  }
  const auto n = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd af(n, n);
  Eigen::VectorXd bf(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    bf[r] = b[free[static_cast<std::size_t>(r)]];
    for (Eigen::Index c = 0; c < n; ++c) af(r, c) = a(free[static_cast<std::size_t>(r)], free[static_cast<std::size_t>(c)]);
  }
  const Eigen::VectorXd yf = af.fullPivLu().solve(bf);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(a.rows());
  for (Eigen::Index r = 0; r < n; ++r) y[free[static_cast<std::size_t>(r)]] = yf[r];
  return y;
}

ConjugateGradientSolver<double> precise_cg() {
  ConjugateGradientSolver<double>::Parameters p;
  p.iterations = 500;
  p.tolerance = 1e-14;
  p.threshold = 1e-40;
  return ConjugateGradientSolver<double>(p);
}

// ---------------------------------------------------------------------------------------------
// ImplicitEulerSolver

TEST(ImplicitEuler, SinglePointStepByHand) {
  // No elements: one point of mass 2, g = (0, -10, 0), v0 = (1, 0, 0), h = 0.1, rm = 0.5.
  //   b = h (m g - rm m v0) = 0.1 ((0, -20, 0) - (1, 0, 0)) = (-0.1, -2, 0)
  //   A = (1 + h rm) m = 1.05 · 2 = 2.1 ;  dv = b / 2.1 = (-1/21, -20/21, 0)
  //   v1 = v0 + dv = (20/21, -20/21, 0) ;  x1 = x0 + h v1 = (1, 2, 3) + (2/21, -2/21, 0)
  for (const bool direct : {true, false}) {
    MechanicalSystem<double> system;
    system.state.position = {Vec3<double>(1, 2, 3)};
    system.state.velocity = {Vec3<double>(1, 0, 0)};
    system.mass = Mass<double>::lumped({2.0});
    system.gravity = Vec3<double>(0, -10, 0);
    system.finalize();
    ImplicitEulerSolver<double>::Parameters p;
    p.rayleigh_mass = 0.5;
    ImplicitEulerSolver<double> euler(p);
    SparseDirectSolver<double> ldlt;
    auto cg = precise_cg();
    LinearSolver<double>& solver = direct ? static_cast<LinearSolver<double>&>(ldlt) : cg;
    const StepReport report = euler.step(system, solver, 0.1);
    EXPECT_EQ(report.linear_solves, 1);
    EXPECT_LT((system.state.velocity[0] - Vec3<double>(20.0 / 21, -20.0 / 21, 0)).norm(), 1e-14);
    EXPECT_LT((system.state.position[0] - Vec3<double>(1 + 2.0 / 21, 2 - 2.0 / 21, 3)).norm(), 1e-14);
  }
}

TEST(ImplicitEuler, FirstOrderSinglePointByHand) {
  // firstOrder (§1.5): b = f = m g = (0, -20, 0), A = m = 2 -> v1 = (0, -10, 0) whatever v0;
  // x1 = x0 + h v1 = (1, 2, 3) + (0, -1, 0).
  MechanicalSystem<double> system;
  system.state.position = {Vec3<double>(1, 2, 3)};
  system.state.velocity = {Vec3<double>(5, 5, 5)};
  system.mass = Mass<double>::lumped({2.0});
  system.gravity = Vec3<double>(0, -10, 0);
  system.finalize();
  ImplicitEulerSolver<double>::Parameters p;
  p.first_order = true;
  ImplicitEulerSolver<double> euler(p);
  SparseDirectSolver<double> ldlt;
  euler.step(system, ldlt, 0.1);
  EXPECT_LT((system.state.velocity[0] - Vec3<double>(0, -10, 0)).norm(), 1e-14);
  EXPECT_LT((system.state.position[0] - Vec3<double>(1, 1, 3)).norm(), 1e-14);
}

struct EulerCase {
  double rs = 0.1;        // solver rayleighStiffness
  double rm = 0.1;        // solver rayleighMass
  double field_rs = 0;    // the force field's own rayleighStiffness (§1.4)
  bool trapezoidal = false;
};

// One step of §1.2 (master form) with the per-component Rayleigh rule of §1.4:
//   b = P h (f + (h tr + rs) K v0 - rm M v0)
//   A = (1 + tr h rm) M - tr h (tr h + rs) K - tr h · field_rs · K
//   v1 = v0 + A^-1 b (free DOFs), x1 = x0 + h v1.
void expect_euler_step_matches_reference(const EulerCase& c, RotationMethod method) {
  const double h = 0.02;
  const double tr = c.trapezoidal ? 0.5 : 1.0;
  const std::vector<Index> fixed = {3};
  const Points x0 = [&] {
    std::mt19937 rng(11);
    return testing::perturbed(two_tets_rest(), 0.1, rng);
  }();
  const Points v0 = random_points(5, 12, 0.5);  // non-zero also at the fixed point 3
  const auto parameters = field_parameters(method, c.field_rs);
  const Dense d = dense_reference(parameters, x0, fixed);
  const Eigen::VectorXd v = flatten(v0);
  const Eigen::VectorXd b = d.p * (h * (d.f + (h * tr + c.rs) * d.k * v - c.rm * d.m * v));
  const Eigen::MatrixXd a =
      (1 + tr * h * c.rm) * d.m - tr * h * (tr * h + c.rs) * d.k - tr * h * c.field_rs * d.k;
  const Eigen::VectorXd v1 = v + free_solve(a, b, fixed);
  const Eigen::VectorXd x1 = flatten(x0) + h * v1;

  ImplicitEulerSolver<double>::Parameters p;
  p.rayleigh_stiffness = c.rs;
  p.rayleigh_mass = c.rm;
  p.trapezoidal = c.trapezoidal;
  {
    auto system = make_system(parameters, x0, v0, fixed);
    ImplicitEulerSolver<double> euler(p);
    SparseDirectSolver<double> ldlt;
    const StepReport report = euler.step(system, ldlt, h);
    EXPECT_EQ(report.linear_solves, 1);
    EXPECT_EQ(report.linear_iterations, 0);
    EXPECT_LT(relative_error(flatten(system.state.velocity), v1), 1e-12);
    EXPECT_LT(relative_error(flatten(system.state.position), x1), 1e-12);
    // The fixed point keeps its velocity and drifts by h v0 (docs/sofa-solvers.md §5.3).
    EXPECT_LT((system.state.velocity[3] - v0[3]).norm(), 1e-15);
    EXPECT_LT((system.state.position[3] - (x0[3] + h * v0[3])).norm(), 1e-15);
  }
  {
    auto system = make_system(parameters, x0, v0, fixed);
    ImplicitEulerSolver<double> euler(p);
    auto cg = precise_cg();
    const StepReport report = euler.step(system, cg, h);
    EXPECT_EQ(report.linear_solves, 1);
    EXPECT_GT(report.linear_iterations, 1);
    EXPECT_LT(relative_error(flatten(system.state.velocity), v1), 1e-9);
    EXPECT_LT(relative_error(flatten(system.state.position), x1), 1e-9);
  }
}

TEST(ImplicitEuler, OneStepMatchesTheDenseFormulaWithRayleighDamping) {
  expect_euler_step_matches_reference({}, RotationMethod::qr);
  expect_euler_step_matches_reference({}, RotationMethod::polar);
}

TEST(ImplicitEuler, NoDamping) { expect_euler_step_matches_reference({0.0, 0.0, 0.0, false}, RotationMethod::qr); }

TEST(ImplicitEuler, ComponentRayleighStiffnessEntersOnlyTheMatrix) {
  // §1.4: in master the force field's own rayleighStiffness reaches A (through bFactor = -h) but not b.
  expect_euler_step_matches_reference({0.1, 0.1, 0.3, false}, RotationMethod::qr);
}

TEST(ImplicitEuler, TrapezoidalMasterForm) {
  // §1.2 "Trapezoidal option": master uses (h tr + rs) in b and -tr h (tr h + rs) for K.
  expect_euler_step_matches_reference({0.1, 0.1, 0.2, true}, RotationMethod::qr);
}

TEST(ImplicitEuler, FirstOrderMatchesTheDenseFormula) {
  // §1.5: b = P f, A = M - h K (bFactor 0: the field's Rayleigh term does not enter), v1 = dv.
  const double h = 0.02;
  const std::vector<Index> fixed = {3};
  std::mt19937 rng(13);
  const Points x0 = testing::perturbed(two_tets_rest(), 0.1, rng);
  const Points v0 = random_points(5, 14, 0.5);
  const auto parameters = field_parameters(RotationMethod::qr, 0.3);
  const Dense d = dense_reference(parameters, x0, fixed);
  const Eigen::VectorXd v1 = free_solve(d.m - h * d.k, d.p * d.f, fixed);
  const Eigen::VectorXd x1 = flatten(x0) + h * v1;

  auto system = make_system(parameters, x0, v0, fixed);
  ImplicitEulerSolver<double>::Parameters p;
  p.first_order = true;
  p.rayleigh_stiffness = 0.1;  // unused by the first-order scheme
  p.rayleigh_mass = 0.1;
  ImplicitEulerSolver<double> euler(p);
  SparseDirectSolver<double> ldlt;
  euler.step(system, ldlt, h);
  EXPECT_LT(relative_error(flatten(system.state.velocity), v1), 1e-12);
  EXPECT_LT(relative_error(flatten(system.state.position), x1), 1e-12);
  // v1 replaces v0: the fixed point's velocity becomes 0 (b = 0 there).
  EXPECT_EQ(system.state.velocity[3], Vec3<double>::Zero());
}

TEST(ImplicitEuler, VelocityDampingScalesVelocityAfterThePositionUpdate) {
  // §1.2 step 7: v1 *= exp(-h vdamping) after x1 = x0 + h v1, so x1 is the undamped one.
  const double h = 0.05, vdamping = 3.0;
  std::mt19937 rng(15);
  const Points x0 = testing::perturbed(two_tets_rest(), 0.1, rng);
  const Points v0 = random_points(5, 16, 0.5);
  ImplicitEulerSolver<double>::Parameters p;
  p.rayleigh_stiffness = 0.1;
  auto plain = make_system(field_parameters(RotationMethod::qr), x0, v0, {3});
  auto damped = make_system(field_parameters(RotationMethod::qr), x0, v0, {3});
  SparseDirectSolver<double> ldlt;
  ImplicitEulerSolver<double>(p).step(plain, ldlt, h);
  p.velocity_damping = vdamping;
  ImplicitEulerSolver<double>(p).step(damped, ldlt, h);
  EXPECT_LT(relative_error(flatten(damped.state.position), flatten(plain.state.position)), 1e-14);
  EXPECT_LT(relative_error(flatten(damped.state.velocity), std::exp(-h * vdamping) * flatten(plain.state.velocity)),
            1e-14);
}

TEST(ImplicitEuler, RestStateWithoutLoadStaysPut) {
  // f = 0, v = 0 -> b = 0 -> nothing moves (CG returns 0 for a null rhs, §2.3).
  MechanicalSystem<double> system = make_system(field_parameters(RotationMethod::qr), two_tets_rest(),
                                                Points(5, Vec3<double>::Zero()), {});
  system.gravity.setZero();
  system.constant_forces.clear();
  ImplicitEulerSolver<double> euler(ImplicitEulerSolver<double>::Parameters{});
  ConjugateGradientSolver<double> cg;
  const StepReport report = euler.step(system, cg, 0.01);
  EXPECT_EQ(report.linear_iterations, 0);
  EXPECT_EQ(flatten(system.state.position), flatten(two_tets_rest()));
  EXPECT_EQ(flatten(system.state.velocity).cwiseAbs().maxCoeff(), 0.0);
}

TEST(ImplicitEuler, ConstructorRejectsNegativeOrNonFiniteCoefficients) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {-0.1, nan, inf}) {
    ImplicitEulerSolver<double>::Parameters p;
    p.rayleigh_stiffness = bad;
    EXPECT_THROW(ImplicitEulerSolver<double>{p}, Error) << bad;
    p = {};
    p.rayleigh_mass = bad;
    EXPECT_THROW(ImplicitEulerSolver<double>{p}, Error) << bad;
    p = {};
    p.velocity_damping = bad;
    EXPECT_THROW(ImplicitEulerSolver<double>{p}, Error) << bad;
  }
  EXPECT_NO_THROW(ImplicitEulerSolver<double>{ImplicitEulerSolver<double>::Parameters{}});
}

// ---------------------------------------------------------------------------------------------
// StaticSolver. A linear problem: method `none`, so f(x) = K (x - rest) + f_ext with a constant K,
// points 0, 1, 2 (the shared face) fixed, points 3 and 4 free and displaced from rest.

struct LinearProblem {
  MechanicalSystem<double> system;
  Eigen::VectorXd x0;
  Eigen::VectorXd exact;  // the static solution x*: P f(x*) = 0, fixed points at x0
  double r0 = 0;          // |P f(x0)|²
};

LinearProblem linear_problem() {
  const std::vector<Index> fixed = {0, 1, 2};
  Points x0 = two_tets_rest();
  x0[3] += Vec3<double>(0.05, -0.02, 0.1);
  x0[4] += Vec3<double>(-0.03, 0.04, 0.02);
  const Points v0 = random_points(5, 17, 1.0);
  LinearProblem lp{make_system(field_parameters(RotationMethod::none), x0, v0, fixed), flatten(x0), {}, 0};
  // K u = -f_ext on the free DOFs, u = x - rest (SPEC: `none` is linear elasticity, K = df/dx at rest).
  const Dense d = dense_reference(field_parameters(RotationMethod::none), two_tets_rest(), fixed);
  const Eigen::VectorXd f_ext = d.f;  // at rest the elastic force is 0: only weight and constant force
  lp.exact = flatten(two_tets_rest()) + free_solve(-d.k, d.p * f_ext, fixed);
  const Eigen::VectorXd r = d.p * (d.k * (lp.x0 - flatten(two_tets_rest())) + f_ext);
  lp.r0 = r.squaredNorm();
  return lp;
}

double projected_residual(MechanicalSystem<double>& system) {
  Points f(static_cast<std::size_t>(system.size()));
  system.compute_force(system.state.position, f);
  system.project(f);
  return flatten(f).squaredNorm();
}

TEST(StaticSolver, DefaultsAreSofas) {
  // docs/sofa-solvers.md §3.1 and §3.2 tables.
  const StaticSolver<double>::NewtonParameters n;
  EXPECT_EQ(n.max_iterations, 1);
  EXPECT_EQ(n.max_line_search_iterations, 5);
  EXPECT_EQ(n.line_search_coefficient, 0.5);
  EXPECT_EQ(n.relative_successive_threshold, 1e-5);
  EXPECT_EQ(n.relative_initial_threshold, 1e-5);
  EXPECT_EQ(n.absolute_residual_threshold, 1e-5);
  EXPECT_EQ(n.relative_estimate_difference_threshold, 0.0);
  EXPECT_EQ(n.absolute_estimate_difference_threshold, 0.0);
  const StaticSolver<double>::LegacyParameters l;
  EXPECT_EQ(l.newton_iterations, 1);
  EXPECT_EQ(l.absolute_correction_threshold, 1e-5);
  EXPECT_EQ(l.relative_correction_threshold, 1e-5);
  EXPECT_EQ(l.absolute_residual_threshold, 1e-5);
  EXPECT_EQ(l.relative_residual_threshold, 1e-5);
}

TEST(StaticSolver, OneNewtonStepSolvesALinearProblemExactly) {
  for (const bool direct : {true, false}) {
    auto lp = linear_problem();
    ASSERT_GT(lp.r0, 1.0);  // far from converged: the thresholds (1e-5)² do not fire at x0
    const Points v_before = lp.system.state.velocity;
    StaticSolver<double> solver(StaticSolver<double>::NewtonParameters{});
    SparseDirectSolver<double> ldlt;
    auto cg = precise_cg();
    LinearSolver<double>& linear = direct ? static_cast<LinearSolver<double>&>(ldlt) : cg;
    const StepReport report = solver.step(lp.system, linear, 123.0);  // dt is unused
    EXPECT_EQ(report.linear_solves, 1);
    EXPECT_TRUE(solver.converged());
    EXPECT_LT(relative_error(flatten(lp.system.state.position), lp.exact), direct ? 1e-12 : 1e-9);
    EXPECT_EQ(flatten(lp.system.state.velocity), flatten(v_before));  // velocities untouched
    EXPECT_LT(projected_residual(lp.system), 1e-16 * lp.r0);
  }
}

TEST(StaticSolver, InitiallyConvergedDoesNotSolve) {
  // |P f(x0)|² <= absoluteResidualStoppingThreshold²: no iteration, x unchanged (§3.1).
  auto lp = linear_problem();
  StaticSolver<double>::NewtonParameters p;
  p.absolute_residual_threshold = std::sqrt(lp.r0) * 1.0001;
  StaticSolver<double> solver(p);
  SparseDirectSolver<double> ldlt;
  const StepReport report = solver.step(lp.system, ldlt, 0.01);
  EXPECT_EQ(report.linear_solves, 0);
  EXPECT_TRUE(solver.converged());
  EXPECT_EQ(flatten(lp.system.state.position), lp.x0);
}

// A test double: the exact direct solution scaled by c. On the linear problem the Newton direction
// is then c·(x* - x), and the residual after x += α c (x* - x) is (1 - α c) times the previous one,
// so every line-search decision can be worked out by hand.
class ScaledSolver final : public LinearSolver<double> {
 public:
  explicit ScaledSolver(double c) : c_(c) {}
  LinearSolveReport solve(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                          std::span<const Vec3<double>> rhs, std::span<Vec3<double>> x) override {
    const LinearSolveReport report = direct_.solve(system, factors, rhs, x);
    for (auto& xi : x) xi *= c_;
    return report;
  }

 private:
  double c_;
  SparseDirectSolver<double> direct_;
};

// x after one Newton step whose accepted step is `fraction` of the way to x*.
Eigen::VectorXd along(const LinearProblem& lp, double fraction) { return lp.x0 + fraction * (lp.exact - lp.x0); }

TEST(StaticSolver, LineSearchHalvesUntilTheResidualDecreases) {
  struct Case {
    double c;            // the linear solver's over-scaling
    double coefficient;  // lineSearchCoefficient
    int line_searches;   // maxNbIterationsLineSearch
    double fraction;     // expected α c, worked out below
    double residual;     // expected |r|² / |r0|² = (1 - α c)²
  };
  const std::vector<Case> cases = {
      // c = 3: α = 1 gives 1 - 3 = -2 (R = 4 R0, rejected); α = 1/2 gives -1/2 (R0/4, accepted).
      {3.0, 0.5, 5, 1.5, 0.25},
      // c = 5: α = 1: -4; 1/2: -1.5 (2.25 R0); 1/4: -0.25 (R0/16, accepted).
      {5.0, 0.5, 5, 1.25, 0.0625},
      // c = 3, coefficient 1/4: α = 1 rejected; α = 1/4 gives 1 - 3/4 = 1/4 (R0/16, accepted).
      {3.0, 0.25, 5, 0.75, 0.0625},
      // c = 100: α = 1, 1/2, 1/4, 1/8, 1/16 give -99, -49, -24, -11.5, -5.25: all rejected, so the
      // full step is taken again (R = 99² R0).
      {100.0, 0.5, 5, 100.0, 99.0 * 99.0},
      // One line-search iteration: the full step, no retry.
      {3.0, 0.5, 1, 3.0, 4.0},
      // maxNbIterationsLineSearch 0 is used as max(0, 1) = 1 (§3.1 table).
      {3.0, 0.5, 0, 3.0, 4.0},
      // c = 1/2 (an under-relaxed solve): α = 1 gives 1/2 (R0/4), accepted at once.
      {0.5, 0.5, 5, 0.5, 0.25},
  };
  for (const Case& c : cases) {
    auto lp = linear_problem();
    StaticSolver<double>::NewtonParameters p;
    p.line_search_coefficient = c.coefficient;
    p.max_line_search_iterations = c.line_searches;
    StaticSolver<double> solver(p);
    ScaledSolver scaled(c.c);
    const StepReport report = solver.step(lp.system, scaled, 0.01);
    EXPECT_EQ(report.linear_solves, 1);
    EXPECT_LT(relative_error(flatten(lp.system.state.position), along(lp, c.fraction)), 1e-10)
        << "c = " << c.c << ", coefficient " << c.coefficient << ", searches " << c.line_searches;
    EXPECT_NEAR(projected_residual(lp.system) / lp.r0, c.residual, 1e-8 * c.residual) << "c = " << c.c;
    EXPECT_FALSE(solver.converged());  // none of these reaches (1e-5)² R
  }
}

TEST(StaticSolver, ConvergenceTests) {
  // With c = 3 every Newton iteration accepts α = 1/2: the residual is multiplied by -1/2
  // (R by 1/4) and x - x* by -1/2. After k iterations x = x0 + (1 - (-1/2)^k)(x* - x0).
  using P = StaticSolver<double>::NewtonParameters;
  struct Case {
    const char* name;
    P parameters;
    int solves;
    bool converged;
    double fraction;
  };
  const auto lp0 = linear_problem();
  const double dx_norm = 3 * (lp0.exact - lp0.x0).norm();  // |dx| of the first solve, before α
  const double x0_norm = lp0.x0.norm();
  const auto make = [](int iterations, double successive, double initial, double absolute, double relative_dx,
                       double absolute_dx) {
    P p;
    p.max_iterations = iterations;
    p.relative_successive_threshold = successive;
    p.relative_initial_threshold = initial;
    p.absolute_residual_threshold = absolute;
    p.relative_estimate_difference_threshold = relative_dx;
    p.absolute_estimate_difference_threshold = absolute_dx;
    return p;
  };
  const std::vector<Case> cases = {
      // Default thresholds never pass: 3 iterations, not converged, x = x0 + (1 + 1/8)(x* - x0).
      {"max iterations", make(3, 1e-5, 1e-5, 1e-5, 0, 0), 3, false, 1.125},
      // relativeInitial 0.3: R < 0.09 R0 first holds at k = 2 (R0/16): x = x0 + 3/4 (x* - x0).
      {"relative initial", make(10, 0, 0.3, 0, 0, 0), 2, true, 0.75},
      // relativeSuccessive 0.6: R_k = R_{k-1}/4 < 0.36 R_{k-1} at k = 1.
      {"relative successive", make(10, 0.6, 0, 0, 0, 0), 1, true, 1.5},
      // absoluteResidual: R < thr² with thr² = 0.1 R0 holds at k = 2 (R0/16), not at k = 1 (R0/4).
      {"absolute residual", make(10, 0, 0, std::sqrt(0.1 * lp0.r0), 0, 0), 2, true, 0.75},
      // absoluteEstimateDifference compares |dx|, the solution before α scaling (3|x* - x0|):
      // just above it converges at k = 1; just below it does not (|dx| halves each iteration).
      {"absolute dx above", make(1, 0, 0, 0, 0, 1.01 * dx_norm), 1, true, 1.5},
      {"absolute dx below", make(1, 0, 0, 0, 0, 0.99 * dx_norm), 1, false, 1.5},
      // relativeEstimateDifference: |dx|² < thr² · |x_before|².
      {"relative dx above", make(1, 0, 0, 0, 1.01 * dx_norm / x0_norm, 0), 1, true, 1.5},
      {"relative dx below", make(1, 0, 0, 0, 0.99 * dx_norm / x0_norm, 0), 1, false, 1.5},
  };
  for (const Case& c : cases) {
    auto lp = linear_problem();
    StaticSolver<double> solver(c.parameters);
    ScaledSolver scaled(3.0);
    const StepReport report = solver.step(lp.system, scaled, 0.01);
    EXPECT_EQ(report.linear_solves, c.solves) << c.name;
    EXPECT_EQ(solver.converged(), c.converged) << c.name;
    EXPECT_LT(relative_error(flatten(lp.system.state.position), along(lp, c.fraction)), 1e-10) << c.name;
  }
}

TEST(StaticSolver, LegacyTakesTheFullStepWithoutLineSearch) {
  // §3.2: x += dx, and with newton_iterations = 1 no residual re-evaluation (no convergence flag).
  auto lp = linear_problem();
  StaticSolver<double> solver(StaticSolver<double>::LegacyParameters{});
  ScaledSolver scaled(100.0);
  const StepReport report = solver.step(lp.system, scaled, 0.01);
  EXPECT_EQ(report.linear_solves, 1);
  EXPECT_FALSE(solver.converged());
  EXPECT_LT(relative_error(flatten(lp.system.state.position), along(lp, 100.0)), 1e-10);
}

TEST(StaticSolver, LegacyExactSolveOfALinearProblem) {
  auto lp = linear_problem();
  StaticSolver<double> solver(StaticSolver<double>::LegacyParameters{});
  SparseDirectSolver<double> ldlt;
  solver.step(lp.system, ldlt, 0.01);
  EXPECT_LT(relative_error(flatten(lp.system.state.position), lp.exact), 1e-12);
  // newton_iterations = 1: SOFA stops right after the update, no residual is evaluated and no
  // convergence test runs (§3.2), although the residual is now ~0.
  EXPECT_FALSE(solver.converged());
}

TEST(StaticSolver, LegacyRelativeResidualIsMeasuredAgainstTheFirstIteration) {
  // c = 1/2: each iteration halves the residual (R × 1/4). R0' := R after iteration 1 = R0/4.
  // relative_residual 0.3 needs R < 0.09 R0': R2 = R0'/4 no, R3 = R0'/16 yes -> 3 solves,
  // x = x0 + (1 - 1/8)(x* - x0). (Measured against R0 it would stop after 2.)
  auto lp = linear_problem();
  StaticSolver<double>::LegacyParameters p;
  p.newton_iterations = 10;
  p.absolute_correction_threshold = 0;
  p.relative_correction_threshold = 0;
  p.absolute_residual_threshold = 0;
  p.relative_residual_threshold = 0.3;
  StaticSolver<double> solver(p);
  ScaledSolver scaled(0.5);
  const StepReport report = solver.step(lp.system, scaled, 0.01);
  EXPECT_EQ(report.linear_solves, 3);
  EXPECT_TRUE(solver.converged());
  EXPECT_LT(relative_error(flatten(lp.system.state.position), along(lp, 0.875)), 1e-10);
}

TEST(StaticSolver, LegacyDoesNotStopWhenTheResidualGrows) {
  // c = 3 with no line search: x1 - x* = -2 (x0 - x*), x2 - x* = 4 (x0 - x*): x2 = x0 - 3 (x* - x0).
  auto lp = linear_problem();
  StaticSolver<double>::LegacyParameters p;
  p.newton_iterations = 2;
  p.diverge_when_residual_grows = true;  // a status flag only in SOFA
  StaticSolver<double> solver(p);
  ScaledSolver scaled(3.0);
  const StepReport report = solver.step(lp.system, scaled, 0.01);
  EXPECT_EQ(report.linear_solves, 2);
  EXPECT_FALSE(solver.converged());
  EXPECT_LT(relative_error(flatten(lp.system.state.position), along(lp, -3.0)), 1e-10);
}

TEST(StaticSolver, LegacyInitiallyConverged) {
  auto lp = linear_problem();
  StaticSolver<double>::LegacyParameters p;
  p.absolute_residual_threshold = std::sqrt(lp.r0) * 1.0001;
  StaticSolver<double> solver(p);
  SparseDirectSolver<double> ldlt;
  EXPECT_EQ(solver.step(lp.system, ldlt, 0.01).linear_solves, 0);
  EXPECT_TRUE(solver.converged());
  EXPECT_EQ(flatten(lp.system.state.position), lp.x0);
}

TEST(StaticSolver, NonlinearProblemResidualDecreasesUntilConverged) {
  // Corotational (polar) under load, one Newton iteration per step: each step lowers |P f|²
  // (the line search accepts only a decrease) until the convergence tests pass. (Not qr: its frame
  // comes from vertices 0, 1, 2 of each tetrahedron, all fixed here, which makes the problem linear.)
  const std::vector<Index> fixed = {0, 1, 2};
  auto system = make_system(field_parameters(RotationMethod::polar), two_tets_rest(), Points(5, Vec3<double>::Zero()),
                            fixed);
  system.constant_forces[0].forces[0] = Vec3<double>(20, -10, 5);
  StaticSolver<double> solver(StaticSolver<double>::NewtonParameters{});
  SparseDirectSolver<double> ldlt;
  double previous = projected_residual(system);
  int steps = 0;
  while (!solver.converged() && steps < 20) {
    solver.step(system, ldlt, 0.01);
    const double residual = projected_residual(system);
    EXPECT_LT(residual, previous) << "step " << steps;
    previous = residual;
    ++steps;
  }
  EXPECT_TRUE(solver.converged());
  EXPECT_GT(steps, 1);  // nonlinear: one linear step is not enough
  EXPECT_LT(previous, 1e-10);
}

TEST(StaticSolver, ConstructorErrors) {
  StaticSolver<double>::NewtonParameters n;
  n.max_iterations = 0;
  EXPECT_THROW(StaticSolver<double>{n}, Error);
  for (double bad : {0.0, 1.0, 1.5, -0.5, std::numeric_limits<double>::quiet_NaN()}) {
    n = {};
    n.line_search_coefficient = bad;
    EXPECT_THROW(StaticSolver<double>{n}, Error) << bad;
  }
  StaticSolver<double>::LegacyParameters l;
  l.newton_iterations = 0;
  EXPECT_THROW(StaticSolver<double>{l}, Error);
}

}  // namespace
}  // namespace fastcorot
