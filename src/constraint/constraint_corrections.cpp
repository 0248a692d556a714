#include "fastcorot/constraint/constraint_corrections.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <limits>

namespace fastcorot {

namespace {

template <class Real>
Real order_factor(const IntegrationFactors<Real>& factors, ConstraintOrder order) {
  return order == ConstraintOrder::velocity ? factors.velocity : factors.position;
}

// The columns of Hᵀ that reach the object (rows of other objects' constraints are empty here):
// their indices, and the columns themselves side by side.
template <class Real>
struct ReachingColumns {
  std::vector<Index> index;
  Eigen::SparseMatrix<Real> matrix;
};

template <class Real>
ReachingColumns<Real> reaching_columns(const Eigen::SparseMatrix<Real>& ht) {
  ReachingColumns<Real> columns;
  std::vector<Eigen::Triplet<Real>> triplets;
  for (Index c = 0; c < static_cast<Index>(ht.cols()); ++c) {
    if (ht.col(c).nonZeros() == 0) continue;
    const auto k = static_cast<Index>(columns.index.size());
    columns.index.push_back(c);
    for (typename Eigen::SparseMatrix<Real>::InnerIterator it(ht, c); it; ++it) {
      triplets.emplace_back(static_cast<Index>(it.row()), k, it.value());
    }
  }
  columns.matrix.resize(ht.rows(), static_cast<Index>(columns.index.size()));
  columns.matrix.setFromTriplets(triplets.begin(), triplets.end());
  return columns;
}

}  // namespace

template <class Real>
LinearSolverConstraintCorrection<Real>::LinearSolverConstraintCorrection(std::string where, std::size_t object,
                                                                         Real regularization, Real compliance_factor)
    : ConstraintCorrection<Real>(std::move(where), object),
      regularization_(regularization),
      compliance_factor_(compliance_factor) {
  if (!(regularization_ >= 0) || !std::isfinite(regularization_)) {
    throw make_error("regularizationTerm = ", regularization_, ": must be a finite number >= 0");
  }
  if (!(compliance_factor_ > 0) || !std::isfinite(compliance_factor_)) {
    throw make_error("complianceFactor = ", compliance_factor_, ": must be a finite number > 0");
  }
}

template <class Real>
IntegrationFactors<Real> LinearSolverConstraintCorrection<Real>::factors(const SimulatedObject<Real>& object, Real dt) const {
  const auto factors = object.ode_solver->integration_factors(dt);
  if (!factors) {
    throw make_error(this->where(), ": the ODE solver of ", object.path,
                     " does not give SOFA's integration factors (use EulerImplicitSolver)");
  }
  return *factors;
}

template <class Real>
void LinearSolverConstraintCorrection<Real>::add_compliance(SimulatedObject<Real>& object, const Eigen::SparseMatrix<Real>& ht,
                                                            ConstraintOrder order, Real dt, DenseMatrix<Real>& w) {
  const IntegrationFactors<Real> f = factors(object, dt);
  const Real factor = order_factor(f, order) * compliance_factor_;
  if (const SparseFactorisation<Real>* direct = object.linear_solver->factorisation()) {
    const ReachingColumns<Real> columns = reaching_columns(ht);
    const auto block = direct->compliance(columns.matrix, object.system.threads());
    for (std::size_t a = 0; a < columns.index.size(); ++a) {
      for (std::size_t b = 0; b < columns.index.size(); ++b) {
        w(columns.index[a], columns.index[b]) += factor * block(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
      }
    }
  } else {
    // One solve per row of H that reaches the object (SOFA's addJMInvJt with an iterative solver).
    const std::size_t n = static_cast<std::size_t>(object.system.size());
    std::vector<Vec3<Real>> column(n), solution(n);
    for (int r = 0; r < ht.cols(); ++r) {
      if (ht.col(r).nonZeros() == 0) continue;
      Eigen::Map<DenseVector<Real>> b(column.data()->data(), static_cast<Eigen::Index>(3 * n));
      b = ht.col(r);
      object.linear_solver->solve_again(object.system, f.matrix, column, solution);
      const Eigen::Map<const DenseVector<Real>> y(solution.data()->data(), static_cast<Eigen::Index>(3 * n));
      w.col(r) += factor * (ht.transpose() * y);
    }
  }
  if (regularization_ > std::numeric_limits<Real>::epsilon()) {
    for (int r = 0; r < ht.cols(); ++r) {
      if (ht.col(r).nonZeros() != 0) w(r, r) += regularization_;
    }
  }
}

template <class Real>
void LinearSolverConstraintCorrection<Real>::correct(SimulatedObject<Real>& object, std::span<const Vec3<Real>> impulse,
                                                     ConstraintOrder order, Real dt) {
  const IntegrationFactors<Real> f = factors(object, dt);
  const std::size_t n = impulse.size();
  dx_.resize(n);
  object.linear_solver->solve_again(object.system, f.matrix, impulse, dx_);
  auto& x = object.system.state.position;
  auto& v = object.system.state.velocity;
  const Real position = f.position * compliance_factor_;
  const Real velocity = f.velocity * compliance_factor_;
  for (std::size_t i = 0; i < n; ++i) {
    if (order != ConstraintOrder::velocity) x[i] += dx_[i] * position;
    v[i] += dx_[i] * velocity;
  }
}

template <class Real>
UncoupledConstraintCorrection<Real>::UncoupledConstraintCorrection(std::string where, std::size_t object, Parameters parameters)
    : ConstraintCorrection<Real>(std::move(where), object), parameters_(std::move(parameters)) {
  for (std::size_t b = 0; b < parameters_.compliance.size(); ++b) {
    if (!parameters_.compliance[b].allFinite()) throw make_error("compliance of point ", b, " is not finite");
  }
}

template <class Real>
void UncoupledConstraintCorrection<Real>::add_compliance(SimulatedObject<Real>& object, const Eigen::SparseMatrix<Real>& ht,
                                                         ConstraintOrder order, Real dt, DenseMatrix<Real>& w) {
  Real factor = 1;
  if (parameters_.use_ode_factors && !this->unbuilt_) {
    const auto f = object.ode_solver->integration_factors(dt);
    if (!f) {
      throw make_error(this->where(), ": the ODE solver of ", object.path,
                       " does not give SOFA's integration factors (use EulerImplicitSolver or useOdeSolverIntegrationFactors=0)");
    }
    factor = order_factor(*f, order);
  }
  // C on the range's rows of Hᵀ: W += factor (C Hᵀ)ᵀ Hᵀ over the range.
  const Index first = 3 * parameters_.offset;
  const Index count = 3 * static_cast<Index>(parameters_.compliance.size());
  const Eigen::SparseMatrix<Real> range = ht.middleRows(first, count);
  std::vector<Eigen::Triplet<Real>> triplets;
  for (std::size_t b = 0; b < parameters_.compliance.size(); ++b) {
    const Mat3<Real>& c = parameters_.compliance[b];
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) {
        if (c(r, k) != 0) triplets.emplace_back(static_cast<Index>(3 * b) + r, static_cast<Index>(3 * b) + k, factor * c(r, k));
      }
    }
  }
  Eigen::SparseMatrix<Real> compliance(count, count);
  compliance.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SparseMatrix<Real> scaled = compliance * range;
  const Eigen::SparseMatrix<Real> product = Eigen::SparseMatrix<Real>(range.transpose()) * scaled;
  w += DenseMatrix<Real>(product);
}

template <class Real>
void UncoupledConstraintCorrection<Real>::correct(SimulatedObject<Real>& object, std::span<const Vec3<Real>> impulse,
                                                  ConstraintOrder order, Real dt) {
  Real position = parameters_.position_factor;
  Real velocity = parameters_.velocity_factor / dt;
  if (parameters_.use_ode_factors) {
    const auto f = object.ode_solver->integration_factors(dt);
    position = f->position;
    velocity = f->velocity;
  }
  auto& x = object.system.state.position;
  auto& v = object.system.state.velocity;
  for (std::size_t b = 0; b < parameters_.compliance.size(); ++b) {
    const std::size_t i = static_cast<std::size_t>(parameters_.offset) + b;
    const Vec3<Real> dx = parameters_.compliance[b] * impulse[i];
    if (order != ConstraintOrder::velocity) x[i] += dx * position;
    v[i] += dx * velocity;
  }
}

template class LinearSolverConstraintCorrection<float>;
template class LinearSolverConstraintCorrection<double>;
template class UncoupledConstraintCorrection<float>;
template class UncoupledConstraintCorrection<double>;

}  // namespace fastcorot
