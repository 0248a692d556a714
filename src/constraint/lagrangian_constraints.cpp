#include "fastcorot/constraint/lagrangian_constraints.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace fastcorot {

namespace {

template <class Real>
void check_indices(const std::vector<Index>& indices, std::size_t size, const char* what) {
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (indices[k] < 0 || static_cast<std::size_t>(indices[k]) >= size) {
      throw make_error(what, "[", k, "] = ", indices[k], " is out of range [0, ", size, ")");
    }
  }
}

}  // namespace

template <class Real>
std::vector<double> LagrangianConstraint<Real>::read_live(const std::string& name) const {
  throw make_error(where_, ": '", name, "' is not a datum the running simulation keeps");
}

template <class Real>
void LagrangianConstraint<Real>::write_live(const std::string& name, std::span<const double>) {
  throw make_error(where_, ": '", name, "' cannot be changed while the simulation runs");
}

template <class Real>
FixedLagrangianConstraint<Real>::FixedLagrangianConstraint(std::string where, ConstraintPoints<Real> points,
                                                           std::vector<Index> indices)
    : LagrangianConstraint<Real>(std::move(where)), points_(std::move(points)), indices_(std::move(indices)) {
  check_indices<Real>(indices_, points_.size(), "indices");
  if (points_.rest_position.size() != points_.size()) {
    throw make_error("the state has ", points_.size(), " points but ", points_.rest_position.size(), " rest positions");
  }
  previous_.assign(indices_.size(), Vec3<Real>::Zero());
}

template <class Real>
void FixedLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  this->rows_ = static_cast<int>(3 * indices_.size());
  this->first_row_ = rows.add_rows(this->rows_);
  for (std::size_t k = 0; k < indices_.size(); ++k) {
    for (int a = 0; a < 3; ++a) {
      rows.add(this->first_row_ + static_cast<int>(3 * k) + a, points_, static_cast<std::size_t>(indices_[k]), Vec3<Real>::Unit(a));
    }
  }
}

template <class Real>
void FixedLagrangianConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  for (std::size_t k = 0; k < indices_.size(); ++k) {
    const auto i = static_cast<std::size_t>(indices_[k]);
    const Vec3<Real> gap = points_.free_position[i] - points_.rest_position[i];
    for (int a = 0; a < 3; ++a) dfree[this->first_row_ + static_cast<int>(3 * k) + a] = gap[a];
  }
}

template <class Real>
void FixedLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  for (auto& previous : previous_) problem.add_block(std::make_unique<BilateralResolution3<Real>>(&previous));
}

template <class Real>
BilateralLagrangianConstraint<Real>::BilateralLagrangianConstraint(std::string where, ConstraintPoints<Real> first,
                                                                   ConstraintPoints<Real> second, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)),
      first_(std::move(first)),
      second_(std::move(second)),
      parameters_(std::move(parameters)) {
  check_indices<Real>(parameters_.first, first_.size(), "first_point");
  check_indices<Real>(parameters_.second, second_.size(), "second_point");
  if (!(parameters_.load >= 0 && parameters_.load <= 1)) throw make_error("load = ", parameters_.load, ": must lie in [0, 1]");
  for (std::size_t k = 0; k < parameters_.rest.size(); ++k) {
    if (!parameters_.rest[k].allFinite()) throw make_error("rest_vector[", k, "] is not finite");
  }
}

template <class Real>
void BilateralLagrangianConstraint<Real>::build(ConstraintRows<Real>& rows) {
  this->rows_ = parameters_.active ? static_cast<int>(3 * pairs()) : 0;
  this->first_row_ = rows.add_rows(this->rows_);
  if (!parameters_.active) return;
  for (std::size_t k = 0; k < pairs(); ++k) {
    for (int a = 0; a < 3; ++a) {
      const int row = this->first_row_ + static_cast<int>(3 * k) + a;
      rows.add(row, first_, static_cast<std::size_t>(parameters_.first[k]), -Vec3<Real>::Unit(a));
      rows.add(row, second_, static_cast<std::size_t>(parameters_.second[k]), Vec3<Real>::Unit(a));
    }
  }
}

template <class Real>
void BilateralLagrangianConstraint<Real>::violation(ConstraintOrder order, Real dt, Real* dfree) const {
  if (!parameters_.active) return;
  for (std::size_t k = 0; k < pairs(); ++k) {
    const auto i = static_cast<std::size_t>(parameters_.first[k]);
    const auto j = static_cast<std::size_t>(parameters_.second[k]);
    const Vec3<Real> rest = k < parameters_.rest.size() ? parameters_.rest[k] : Vec3<Real>::Zero();
    Vec3<Real> gap;
    if (order == ConstraintOrder::velocity) {
      // SOFA adds the rest vector here (a sign slip, BilateralLagrangianConstraint.inl); the gap to
      // close is x2 - x1 - rest, as in the position order.
      gap = (second_.free_velocity[j] - first_.free_velocity[i]) + (second_.position[j] - first_.position[i] - rest) / dt;
    } else {
      gap = second_.free_position[j] - first_.free_position[i] - rest;
    }
    for (int a = 0; a < 3; ++a) dfree[this->first_row_ + static_cast<int>(3 * k) + a] = gap[a];
  }
}

template <class Real>
void BilateralLagrangianConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  if (!parameters_.active) return;
  // SOFA keeps one warm start per pair index (prevForces resized to the pair count).
  previous_.resize(pairs(), Vec3<Real>::Zero());
  for (std::size_t k = 0; k < pairs(); ++k) {
    problem.add_block(std::make_unique<BilateralResolution3<Real>>(&previous_[k], parameters_.load));
  }
}

template class LagrangianConstraint<float>;
template class LagrangianConstraint<double>;
template class FixedLagrangianConstraint<float>;
template class FixedLagrangianConstraint<double>;
template class BilateralLagrangianConstraint<float>;
template class BilateralLagrangianConstraint<double>;

}  // namespace fastcorot
