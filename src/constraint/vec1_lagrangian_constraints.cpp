#include "fastcorot/constraint/vec1_lagrangian_constraints.h"

#include "fastcorot/core/error.h"

#include <memory>

namespace fastcorot {

template <class Real>
UniformLagrangianConstraint<Real>::UniformLagrangianConstraint(std::string where, ConstraintPoints<Real> points, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)), points_(std::move(points)), parameters_(parameters) {
  if (parameters_.coordinates < 1 || parameters_.coordinates > 3) {
    throw make_error("UniformLagrangianConstraint: ", parameters_.coordinates, " coordinates per point (1 to 3)");
  }
  if (points_.rest_position.size() != points_.size()) {
    throw make_error("the state has ", points_.size(), " points but ", points_.rest_position.size(), " rest positions");
  }
}

template <class Real>
void UniformLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  const int n = parameters_.coordinates;
  this->rows_ = static_cast<int>(points_.size()) * n;
  this->first_row_ = rows.add_rows(this->rows_);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    for (int j = 0; j < n; ++j) rows.add(this->first_row_ + static_cast<int>(i) * n + j, points_, i, Vec3<Real>::Unit(j));
  }
}

template <class Real>
void UniformLagrangianConstraint<Real>::violation(ConstraintOrder order, Real dt, Real* dfree) const {
  const int n = parameters_.coordinates;
  const Real inverse_dt = Real(1) / dt;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    for (int j = 0; j < n; ++j) {
      const Real rest = parameters_.constrain_to_rest ? points_.rest_position[i][j] : Real(0);
      Real& row = dfree[this->first_row_ + static_cast<int>(i) * n + j];
      if (order == ConstraintOrder::velocity) {
        row = parameters_.constrain_to_rest ? points_.free_velocity[i][j] + inverse_dt * (points_.position[i][j] - rest)
                                            : points_.free_velocity[i][j] + inverse_dt * points_.position[i][j];
      } else {
        row = parameters_.constrain_to_rest ? points_.free_position[i][j] - rest : points_.free_position[i][j];
      }
    }
  }
}

template <class Real>
void UniformLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  if (this->rows_ == 0) return;
  if (!parameters_.iterative) {
    problem.add_block(std::make_unique<BilateralResolutionN<Real>>(this->rows_));
    return;
  }
  for (int r = 0; r < this->rows_; ++r) problem.add_block(std::make_unique<BilateralResolution1<Real>>());
}

template <class Real>
StopperLagrangianConstraint<Real>::StopperLagrangianConstraint(std::string where, ConstraintPoints<Real> points, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)), points_(std::move(points)), parameters_(parameters) {
  if (parameters_.index < 0 || static_cast<std::size_t>(parameters_.index) >= points_.size()) {
    throw make_error("index = ", parameters_.index, " is out of range [0, ", points_.size(), ")");
  }
  if (!(parameters_.min <= parameters_.max)) throw make_error("min = ", parameters_.min, " is above max = ", parameters_.max);
}

template <class Real>
void StopperLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  this->rows_ = 1;
  this->first_row_ = rows.add_rows(1);
  rows.add(this->first_row_, points_, static_cast<std::size_t>(parameters_.index), Vec3<Real>::UnitX());
}

template <class Real>
void StopperLagrangianConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  dfree[this->first_row_] = points_.free_position[static_cast<std::size_t>(parameters_.index)][0];
}

template <class Real>
void StopperLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  problem.add_block(std::make_unique<StopperResolution<Real>>(parameters_.min, parameters_.max));
}

template <class Real>
void StopperResolution<Real>::init(int line, const DenseMatrix<Real>& w, Real* f) {
  w_ = w(line, line);
  inverse_w_ = Real(1) / w_;
  f[line] = 0;
}

template <class Real>
void StopperResolution<Real>::resolve(int line, const DenseMatrix<Real>&, const Real* d, Real* f, const Real*) {
  const Real free = d[line] - w_ * f[line];
  if (free > max_) {
    f[line] = (max_ - free) * inverse_w_;
  } else if (free < min_) {
    f[line] = (min_ - free) * inverse_w_;
  } else {
    f[line] = 0;
  }
}

template class UniformLagrangianConstraint<float>;
template class UniformLagrangianConstraint<double>;
template class StopperLagrangianConstraint<float>;
template class StopperLagrangianConstraint<double>;
template class StopperResolution<float>;
template class StopperResolution<double>;

}  // namespace fastcorot
