#include "fastcorot/constraint/stick_contact_constraint.h"

#include "fastcorot/constraint/constraint_problem.h"
#include "fastcorot/sim/simulation.h"

namespace fastcorot {

template <class Real>
void StickContactConstraint<Real>::prepare(std::span<const SimulatedObject<Real>> objects, Real dt) {
  motion_.resize(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    motion_[k] = {free_motion(contacts_[k].first, objects, dt), free_motion(contacts_[k].second, objects, dt)};
  }
}

template <class Real>
void StickContactConstraint<Real>::build(ConstraintRows<Real>& rows) {
  this->rows_ = 3 * static_cast<int>(contacts_.size());
  this->first_row_ = rows.add_rows(this->rows_);
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const auto& c = contacts_[k];
    for (int a = 0; a < 3; ++a) {
      const int row = this->first_row_ + 3 * static_cast<int>(k) + a;
      if (!c.first.still) rows.add_blocks(row, c.first.object, c.first.blocks, -Vec3<Real>::Unit(a));
      if (!c.second.still) rows.add_blocks(row, c.second.object, c.second.blocks, Vec3<Real>::Unit(a));
    }
  }
}

template <class Real>
void StickContactConstraint<Real>::violation(ConstraintOrder order, Real dt, Real* dfree) const {
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const auto& c = contacts_[k];
    Vec3<Real> gap;
    if (order == ConstraintOrder::velocity) {
      gap = (motion_[k][1].free_velocity - motion_[k][0].free_velocity) + (c.second.position - c.first.position - c.rest) / dt;
    } else {
      gap = motion_[k][1].free_position - motion_[k][0].free_position - c.rest;
    }
    for (int a = 0; a < 3; ++a) dfree[this->first_row_ + 3 * static_cast<int>(k) + a] = gap[a];
  }
}

template <class Real>
void StickContactConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  // SOFA resizes its warm starts to the pair count (shrinking drops, growing adds zeros).
  previous_.resize(contacts_.size(), Vec3<Real>::Zero());
  for (std::size_t k = 0; k < contacts_.size(); ++k) problem.add_block(std::make_unique<BilateralResolution3<Real>>(&previous_[k]));
}

template class StickContactConstraint<double>;

}  // namespace fastcorot
