#include "fastcorot/softrobots/unilateral_plane_constraint.h"

#include "fastcorot/core/error.h"

#include <memory>

namespace fastcorot {

template <class Real>
UnilateralPlaneConstraint<Real>::UnilateralPlaneConstraint(std::string where, ConstraintPoints<Real> points, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)), points_(std::move(points)), parameters_(parameters) {
  for (std::size_t k = 0; k < 4; ++k) {
    const Index i = parameters_.indices[k];
    if (i < 0 || static_cast<std::size_t>(i) >= points_.size()) {
      throw make_error("indices[", k, "] = ", i, " is out of range: the state has ", points_.size(), " points");
    }
  }
}

template <class Real>
void UnilateralPlaneConstraint<Real>::build(ConstraintRows<Real>& rows) {
  const auto at = [&](std::size_t k) -> const Vec3<Real>& {
    return points_.position[static_cast<std::size_t>(parameters_.indices[k])];
  };
  normal_ = (at(2) - at(1)).cross(at(3) - at(1));
  if (parameters_.flip_normal) normal_ = -normal_;
  this->rows_ = 1;
  this->first_row_ = rows.add_rows(1);
  rows.add(this->first_row_, points_, static_cast<std::size_t>(parameters_.indices[0]), normal_);
  for (std::size_t k = 1; k < 4; ++k) {
    rows.add(this->first_row_, points_, static_cast<std::size_t>(parameters_.indices[k]), -normal_ / Real(3));
  }
}

template <class Real>
void UnilateralPlaneConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  const auto moved = [&](std::size_t k) {
    const auto i = static_cast<std::size_t>(parameters_.indices[k]);
    return Vec3<Real>(points_.free_position[i] - points_.position[i]);
  };
  Real jdx = normal_.dot(moved(0));
  for (std::size_t k = 1; k < 4; ++k) jdx += (-normal_ / Real(3)).dot(moved(k));
  const Vec3<Real>& p0 = points_.position[static_cast<std::size_t>(parameters_.indices[0])];
  const Vec3<Real>& p1 = points_.position[static_cast<std::size_t>(parameters_.indices[1])];
  dfree[this->first_row_] = jdx + (p0 - p1).dot(normal_) / normal_.norm();
}

template <class Real>
void UnilateralPlaneConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  problem.add_block(std::make_unique<UnilateralResolution<Real>>());
}

template class UnilateralPlaneConstraint<float>;
template class UnilateralPlaneConstraint<double>;

}  // namespace fastcorot
