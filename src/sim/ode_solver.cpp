#include "fastcorot/sim/ode_solver.h"

#include "coefficient_checks.h"
#include "fastcorot/core/error.h"

#include <cmath>
#include <limits>

namespace fastcorot {

using detail::check_coefficient;

template <class Real>
ImplicitEulerSolver<Real>::ImplicitEulerSolver(Parameters parameters) : parameters_(parameters) {
  check_coefficient(parameters_.rayleigh_stiffness, "EulerImplicitSolver: rayleighStiffness");
  check_coefficient(parameters_.rayleigh_mass, "EulerImplicitSolver: rayleighMass");
  check_coefficient(parameters_.velocity_damping, "EulerImplicitSolver: vdamping");
}

template <class Real>
StepReport ImplicitEulerSolver<Real>::step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver,
                                           Real dt) {
  const std::size_t n = static_cast<std::size_t>(system.size());
  auto& x = system.state.position;
  auto& v = system.state.velocity;
  force_.resize(n);
  rhs_.resize(n);
  dv_.resize(n);
  const Real h = dt;
  const Real tr = parameters_.trapezoidal ? Real(0.5) : Real(1);
  const Real rs = parameters_.rayleigh_stiffness;
  const Real rm = parameters_.rayleigh_mass;

  system.compute_force(x, force_);  // records the force fields' linearisation at x_n
  rhs_ = force_;
  MatrixFactors<Real> factors;
  if (parameters_.first_order) {
    factors = {Real(1), Real(0), -h * tr};
  } else {
    // b += (h tr + rs) K v - rm M v through the matrix-free products (component Rayleigh
    // coefficients do not enter the right-hand side, as in SOFA).
    const PhaseTimer timer(system.timer_slot(&PhaseTimes::matrix_vector));
    // In a distributed run the products are partial at shared points: they are completed apart
    // from the force, which is already complete (dv_ serves as the work vector).
    std::vector<Vec3<Real>>& terms = system.exchange ? dv_ : rhs_;
    if (system.exchange) std::fill(dv_.begin(), dv_.end(), Vec3<Real>::Zero());
    for (const auto& field : system.force_fields) field->add_dforce(v, terms, h * tr + rs, Real(0));
    if (rm != 0 && system.mass.size() != 0) system.mass.add_mdx(v, terms, -rm);
    if (system.exchange) {
      system.exchange->sum_shared(dv_);
      for (std::size_t i = 0; i < n; ++i) rhs_[i] += dv_[i];
    }
    for (auto& b : rhs_) b *= h;
    factors = {1 + tr * h * rm, -tr * h, -tr * h * (tr * h + rs)};
  }
  system.project(rhs_);
  const LinearSolveReport solved = solver.solve(system, factors, rhs_, dv_);
  const PhaseTimer timer(system.timer_slot(&PhaseTimes::mass_constraints));
  if (parameters_.first_order) {
    v = dv_;
  } else {
    for (std::size_t i = 0; i < n; ++i) v[i] += dv_[i];
  }
  for (std::size_t i = 0; i < n; ++i) x[i] += h * v[i];
  if (parameters_.velocity_damping != 0) {
    const Real decay = std::exp(-h * parameters_.velocity_damping);
    for (auto& vi : v) vi *= decay;
  }
  return {1, solved.iterations};
}

template <class Real>
std::optional<IntegrationFactors<Real>> ImplicitEulerSolver<Real>::integration_factors(Real dt) const {
  const Real h = dt;
  const Real tr = parameters_.trapezoidal ? Real(0.5) : Real(1);
  const Real rs = parameters_.rayleigh_stiffness;
  const Real rm = parameters_.rayleigh_mass;
  IntegrationFactors<Real> factors;
  factors.position = h;
  factors.velocity = 1;
  factors.matrix = parameters_.first_order ? MatrixFactors<Real>{Real(1), Real(0), -h * tr}
                                           : MatrixFactors<Real>{1 + tr * h * rm, -tr * h, -tr * h * (tr * h + rs)};
  return factors;
}

template <class Real>
StaticSolver<Real>::StaticSolver(NewtonParameters parameters) : newton_(parameters) {
  if (newton_.max_iterations < 1) {
    throw make_error("NewtonRaphsonSolver: maxNbIterationsNewton = ", newton_.max_iterations, ": must be at least 1");
  }
  if (!(newton_.line_search_coefficient > 0 && newton_.line_search_coefficient < 1)) {
    throw make_error("NewtonRaphsonSolver: lineSearchCoefficient = ", newton_.line_search_coefficient,
                     ": must be in (0, 1)");
  }
}

template <class Real>
StaticSolver<Real>::StaticSolver(LegacyParameters parameters) : legacy_(true), legacy_parameters_(parameters) {
  if (legacy_parameters_.newton_iterations < 1) {
    throw make_error("StaticSolver: newton_iterations = ", legacy_parameters_.newton_iterations,
                     ": must be at least 1");
  }
}

template <class Real>
Real StaticSolver<Real>::projected_residual(MechanicalSystem<Real>& system) {
  force_.resize(static_cast<std::size_t>(system.size()));
  system.compute_force(system.state.position, force_);
  system.project(force_);
  return dot<Real>(force_, force_);
}

template <class Real>
StepReport StaticSolver<Real>::step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real) {
  dx_.resize(static_cast<std::size_t>(system.size()));
  return legacy_ ? legacy_step(system, solver) : newton_step(system, solver);
}

template <class Real>
StepReport StaticSolver<Real>::newton_step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver) {
  const NewtonParameters& p = newton_;
  auto& x = system.state.position;
  const auto squared = [](Real t) { return t * t; };
  StepReport report;
  converged_ = false;
  const Real r0 = projected_residual(system);
  if (p.absolute_residual_threshold > 0 && r0 <= squared(p.absolute_residual_threshold)) {
    converged_ = true;
    return report;
  }
  const MatrixFactors<Real> factors{Real(0), Real(0), Real(-1)};
  const int line_searches = std::max(p.max_line_search_iterations, 1);
  Real residual = r0;
  for (int iteration = 0; iteration < p.max_iterations && !converged_; ++iteration) {
    const Real previous = residual;
    const Real previous_position = dot<Real>(x, x);
    // force_ holds P f(x) at the current x, and the force fields are linearised there.
    const LinearSolveReport solved = solver.solve(system, factors, force_, dx_);
    ++report.linear_solves;
    report.linear_iterations += solved.iterations;
    Real alpha = 1, applied = 0;
    bool decreased = false;
    for (int search = 0; search < line_searches; ++search) {
      for (std::size_t i = 0; i < x.size(); ++i) x[i] += (alpha - applied) * dx_[i];
      applied = alpha;
      residual = projected_residual(system);
      if (residual < previous) {
        decreased = true;
        break;
      }
      alpha *= p.line_search_coefficient;
    }
    if (!decreased && line_searches > 1) {
      for (std::size_t i = 0; i < x.size(); ++i) x[i] += (1 - applied) * dx_[i];
      residual = projected_residual(system);
    }
    const Real dx_squared = dot<Real>(dx_, dx_);
    converged_ =
        (p.relative_successive_threshold > 0 && residual < squared(p.relative_successive_threshold) * previous) ||
        (p.relative_initial_threshold > 0 && residual < squared(p.relative_initial_threshold) * r0) ||
        (p.absolute_residual_threshold > 0 && residual < squared(p.absolute_residual_threshold)) ||
        (p.relative_estimate_difference_threshold > 0 && previous_position > 0 &&
         dx_squared < squared(p.relative_estimate_difference_threshold) * previous_position) ||
        (p.absolute_estimate_difference_threshold > 0 &&
         dx_squared < squared(p.absolute_estimate_difference_threshold));
  }
  return report;
}

template <class Real>
StepReport StaticSolver<Real>::legacy_step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver) {
  const LegacyParameters& p = legacy_parameters_;
  auto& x = system.state.position;
  const auto squared = [](Real t) { return t * t; };
  StepReport report;
  std::vector<Vec3<Real>> total(x.size(), Vec3<Real>::Zero());
  Real residual = projected_residual(system);
  converged_ = p.absolute_residual_threshold > 0 && residual <= squared(p.absolute_residual_threshold);
  Real first = 0;
  const MatrixFactors<Real> factors{Real(0), Real(0), Real(-1)};
  for (int iteration = 1; !converged_ && iteration <= p.newton_iterations; ++iteration) {
    const LinearSolveReport solved = solver.solve(system, factors, force_, dx_);
    ++report.linear_solves;
    report.linear_iterations += solved.iterations;
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += dx_[i];
    if (p.newton_iterations == 1) break;  // SOFA does not re-evaluate the residual then
    residual = projected_residual(system);
    if (iteration == 1) first = residual;
    for (std::size_t i = 0; i < x.size(); ++i) total[i] += dx_[i];
    const Real dx_squared = dot<Real>(dx_, dx_);
    const Real total_squared = dot<Real>(total, total);
    const Real eps = std::numeric_limits<Real>::epsilon();
    if (std::isnan(residual) || std::isnan(dx_squared) || total_squared < eps * eps) break;
    if ((p.absolute_correction_threshold > 0 && dx_squared < squared(p.absolute_correction_threshold)) ||
        (p.relative_correction_threshold > 0 && dx_squared < squared(p.relative_correction_threshold) * total_squared) ||
        (p.absolute_residual_threshold > 0 && residual < squared(p.absolute_residual_threshold)) ||
        (p.relative_residual_threshold > 0 && residual < squared(p.relative_residual_threshold) * first)) {
      converged_ = true;
    }
  }
  return report;
}

template class ImplicitEulerSolver<float>;
template class ImplicitEulerSolver<double>;
template class StaticSolver<float>;
template class StaticSolver<double>;

}  // namespace fastcorot
