#include "fastcorot/constraint/constraint_solvers.h"

#include "fastcorot/core/error.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

namespace fastcorot {

template <class Real>
ConstraintSolver<Real>::ConstraintSolver(ConstraintSolverParameters<Real> parameters) : parameters_(parameters) {
  if (parameters_.max_iterations < 1) throw make_error("maxIterations = ", parameters_.max_iterations, ": must be at least 1");
  if (!(parameters_.tolerance >= 0) || !std::isfinite(parameters_.tolerance)) {
    throw make_error("tolerance = ", parameters_.tolerance, ": must be a finite number >= 0");
  }
  if (!(parameters_.sor > 0 && parameters_.sor < 2)) throw make_error("sor = ", parameters_.sor, ": must lie in (0, 2)");
  if (!(parameters_.regularization >= 0) || !std::isfinite(parameters_.regularization)) {
    throw make_error("regularizationTerm = ", parameters_.regularization, ": must be a finite number >= 0");
  }
  if (!(parameters_.svd_value_factor >= 0) || !(parameters_.svd_vector_factor >= 0) || !std::isfinite(parameters_.svd_value_factor) ||
      !std::isfinite(parameters_.svd_vector_factor)) {
    throw make_error("svdSingularValueNullSpaceCriteriaFactor = ", parameters_.svd_value_factor, ", svdSingularVectorNullSpaceCriteriaFactor = ",
                     parameters_.svd_vector_factor, ": must be finite numbers >= 0");
  }
}

template <class Real>
Real ConstraintSolver<Real>::effective_tolerance(int rows) const {
  Real tolerance = parameters_.tolerance;
  if (parameters_.scale_tolerance && !parameters_.all_verified) tolerance *= static_cast<Real>(rows);
  return tolerance;
}

template <class Real>
void ConstraintSolver<Real>::regularize(ConstraintProblem<Real>& problem) const {
  const Real term = parameters_.regularization;
  if (!(term > std::numeric_limits<Real>::epsilon())) return;
  const int n = problem.size();
  if (!parameters_.svd_regularization) {
    for (int i = 0; i < n; ++i) problem.w(i, i) += term;
    return;
  }
  using Matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  const Eigen::JacobiSVD<Matrix> svd(Matrix(problem.w), Eigen::ComputeFullV);  // U is not used (V and the values are the same bits)
  const auto& values = svd.singularValues();  // decreasing
  int null_begin = -1;
  for (int i = 0; i < n; ++i) {
    if (std::fabs(values[i]) < std::fabs(values[0]) * parameters_.svd_value_factor) {
      null_begin = i;
      break;
    }
  }
  if (null_begin < 0) return;
  for (int j = 0; j < n; ++j) {
    bool in_null_space = false;
    for (int i = null_begin; i < n && !in_null_space; ++i) in_null_space = std::fabs(svd.matrixV()(j, i)) > parameters_.svd_vector_factor;
    if (in_null_space) problem.w(j, j) += term;
  }
}

template <class Real>
void ConstraintSolver<Real>::init_blocks(ConstraintProblem<Real>& problem) const {
  problem.check_blocks();
  regularize(problem);
  problem.find_column_spans();
  for (std::size_t b = 0; b < problem.resolutions.size(); ++b) {
    problem.resolutions[b]->init(problem.first_line[b], problem.w, problem.f.data());
  }
}

template <class Real>
void ConstraintSolver<Real>::store_blocks(ConstraintProblem<Real>& problem) const {
  for (std::size_t b = 0; b < problem.resolutions.size(); ++b) {
    problem.resolutions[b]->store(problem.first_line[b], problem.f.data());
  }
}

template <class Real>
Real ConstraintSolver<Real>::sweep(ConstraintProblem<Real>& problem, Real tolerance, bool& verified) const {
  if (problem.span_begin.size() != problem.resolutions.size() + 1) problem.find_column_spans();
  Real* f = problem.f.data();
  Real* d = problem.d.data();
  const Real* dfree = problem.dfree.data();
  const auto& w = problem.w;
  Real error = 0;
  Real before[8];
  std::vector<Real> before_large;
  for (std::size_t b = 0; b < problem.resolutions.size(); ++b) {
    ConstraintResolution<Real>& resolution = *problem.resolutions[b];
    const int j = problem.first_line[b];
    const int nb = resolution.lines();
    Real* old = before;
    if (nb > 8) {
      before_large.resize(static_cast<std::size_t>(nb));
      old = before_large.data();
    }
    // d = δ_free + W λ on the block's rows (each a dot product over the row's nonzero spans,
    // vectorised: the same values as SOFA's loop over the full row to round-off).
    for (int l = 0; l < nb; ++l) {
      old[l] = f[j + l];
      d[j + l] = dfree[j + l] + problem.row_times_lambda(j + l, b);
    }
    resolution.resolve(j, w, d, f, dfree);
    Real block_error = 0;
    if (nb > 1) {
      for (int l = 0; l < nb; ++l) {
        Real line = 0;
        for (int m = 0; m < nb; ++m) {
          const Real e = w(j + l, j + m) * (f[j + m] - old[m]);
          line += e * e;
        }
        line = std::sqrt(line);
        if (line > tolerance) verified = false;
        block_error += line;
      }
    } else {
      block_error = std::fabs(w(j, j) * (f[j] - old[0]));
      if (block_error > tolerance) verified = false;
    }
    if (resolution.tolerance() != 0) {
      if (block_error > resolution.tolerance()) verified = false;
      block_error *= tolerance / resolution.tolerance();
    }
    error += block_error;
  }
  return error;
}

template <class Real>
ConstraintSolveReport BlockGaussSeidelSolver<Real>::solve(ConstraintProblem<Real>& problem) {
  ConstraintSolveReport report;
  const int n = problem.size();
  if (n == 0) return report;
  const auto& p = this->parameters_;
  const Real tolerance = this->effective_tolerance(n);
  report.tolerance = static_cast<double>(tolerance);
  this->init_blocks(problem);
  if (!warm_start_) problem.f.setZero();
  DenseVector<Real> previous;
  report.converged = false;
  Real error = 0;
  for (int it = 0; it < p.max_iterations; ++it) {
    report.iterations = it + 1;
    if (p.sor != 1) previous = problem.f;
    bool verified = true;
    error = this->sweep(problem, tolerance, verified);
    if (p.sor != 1) problem.f = p.sor * problem.f + (1 - p.sor) * previous;
    if (p.all_verified ? verified : error < tolerance) {
      report.converged = true;
      break;
    }
  }
  report.error = static_cast<double>(error);
  this->store_blocks(problem);
  return report;
}

template <class Real>
ConstraintSolveReport NNCGSolver<Real>::solve(ConstraintProblem<Real>& problem) {
  ConstraintSolveReport report;
  const int n = problem.size();
  if (n == 0) return report;
  const auto& p = this->parameters_;
  const Real tolerance = this->effective_tolerance(n);
  report.tolerance = static_cast<double>(tolerance);
  this->init_blocks(problem);
  bool verified = true;
  // The first sweep gives the first direction (its error is not measured, as in SOFA).
  DenseVector<Real> before = problem.f;
  this->sweep(problem, tolerance, verified);
  DenseVector<Real> change = before - problem.f;  // SOFA's Δλ = -(λ - λ_before)
  DenseVector<Real> direction = -change;
  report.iterations = 1;
  report.converged = false;
  Real error = 0;
  for (int it = 1; it < p.max_iterations; ++it) {
    report.iterations = it + 1;
    before = problem.f;
    verified = true;
    error = this->sweep(problem, tolerance, verified);
    if (p.all_verified ? verified : error < tolerance) {
      report.converged = true;
      break;
    }
    const DenseVector<Real> change_new = before - problem.f;
    const Real old_norm = change.squaredNorm();
    const Real beta = old_norm > 0 ? change_new.squaredNorm() / old_norm : Real(0);
    change = change_new;
    if (beta > 1) {
      direction.setZero();
    } else {
      problem.f += beta * direction;
      direction = beta * direction - change;
    }
    if (change.norm() < tolerance) {
      report.converged = true;  // λ no longer moves: SOFA stops here too
      break;
    }
  }
  report.error = static_cast<double>(error);
  this->store_blocks(problem);
  return report;
}

template <class Real>
ConstraintSolveReport PreconditionedConjugateResidualSolver<Real>::solve(ConstraintProblem<Real>& problem) {
  ConstraintSolveReport report;
  const int n = problem.size();
  if (n == 0) return report;
  problem.check_blocks();
  const auto& p = this->parameters_;
  this->regularize(problem);
  const auto& w = problem.w;
  DenseVector<Real> scale(n);
  for (int j = 0; j < n; ++j) {
    if (!(w(j, j) > 0)) throw make_error("PreconditionedConjugateResidual: W's diagonal entry ", j, " is not positive");
    scale[j] = Real(1) / std::sqrt(w(j, j));
  }
  const DenseMatrix<Real> mw = scale.asDiagonal() * w * scale.asDiagonal();
  DenseVector<Real> r = -problem.dfree.cwiseProduct(scale);
  problem.f.setZero();
  DenseVector<Real> direction = r;
  DenseVector<Real> w_direction = mw * direction;
  DenseVector<Real> w_r = mw * r;
  Real rwr = r.dot(w_r);
  const Real tolerance = this->effective_tolerance(n);
  report.tolerance = static_cast<double>(tolerance);
  report.converged = false;
  const int iterations = std::min(p.max_iterations, n);
  Real error = 0;
  for (int i = 0; i < iterations; ++i) {
    // A zero residual (or direction) is the solution already: stop before dividing by zero.
    const Real direction_norm = w_direction.dot(w_direction);
    if (rwr == 0 || direction_norm == 0) {
      report.converged = true;
      error = 0;
      break;
    }
    report.iterations = i + 1;
    const Real alpha = rwr / direction_norm;
    problem.f += alpha * direction;
    r -= alpha * w_direction;
    w_r = mw * r;
    const Real old = rwr;
    rwr = r.dot(w_r);
    const Real beta = rwr / old;
    direction = r + beta * direction;
    error = 0;
    bool verified = true;
    for (std::size_t b = 0; b < problem.resolutions.size(); ++b) {
      Real block = 0;
      for (int l = 0; l < problem.resolutions[b]->lines(); ++l) {
        block += r[i] * r[i];  // SOFA's measure, as written (see the header)
        verified = verified && block < tolerance * tolerance;
      }
      error += std::sqrt(block);
    }
    if (p.all_verified ? verified : (error < tolerance && i > 0)) {
      report.converged = true;
      break;
    }
    w_direction = w_r + beta * w_direction;
  }
  problem.f = problem.f.cwiseProduct(scale);
  report.error = static_cast<double>(error);
  this->store_blocks(problem);
  return report;
}

template <class Real>
ImprovedJacobiSolver<Real>::ImprovedJacobiSolver(ConstraintSolverParameters<Real> parameters, Options options)
    : ConstraintSolver<Real>(parameters), options_(options) {
  if (!(options_.spectral_factor > 0) || !std::isfinite(options_.spectral_factor)) {
    throw make_error("spectralCorrectionFactor = ", options_.spectral_factor, ": must be a finite number > 0");
  }
  if (!(options_.conjugate_residue_speed >= 0) || !std::isfinite(options_.conjugate_residue_speed)) {
    throw make_error("conjugateResidueSpeedFactor = ", options_.conjugate_residue_speed, ": must be a finite number >= 0");
  }
}

template <class Real>
ConstraintSolveReport ImprovedJacobiSolver<Real>::solve(ConstraintProblem<Real>& problem) {
  ConstraintSolveReport report;
  const int n = problem.size();
  if (n == 0) return report;
  const auto& p = this->parameters_;
  const Real tolerance = this->effective_tolerance(n);
  report.tolerance = static_cast<double>(tolerance);
  problem.f.setZero();
  this->init_blocks(problem);  // a warm start puts λ in f, measured against δ_free alone at first
  const auto& w = problem.w;
  DenseVector<Real>& f = problem.f;
  DenseVector<Real>& d = problem.d;
  d = problem.dfree;
  DenseVector<Real> last = DenseVector<Real>::Zero(n);
  DenseVector<Real> change = DenseVector<Real>::Zero(n);
  DenseVector<Real> scaled(n);
  Real rho = 1;
  if (options_.spectral_correction) {
    // SOFA's measure: the largest squared modulus of W's eigenvalues (std::norm of each).
    const Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> dense = w;
    Real radius = 0;
    const Eigen::EigenSolver<Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>> eigen(dense, false);  // kept: eigenvalues() is a view into it
    for (const auto& value : eigen.eigenvalues()) radius = std::max(radius, std::norm(value));
    rho = options_.spectral_factor * std::min(Real(1), Real(0.9) * 2 / radius);
  }
  report.converged = false;
  Real error = 0;
  for (int it = 0; it < p.max_iterations; ++it) {
    report.iterations = it + 1;
    // SOFA's momentum weight: i / maxIterations in single precision, then its power.
    const Real fraction = static_cast<Real>(static_cast<float>(it) / static_cast<float>(p.max_iterations));
    const Real beta = options_.conjugate_residue
                          ? std::min(Real(1), static_cast<Real>(std::pow(fraction, options_.conjugate_residue_speed)))
                          : Real(0);
    d.noalias() += w * change;
    scaled = rho * d;
    bool verified = true;
    error = 0;
    for (std::size_t b = 0; b < problem.resolutions.size(); ++b) {
      const int j = problem.first_line[b];
      const int nb = problem.resolutions[b]->lines();
      problem.resolutions[b]->resolve(j, w, scaled.data(), f.data(), problem.dfree.data());
      for (int l = j; l < j + nb; ++l) {
        f[l] += beta * change[l];
        change[l] = f[l] - last[l];
        last[l] = f[l];
      }
      // The block's error with the changes known so far (later blocks' from the last iteration).
      Real block = 0;
      for (int l = j; l < j + nb; ++l) {
        block += w.row(l).cwiseProduct(change.transpose()).squaredNorm();
        verified = verified && block < tolerance * tolerance;
      }
      error += std::sqrt(block);
    }
    if (p.all_verified ? verified : (error < tolerance && it > 0)) {
      report.converged = true;
      break;
    }
  }
  report.error = static_cast<double>(error);
  this->store_blocks(problem);
  return report;
}

template class ConstraintSolver<float>;
template class ConstraintSolver<double>;
template class BlockGaussSeidelSolver<float>;
template class BlockGaussSeidelSolver<double>;
template class NNCGSolver<float>;
template class NNCGSolver<double>;
template class PreconditionedConjugateResidualSolver<float>;
template class PreconditionedConjugateResidualSolver<double>;
template class ImprovedJacobiSolver<float>;
template class ImprovedJacobiSolver<double>;

}  // namespace fastcorot
