#include "fastcorot/constraint/rigid_lagrangian_constraints.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fastcorot {

namespace {

void check_indices(const std::vector<Index>& indices, std::size_t size, const char* what) {
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (indices[k] < 0 || static_cast<std::size_t>(indices[k]) >= size) {
      throw make_error(what, "[", k, "] = ", indices[k], " is out of range: the Rigid3 state has ", size, " rigids");
    }
  }
}

// The pose of rigid k turned by the rotation offset theta (its angular block).
template <class Real>
RigidCoord<Real> pose(const RigidBlocks<Real>& rigids, std::size_t k, const Vec3<Real>& center, const Vec3<Real>& theta) {
  RigidCoord<Real> c;
  c.center = center;
  c.orientation = rigids.orientation[k];
  if (theta[0] != 0 || theta[1] != 0 || theta[2] != 0) integrate(c, Vec3<Real>::Zero(), theta);
  return c;
}

template <class Real>
Real quaternion_dot(const Eigen::Quaternion<Real>& a, const Eigen::Quaternion<Real>& b) {
  return a.x() * b.x() + a.y() * b.y() + a.z() * b.z() + a.w() * b.w();
}

}  // namespace

template <class Real>
Vec3<Real> sofa_euler_vector(Eigen::Quaternion<Real> q) {
  normalize_as_sofa(q);
  const Real x = q.x(), y = q.y(), z = q.z(), w = q.w();
  const Real pitch = std::max(Real(-1), std::min(Real(1), Real(2) * (w * y - z * x)));
  return {std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y)), std::asin(pitch),
          std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))};
}

template <class Real>
Vec3<Real> sofa_rotation_vector(Eigen::Quaternion<Real> q) {
  normalize_as_sofa(q);
  if (q.w() < 0) q.coeffs() *= Real(-1);
  Real sin_half, angle;
  if (q.w() > Real(0.999)) {
    sin_half = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z());
    angle = static_cast<Real>(2.0 * std::asin(sin_half));
  } else {
    const Real half = std::acos(q.w());
    sin_half = std::sin(half);
    angle = 2 * half;
  }
  if (sin_half < std::numeric_limits<Real>::epsilon()) return Vec3<Real>::Zero();
  return Vec3<Real>(q.x(), q.y(), q.z()) / sin_half * angle;
}

template <class Real>
Eigen::Quaternion<Real> sofa_quaternion_difference(Eigen::Quaternion<Real> a, const Eigen::Quaternion<Real>& b) {
  if (quaternion_dot(a, b) < 0) a.coeffs() *= Real(-1);
  return quaternion_product(quaternion_inverse(b), a);
}

template <class Real>
RigidCoord<Real> RigidConstraintFrames<Real>::start_pose(std::size_t i) const {
  return pose(*rigids, index[i], linear.position[i], angular.position[i]);
}

template <class Real>
RigidCoord<Real> RigidConstraintFrames<Real>::free_pose(std::size_t i) const {
  return pose(*rigids, index[i], linear.free_position[i], angular.free_position[i]);
}

template <class Real>
RigidFixedLagrangianConstraint<Real>::RigidFixedLagrangianConstraint(std::string where, RigidConstraintFrames<Real> frames,
                                                                     std::vector<Index> indices)
    : LagrangianConstraint<Real>(std::move(where)), frames_(std::move(frames)), indices_(std::move(indices)) {
  check_indices(indices_, frames_.size(), "indices");
  if (frames_.rest.size() != frames_.size()) throw make_error("the Rigid3 state has ", frames_.size(), " rigids but ", frames_.rest.size(), " rest poses");
  previous_.assign(indices_.size(), {Vec3<Real>::Zero(), Vec3<Real>::Zero()});
}

template <class Real>
void RigidFixedLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  this->rows_ = static_cast<int>(6 * indices_.size());
  this->first_row_ = rows.add_rows(this->rows_);
  for (std::size_t k = 0; k < indices_.size(); ++k) {
    const auto i = static_cast<std::size_t>(indices_[k]);
    const int row = this->first_row_ + static_cast<int>(6 * k);
    for (int a = 0; a < 3; ++a) {
      rows.add(row + a, frames_.linear, i, Vec3<Real>::Unit(a));
      rows.add(row + 3 + a, frames_.angular, i, Vec3<Real>::Unit(a));
    }
  }
}

template <class Real>
void RigidFixedLagrangianConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  for (std::size_t k = 0; k < indices_.size(); ++k) {
    const auto i = static_cast<std::size_t>(indices_[k]);
    const RigidCoord<Real> free = frames_.free_pose(i);
    const RigidCoord<Real>& rest = frames_.rest[i];
    const Vec3<Real> linear = free.center - rest.center;
    const Vec3<Real> angular = sofa_euler_vector(quaternion_product(free.orientation, quaternion_inverse(rest.orientation)));
    Real* d = dfree + this->first_row_ + 6 * k;
    for (int a = 0; a < 3; ++a) {
      d[a] = linear[a];
      d[3 + a] = angular[a];
    }
  }
}

template <class Real>
void RigidFixedLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  for (auto& [linear, angular] : previous_) {
    problem.add_block(std::make_unique<BilateralResolution3<Real>>(&linear));
    problem.add_block(std::make_unique<BilateralResolution3<Real>>(&angular));
  }
}

template <class Real>
RigidBilateralLagrangianConstraint<Real>::RigidBilateralLagrangianConstraint(std::string where, RigidConstraintFrames<Real> first,
                                                                             RigidConstraintFrames<Real> second, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)),
      first_(std::move(first)),
      second_(std::move(second)),
      parameters_(std::move(parameters)) {
  check_indices(parameters_.first, first_.size(), "first_point");
  check_indices(parameters_.second, second_.size(), "second_point");
  for (std::size_t k = 0; k < parameters_.rest.size(); ++k) {
    for (Real value : parameters_.rest[k]) {
      if (!std::isfinite(value)) throw make_error("rest_vector[", k, "] is not finite");
    }
  }
  if (!parameters_.keep_orientation_difference) return;
  // SOFA's bwdInit: the difference of the poses at init, orientations normalised first.
  parameters_.rest.clear();
  for (std::size_t k = 0; k < pairs(); ++k) {
    const RigidCoord<Real>& p = first_.initial.at(static_cast<std::size_t>(parameters_.first[k]));
    const RigidCoord<Real>& q = second_.initial.at(static_cast<std::size_t>(parameters_.second[k]));
    Eigen::Quaternion<Real> qp = p.orientation, qq = q.orientation;
    normalize_as_sofa(qp);
    normalize_as_sofa(qq);
    RigidCoord<Real> difference;
    difference.center = q.center - p.center;
    difference.orientation = sofa_quaternion_difference(qq, qp);
    normalize_as_sofa(difference.orientation);
    initial_difference_.push_back(difference);
  }
}

template <class Real>
void RigidBilateralLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  this->rows_ = static_cast<int>(6 * pairs());
  this->first_row_ = rows.add_rows(this->rows_);
  for (std::size_t k = 0; k < pairs(); ++k) {
    const auto i = static_cast<std::size_t>(parameters_.first[k]);
    const auto j = static_cast<std::size_t>(parameters_.second[k]);
    const int row = this->first_row_ + static_cast<int>(6 * k);
    for (int a = 0; a < 3; ++a) {
      rows.add(row + a, first_.linear, i, -Vec3<Real>::Unit(a));
      rows.add(row + a, second_.linear, j, Vec3<Real>::Unit(a));
      rows.add(row + 3 + a, first_.angular, i, -Vec3<Real>::Unit(a));
      rows.add(row + 3 + a, second_.angular, j, Vec3<Real>::Unit(a));
    }
  }
}

template <class Real>
void RigidBilateralLagrangianConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  for (std::size_t k = 0; k < pairs(); ++k) {
    RigidCoord<Real> p = first_.free_pose(static_cast<std::size_t>(parameters_.first[k]));
    const RigidCoord<Real> q = second_.free_pose(static_cast<std::size_t>(parameters_.second[k]));
    if (parameters_.keep_orientation_difference) {
      const RigidCoord<Real>& difference = initial_difference_[k];
      p.center += difference.center;
      p.orientation = quaternion_product(p.orientation, difference.orientation);
    }
    Vec3<Real> linear = q.center - p.center;
    Vec3<Real> angular = p.rotate(sofa_rotation_vector(sofa_quaternion_difference(q.orientation, p.orientation)));
    if (k < parameters_.rest.size()) {
      const auto& rest = parameters_.rest[k];
      linear -= Vec3<Real>(rest[0], rest[1], rest[2]);
      angular -= Vec3<Real>(rest[3], rest[4], rest[5]);
    }
    Real* d = dfree + this->first_row_ + 6 * k;
    for (int a = 0; a < 3; ++a) {
      d[a] = linear[a];
      d[3 + a] = angular[a];
    }
  }
}

template <class Real>
void RigidBilateralLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  for (std::size_t k = 0; k < 2 * pairs(); ++k) problem.add_block(std::make_unique<BilateralResolution3<Real>>());
}

#define FASTCOROT_RIGID_CONSTRAINTS(Real)                                                                          \
  template Vec3<Real> sofa_euler_vector(Eigen::Quaternion<Real>);                                                  \
  template Vec3<Real> sofa_rotation_vector(Eigen::Quaternion<Real>);                                               \
  template Eigen::Quaternion<Real> sofa_quaternion_difference(Eigen::Quaternion<Real>, const Eigen::Quaternion<Real>&); \
  template struct RigidConstraintFrames<Real>;                                                                     \
  template class RigidFixedLagrangianConstraint<Real>;                                                             \
  template class RigidBilateralLagrangianConstraint<Real>;
FASTCOROT_RIGID_CONSTRAINTS(float)
FASTCOROT_RIGID_CONSTRAINTS(double)
#undef FASTCOROT_RIGID_CONSTRAINTS

}  // namespace fastcorot
