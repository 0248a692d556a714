#include "fastcorot/sim/minres_solver.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/parallel.h"
#include "carried_bits.h"
#include "solver_vectors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace fastcorot {

using solver_vectors::dot_range;
using solver_vectors::flat;

template <class Real>
MinResSolver<Real>::MinResSolver(Parameters parameters, Index points) : parameters_(parameters) {
  if (parameters_.iterations < 1) {
    throw make_error("MinResLinearSolver: iterations = ", parameters_.iterations, ": must be at least 1");
  }
  if (!(parameters_.tolerance >= 0) || !std::isfinite(parameters_.tolerance)) {
    throw make_error("MinResLinearSolver: tolerance = ", parameters_.tolerance, ": must be finite and >= 0");
  }
  if (points < 0) throw make_error("MinResLinearSolver: ", points, " points");
  previous_.assign(static_cast<std::size_t>(points), Vec3<Real>::Zero());
}

template <class Real>
LinearSolveReport MinResSolver<Real>::solve(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                                            std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) {
  const std::size_t n = previous_.size();
  if (rhs.size() != n || x.size() != n || static_cast<std::size_t>(system.size()) != n) {
    throw make_error("MinResLinearSolver: a system of ", system.size(), " points; this solver was made for ", n);
  }
  const std::size_t m = 3 * n;
  const int threads = system.threads();
  double* vector_time = system.timer_slot(&PhaseTimes::solver_vectors);
  for (auto* v : {&r1_, &r2_, &y_, &w_, &w2_, &v_}) v->assign(n, Vec3<Real>::Zero());
  std::copy(previous_.begin(), previous_.end(), x.begin());
  // r1, r2, w and w2 trade places (SOFA swaps its pointers); v and y keep theirs.
  Real* r1 = flat<Real>(std::span<Vec3<Real>>(r1_));
  Real* r2 = flat<Real>(std::span<Vec3<Real>>(r2_));
  Real* w = flat<Real>(std::span<Vec3<Real>>(w_));
  Real* w2 = flat<Real>(std::span<Vec3<Real>>(w2_));
  Real* y = flat<Real>(std::span<Vec3<Real>>(y_));
  Real* v = flat<Real>(std::span<Vec3<Real>>(v_));
  Real* xs = flat<Real>(x);
  const Real* b = flat<Real>(rhs);
  const auto sum = [&](const auto& body) { return parallel_sum<Real>(threads, m, body); };
  const auto each = [&](const auto& body) { parallel_ranges(threads, m, body); };
  const auto dot = [&](const Real* a, const Real* c) {
    return sum([&](std::size_t begin, std::size_t end) { return dot_range(a, c, begin, end); });
  };

  system.multiply(factors, x, r1_);  // A x0, even for x0 = 0, as SOFA does
  Real beta1 = 0, b_norm = 0;
  {
    const PhaseTimer timer(vector_time);
    each([&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) r1[i] = b[i] - r1[i];
    });
    beta1 = dot(r1, r1);
    b_norm = std::sqrt(dot(b, b));
  }
  LinearSolveReport report;
  if (!(beta1 > 0)) return report;  // b = A x0 exactly: x stays x0
  beta1 = std::sqrt(beta1);
  std::copy(r1_.begin(), r1_.end(), y_.begin());

  constexpr Real eps = std::numeric_limits<Real>::epsilon();
  Real oldb = 0, beta = beta1, dbar = 0, epsln = 0, phibar = beta1, tnorm2 = 0;
  Real cs = -1, sn = 0, gmax = 0, gmin = std::numeric_limits<Real>::max();
  const Real tolerance = parameters_.tolerance;
  const int iterations = parameters_.iterations;
  for (int itn = 0; itn < iterations; ++itn) {
    // The next Lanczos vector: v = y / beta, y = A v - (beta / oldb) r1 - (alpha / beta) r2.
    {
      const PhaseTimer timer(vector_time);
      const Real s = Real(1) / beta;
      each([&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          r2[i] = y[i];
          v[i] = y[i] * s;
        }
      });
    }
    system.multiply(factors, v_, y_);
    Real alpha = 0;
    {
      const PhaseTimer timer(vector_time);
      if (itn > 0) {
        const Real f = -beta / oldb;
        each([&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) y[i] += r1[i] * f;
        });
      }
      alpha = dot(v, y);
      const Real f = -alpha / beta;
      each([&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) y[i] += r2[i] * f;
      });
      std::swap(r1, r2);
      oldb = beta;
      beta = dot(y, y);
    }
    if (beta < 0) break;
    beta = std::sqrt(beta);
    tnorm2 += alpha * alpha + oldb * oldb + beta * beta;

    // The previous plane rotation applied to the new column, then the next rotation.
    const Real oldeps = epsln;
    const Real delta = cs * dbar + sn * alpha;
    const Real gbar = sn * dbar - cs * alpha;
    epsln = sn * beta;
    dbar = -cs * beta;
    const Real root = std::sqrt(gbar * gbar + dbar * dbar);
    const Real gamma = std::max(std::sqrt(gbar * gbar + beta * beta), eps);
    const Real denom = Real(1) / gamma;
    cs = gbar * denom;
    sn = beta * denom;
    const Real phi = cs * phibar;
    phibar = sn * phibar;

    // w = (v - oldeps w_(k-2) - delta w_(k-1)) / gamma, x += phi w; then |x|^2.
    std::swap(w, w2);
    Real x_squared = 0;
    {
      const PhaseTimer timer(vector_time);
      x_squared = sum([&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          Real t = w[i] * -oldeps;
          t += w2[i] * -delta;
          t += v[i];
          w[i] = t * denom;
          xs[i] += w[i] * phi;
        }
        return dot_range(xs, xs, begin, end);
      });
    }
    report.iterations = itn + 1;
    if (itn == 0 && beta / beta1 < 10 * eps) break;

    const Real a_norm = std::sqrt(tnorm2);
    const Real x_norm = std::sqrt(x_squared);
    const Real test1 = phibar / (a_norm * x_norm);  // |r| / (|A| |x|)
    gmax = std::max(gmax, gamma);
    gmin = std::min(gmin, gamma);
    const Real test2 = root / a_norm;  // |A r| / (|A| |r|)
    if (test1 <= 0 || test2 <= 0 || itn >= iterations - 1 || gmax / gmin >= Real(0.1) / eps ||
        a_norm * eps * x_norm >= beta1 || test2 <= tolerance || test1 <= tolerance) {
      break;
    }
  }
  std::copy(x.begin(), x.end(), previous_.begin());
  report.relative_residual = b_norm > 0 ? static_cast<double>(phibar / b_norm) : 0.0;
  return report;
}

template <class Real>
std::vector<std::int64_t> MinResSolver<Real>::carried_state() const {
  std::vector<std::int64_t> state;
  state.reserve(3 * previous_.size());
  for (const auto& p : previous_) {
    for (int c = 0; c < 3; ++c) state.push_back(carried_bits::to_bits(p[c]));
  }
  return state;
}

template <class Real>
void MinResSolver<Real>::restore_carried_state(const std::vector<std::int64_t>& state) {
  this->check_carried_state(state);
  std::size_t k = 0;
  for (auto& p : previous_) {
    for (int c = 0; c < 3; ++c) p[c] = carried_bits::from_bits<Real>(state[k++]);
  }
}

template class MinResSolver<float>;
template class MinResSolver<double>;

}  // namespace fastcorot
