#include "fastcorot/sim/conjugate_gradient.h"

#include "fastcorot/core/error.h"

#include <cmath>

namespace fastcorot {

template <class Real>
ConjugateGradientSolver<Real>::ConjugateGradientSolver(Parameters parameters) : parameters_(parameters) {
  if (parameters_.iterations < 1) {
    throw make_error("CGLinearSolver: iterations = ", parameters_.iterations, ": must be at least 1");
  }
  if (!(parameters_.tolerance >= 0) || !std::isfinite(parameters_.tolerance)) {
    throw make_error("CGLinearSolver: tolerance = ", parameters_.tolerance, ": must be finite and >= 0");
  }
  if (!(parameters_.threshold >= 0) || !std::isfinite(parameters_.threshold)) {
    throw make_error("CGLinearSolver: threshold = ", parameters_.threshold, ": must be finite and >= 0");
  }
}

template <class Real>
void ConjugateGradientSolver<Real>::restore_carried_state(const std::vector<std::int64_t>& state) {
  if (state.size() != 1 || state[0] < 0) {
    throw make_error("CGLinearSolver: expected one solve count >= 0 to restore, got ", state.size(),
                     " values");
  }
  solves_ = state[0];
}

template <class Real>
LinearSolveReport ConjugateGradientSolver<Real>::solve(const MechanicalSystem<Real>& system,
                                                       const MatrixFactors<Real>& factors,
                                                       std::span<const Vec3<Real>> rhs,
                                                       std::span<Vec3<Real>> x) {
  const std::size_t n = rhs.size();
  r_.assign(rhs.begin(), rhs.end());
  p_.resize(n);
  q_.resize(n);
  set_zero(x);
  const bool first_solve = solves_++ == 0;
  const Real norm_b = std::sqrt(dot<Real>(rhs, rhs));
  LinearSolveReport report;
  if (norm_b == 0) return report;
  Real rho_previous = 0;
  for (int iteration = 1; iteration <= parameters_.iterations; ++iteration) {
    const bool may_stop = !(iteration == 1 && first_solve);
    const Real rho = dot<Real>(r_, r_);
    report.relative_residual = std::sqrt(rho) / norm_b;
    if (report.relative_residual <= parameters_.tolerance && may_stop) break;
    if (iteration == 1) {
      p_ = r_;
    } else {
      const Real beta = rho / rho_previous;
      for (std::size_t i = 0; i < n; ++i) p_[i] = r_[i] + beta * p_[i];
    }
    system.multiply(factors, p_, q_);
    const Real den = dot<Real>(p_, q_);
    if (den == 0) break;
    if (std::abs(den) <= parameters_.threshold && may_stop) break;
    const Real alpha = rho / den;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * p_[i];
      r_[i] -= alpha * q_[i];
    }
    rho_previous = rho;
    report.iterations = iteration;
  }
  report.relative_residual = std::sqrt(dot<Real>(r_, r_)) / norm_b;
  return report;
}

template class ConjugateGradientSolver<float>;
template class ConjugateGradientSolver<double>;

}  // namespace fastcorot
