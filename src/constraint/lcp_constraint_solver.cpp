#include "fastcorot/constraint/lcp_constraint_solver.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fastcorot {

namespace {

// One contact's Gauss–Seidel update with Coulomb friction (SOFA's LocalBlock33 GS_State): the
// normal λ from the normal violation, then both tangent λ from the tangent violations with the
// tangents' mean compliance, the tangent λ scaled back onto the disk of radius mu λ_n. `w` holds
// the contact's 3×3 block, `d` the violations without the contact's own λ; on return d includes
// the new λ, except when the contact separates (λ = 0, d left as it was).
template <class Real>
void update_contact(const Real (&w)[3][3], Real mu, Real (&d)[3], Real (&f)[3]) {
  const Real normal = w[0][0] * f[0] + w[0][1] * f[1] + w[0][2] * f[2] + d[0];
  f[0] -= normal / w[0][0];
  if (f[0] < 0) {
    f[0] = f[1] = f[2] = 0;
    return;
  }
  const Real t = w[0][1] * f[0] + w[1][1] * f[1] + w[1][2] * f[2] + d[1];
  const Real s = w[0][2] * f[0] + w[1][2] * f[1] + w[2][2] * f[2] + d[2];
  const Real tangent_compliance = w[1][1] + w[2][2];
  f[1] -= 2 * t / tangent_compliance;
  f[2] -= 2 * s / tangent_compliance;
  const Real tangent = std::sqrt(f[1] * f[1] + f[2] * f[2]);
  if (tangent > mu * f[0]) {
    f[1] *= mu * f[0] / tangent;
    f[2] *= mu * f[0] / tangent;
  }
  for (int k = 0; k < 3; ++k) d[k] += w[k][0] * f[0] + w[k][1] * f[1] + w[k][2] * f[2];
}

}  // namespace

template <class Real>
LCPConstraintSolver<Real>::LCPConstraintSolver(ConstraintSolverParameters<Real> parameters, Options options)
    : ConstraintSolver<Real>(parameters), options_(options) {
  if (!(options_.mu >= 0) || !std::isfinite(options_.mu)) throw make_error("mu = ", options_.mu, ": must be a finite number >= 0");
  if (!(options_.min_w >= 0) || !std::isfinite(options_.min_w)) throw make_error("minW = ", options_.min_w, ": must be a finite number >= 0");
  if (!(options_.max_f >= 0) || !std::isfinite(options_.max_f)) throw make_error("maxF = ", options_.max_f, ": must be a finite number >= 0");
}

template <class Real>
ConstraintSolveReport LCPConstraintSolver<Real>::solve(ConstraintProblem<Real>& problem) {
  if (problem.size() == 0) return {};
  problem.check_blocks();
  const Real regularization = this->parameters_.regularization;
  if (regularization > std::numeric_limits<Real>::epsilon()) {
    for (int i = 0; i < problem.size(); ++i) problem.w(i, i) += regularization;
  }
  // λ starts from zero: SOFA's initial guess only reaches contacts that carry persistent ids.
  problem.f.setZero();
  return options_.mu > 0 ? solve_with_friction(problem) : solve_frictionless(problem);
}

template <class Real>
ConstraintSolveReport LCPConstraintSolver<Real>::solve_with_friction(ConstraintProblem<Real>& problem) const {
  const int n = problem.size();
  if (n % 3 != 0) {
    throw make_error("LCPConstraintSolver: with mu = ", options_.mu, " it solves the rows three at a time (a contact's normal "
                     "and two tangents), but the constraints give ", n, " rows (SOFA then leaves every constraint unsolved); "
                     "use a BlockGaussSeidelConstraintSolver, or mu=\"0\"");
  }
  const int contacts = n / 3;
  const auto& w = problem.w;
  const Real* dfree = problem.dfree.data();
  Real* f = problem.f.data();
  ConstraintSolveReport report;
  const Real tolerance = this->parameters_.tolerance * static_cast<Real>(contacts + 1);
  report.tolerance = static_cast<double>(tolerance);
  report.converged = false;
  const Eigen::Map<const DenseVector<Real>> lambda(f, n);
  Real error = 0;
  for (int it = 0; it < this->parameters_.max_iterations; ++it) {
    report.iterations = it + 1;
    error = 0;
    for (int c = 0; c < contacts; ++c) {
      const int r = 3 * c;
      Real previous[3] = {f[r], f[r + 1], f[r + 2]};
      f[r] = f[r + 1] = f[r + 2] = 0;
      Real d[3];
      Real block[3][3];
      for (int k = 0; k < 3; ++k) {
        d[k] = dfree[r + k] + w.row(r + k).dot(lambda);
        for (int m = 0; m < 3; ++m) block[k][m] = w(r + std::min(k, m), r + std::max(k, m));  // SOFA reads the upper triangle
      }
      Real before[3];
      for (int k = 0; k < 3; ++k) before[k] = d[k] + block[k][0] * previous[0] + block[k][1] * previous[1] + block[k][2] * previous[2];
      if (options_.min_w != 0 && std::fabs(block[0][0]) <= options_.min_w) {
        previous[0] = previous[1] = previous[2] = 0;
      } else {
        update_contact(block, options_.mu, d, previous);
      }
      error += std::sqrt((before[0] - d[0]) * (before[0] - d[0]) + (before[1] - d[1]) * (before[1] - d[1]) +
                         (before[2] - d[2]) * (before[2] - d[2]));
      for (int k = 0; k < 3; ++k) f[r + k] = previous[k];
    }
    if (error < tolerance) {
      report.converged = true;
      if (options_.max_f != 0) {
        for (int c = 0; c < contacts; ++c) {
          if (std::fabs(f[3 * c]) >= options_.max_f) f[3 * c] = f[3 * c + 1] = f[3 * c + 2] = 0;
        }
      }
      break;
    }
  }
  report.error = static_cast<double>(error);
  return report;
}

template <class Real>
ConstraintSolveReport LCPConstraintSolver<Real>::solve_frictionless(ConstraintProblem<Real>& problem) const {
  const int n = problem.size();
  const auto& w = problem.w;
  const Real* dfree = problem.dfree.data();
  Real* f = problem.f.data();
  const Eigen::Map<const DenseVector<Real>> lambda(f, n);
  ConstraintSolveReport report;
  const Real tolerance = this->parameters_.tolerance;
  report.tolerance = static_cast<double>(tolerance);
  report.converged = false;
  Real error = 0;
  for (int it = 0; it < this->parameters_.max_iterations; ++it) {
    report.iterations = it + 1;
    error = 0;
    for (int i = 0; i < n; ++i) {
      const Real diagonal = w(i, i);
      const Real violation = dfree[i] + w.row(i).dot(lambda) - diagonal * f[i];  // without the row's own λ
      const Real previous = f[i];
      if (options_.min_w != 0 && std::fabs(diagonal) <= options_.min_w) {
        f[i] = 0;
      } else {
        f[i] = violation < 0 ? -violation / diagonal : Real(0);
      }
      error += std::fabs(diagonal * (f[i] - previous));
    }
    if (error < tolerance) {
      report.converged = true;
      break;
    }
  }
  if (options_.max_f != 0) {
    for (int i = 0; i < n; ++i) {
      if (std::fabs(f[i]) >= options_.max_f) f[i] = 0;
    }
  }
  report.error = static_cast<double>(error);
  return report;
}

template class LCPConstraintSolver<float>;
template class LCPConstraintSolver<double>;

}  // namespace fastcorot
