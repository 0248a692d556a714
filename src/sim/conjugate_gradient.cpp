#include "fastcorot/sim/conjugate_gradient.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/packed.h"
#include "fastcorot/core/parallel.h"

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

namespace {

// Every sum here keeps four interleaved partial sums in one SIMD register (lane k sums the terms
// i = begin + k mod 4, those past the last whole four in lane 0: a fixed order), then adds the
// lanes pairwise.
template <class Real>
Real sum_lanes(const Packed<Real>& partial) {
  return (partial[0] + partial[1]) + (partial[2] + partial[3]);
}

// sum_i a[i] b[i] over [begin, end).
template <class Real>
Real dot_range(const Real* a, const Real* b, std::size_t begin, std::size_t end) {
  Packed<Real> partial{};
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) partial += load_packed(a + i) * load_packed(b + i);
  for (; i < end; ++i) partial[0] += a[i] * b[i];
  return sum_lanes<Real>(partial);
}

// x += alpha p and r -= alpha q over [begin, end), returning the new r^T r summed exactly as
// dot_range(r, r, begin, end) would sum it (the same lanes, in the same order), in the same loop:
// the sum's chain of additions then overlaps the updates instead of running after them.
template <class Real>
Real update_range(Real* x, Real* r, const Real* p, const Real* q, Real alpha, std::size_t begin, std::size_t end) {
  const Packed<Real> a = broadcast(alpha);
  Packed<Real> partial{};
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) {
    store_packed(x + i, load_packed(x + i) + a * load_packed(p + i));
    const Packed<Real> ri = load_packed(r + i) - a * load_packed(q + i);
    store_packed(r + i, ri);
    partial += ri * ri;
  }
  for (; i < end; ++i) {
    x[i] += alpha * p[i];
    r[i] -= alpha * q[i];
    partial[0] += r[i] * r[i];
  }
  return sum_lanes<Real>(partial);
}

template <class Real>
Real* flat(std::span<Vec3<Real>> v) {
  return v.data()->data();
}
template <class Real>
const Real* flat(std::span<const Vec3<Real>> v) {
  return v.data()->data();
}

}  // namespace

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
