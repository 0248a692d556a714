#include "fastcorot/sim/conjugate_gradient.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/parallel.h"
#include "solver_vectors.h"

#include <cmath>

namespace fastcorot {

using solver_vectors::dot_range;
using solver_vectors::flat;
using solver_vectors::update_range;

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
  // SOFA's iteration with its vector work fused into three passes per iteration (direction,
  // curvature, update with the new residual norm) over the coordinates as one flat array; every sum
  // is a parallel_sum of dot_range, so any thread count gives the same bits.
  const std::size_t n = rhs.size();
  const std::size_t m = 3 * n;
  const int threads = system.threads();
  double* vector_time = system.timer_slot(&PhaseTimes::solver_vectors);
  r_.resize(n);
  p_.resize(n);
  q_.resize(n);
  Real* r = flat<Real>(std::span<Vec3<Real>>(r_));
  Real* p = flat<Real>(std::span<Vec3<Real>>(p_));
  const Real* q = flat<Real>(std::span<const Vec3<Real>>(q_));
  const Real* b = flat<Real>(rhs);
  Real* xs = flat<Real>(x);
  const bool first_solve = solves_++ == 0;
  Real rho = 0;  // r^T r of the current residual
  {
    const PhaseTimer timer(vector_time);
    rho = parallel_sum<Real>(threads, m, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        r[i] = b[i];
        xs[i] = 0;
      }
      return dot_range(b, b, begin, end);
    });
  }
  const Real norm_b = std::sqrt(rho);
  LinearSolveReport report;
  if (norm_b == 0) return report;
  Real rho_previous = 0;
  for (int iteration = 1; iteration <= parameters_.iterations; ++iteration) {
    const bool may_stop = !(iteration == 1 && first_solve);
    report.relative_residual = std::sqrt(rho) / norm_b;
    if (report.relative_residual <= parameters_.tolerance && may_stop) break;
    {
      const PhaseTimer timer(vector_time);
      const Real beta = iteration == 1 ? Real(0) : rho / rho_previous;
      parallel_ranges(threads, m, [&](std::size_t begin, std::size_t end) {
        if (iteration == 1) {
          for (std::size_t i = begin; i < end; ++i) p[i] = r[i];
        } else {
          for (std::size_t i = begin; i < end; ++i) p[i] = r[i] + beta * p[i];
        }
      });
    }
    system.multiply(factors, p_, q_);
    Real den = 0;
    {
      const PhaseTimer timer(vector_time);
      den = parallel_sum<Real>(threads, m, [&](std::size_t begin, std::size_t end) { return dot_range(p, q, begin, end); });
    }
    if (den == 0) break;
    if (std::abs(den) <= parameters_.threshold && may_stop) break;
    const Real alpha = rho / den;
    rho_previous = rho;
    {
      const PhaseTimer timer(vector_time);
      rho = parallel_sum<Real>(threads, m, [&](std::size_t begin, std::size_t end) {
        return update_range(xs, r, p, q, alpha, begin, end);
      });
    }
    report.iterations = iteration;
  }
  report.relative_residual = std::sqrt(rho) / norm_b;
  return report;
}

template class ConjugateGradientSolver<float>;
template class ConjugateGradientSolver<double>;

}  // namespace fastcorot
