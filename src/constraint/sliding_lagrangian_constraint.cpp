#include "fastcorot/constraint/sliding_lagrangian_constraint.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <limits>
#include <memory>

namespace fastcorot {

namespace {

void check_index(Index index, std::size_t size, const char* what, const char* object) {
  if (index < 0 || static_cast<std::size_t>(index) >= size) {
    throw make_error(what, " = ", index, " is out of range: ", object, " has ", size, " points");
  }
}

}  // namespace

template <class Real>
SlidingLagrangianConstraint<Real>::SlidingLagrangianConstraint(std::string where, ConstraintPoints<Real> first,
                                                               ConstraintPoints<Real> second, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)),
      first_(std::move(first)),
      second_(std::move(second)),
      parameters_(parameters) {
  check_index(parameters_.sliding_point, first_.size(), "sliding_point", "object1");
  check_index(parameters_.axis_1, second_.size(), "axis_1", "object2");
  check_index(parameters_.axis_2, second_.size(), "axis_2", "object2");
}

template <class Real>
void SlidingLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  const auto p = static_cast<std::size_t>(parameters_.sliding_point);
  const auto a = static_cast<std::size_t>(parameters_.axis_1);
  const auto b = static_cast<std::size_t>(parameters_.axis_2);
  const Vec3<Real>& P = first_.position[p];
  const Vec3<Real>& A = second_.position[a];
  const Vec3<Real>& B = second_.position[b];
  constexpr Real epsilon = std::numeric_limits<Real>::epsilon();
  directions_.clear();
  beta_ = 0;
  Vec3<Real> axis = B - A;
  const Real length = axis.norm();
  if (length < epsilon) {
    directions_ = {Vec3<Real>::UnitX(), Vec3<Real>::UnitY(), Vec3<Real>::UnitZ()};
  } else {
    axis.normalize();
    const Real along = (P - A).dot(axis);
    beta_ = std::clamp(along / length, Real(0), Real(1));
    Vec3<Real> normal = P - (A + axis * along);
    if (normal.norm() < epsilon) {
      // P on the line: any direction across it (SOFA's choice).
      Vec3<Real> x = Vec3<Real>::UnitX();
      if (x.cross(axis).norm() < epsilon) x.y() = 1;
      normal = x.cross(axis);
    }
    normal.normalize();
    directions_ = {normal, normal.cross(axis).normalized(), axis, -axis};
  }
  this->rows_ = static_cast<int>(directions_.size());
  this->first_row_ = rows.add_rows(this->rows_);
  const int row = this->first_row_;
  if (collapsed()) {
    for (int k = 0; k < 3; ++k) {
      rows.add(row + k, first_, p, directions_[static_cast<std::size_t>(k)]);
      rows.add(row + k, second_, a, -directions_[static_cast<std::size_t>(k)]);
    }
    return;
  }
  for (int k = 0; k < 2; ++k) {
    const Vec3<Real>& d = directions_[static_cast<std::size_t>(k)];
    rows.add(row + k, first_, p, d);
    rows.add(row + k, second_, a, -d * (1 - beta_));
    rows.add(row + k, second_, b, -d * beta_);
  }
  rows.add(row + 2, first_, p, directions_[2]);
  rows.add(row + 2, second_, a, -directions_[2]);
  rows.add(row + 3, first_, p, directions_[3]);
  rows.add(row + 3, second_, b, -directions_[3]);
}

template <class Real>
void SlidingLagrangianConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  const Vec3<Real>& P = first_.free_position[static_cast<std::size_t>(parameters_.sliding_point)];
  const Vec3<Real>& A = second_.free_position[static_cast<std::size_t>(parameters_.axis_1)];
  const Vec3<Real>& B = second_.free_position[static_cast<std::size_t>(parameters_.axis_2)];
  Real* d = dfree + this->first_row_;
  if (collapsed()) {
    const Vec3<Real> gap = P - A;
    for (int k = 0; k < 3; ++k) d[k] = gap[k];
    return;
  }
  const Vec3<Real> to_projection = P - (B * beta_ + A * (1 - beta_));
  d[0] = to_projection.dot(directions_[0]);
  d[1] = to_projection.dot(directions_[1]);
  d[2] = (P - A).dot(directions_[2]);
  d[3] = (P - B).dot(directions_[3]);
}

template <class Real>
void SlidingLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  const int bilateral = collapsed() ? 3 : 2;
  for (int k = 0; k < bilateral; ++k) problem.add_block(std::make_unique<BilateralResolution1<Real>>());
  if (collapsed()) return;
  for (int k = 0; k < 2; ++k) problem.add_block(std::make_unique<UnilateralResolution<Real>>());
}

template class SlidingLagrangianConstraint<float>;
template class SlidingLagrangianConstraint<double>;

}  // namespace fastcorot
