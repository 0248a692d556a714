#include "fastcorot/constraint/constraint_points.h"

#include "fastcorot/state/rigid3.h"

#include <algorithm>

namespace fastcorot {

template <class Real>
void PrescribedMotion<Real>::apply(double time, std::vector<Vec3<Real>>& points) {
  movement.apply(time, state, frames.get());
  if (!frames) {
    points = state.position;
    return;
  }
  const std::vector<RigidCoord<Real>> coords = frames->coords(state.position);
  points.resize(local.size());
  for (std::size_t i = 0; i < local.size(); ++i) points[i] = coords[rigid[i]].project_point(local[i]);
}

template <class Real>
void ConstraintPoints<Real>::prepare(const MechanicalState<Real>& start, const MechanicalState<Real>& free, Real h) {
  if (unsimulated) return;
  const std::size_t n = size();
  position.resize(n);
  free_position.resize(n);
  free_velocity.resize(n);
  if (!mapping) {
    for (std::size_t i = 0; i < n; ++i) {
      const auto b = static_cast<std::size_t>(blocks[i]);
      position[i] = start.position[b];
      free_position[i] = free.position[b];
      free_velocity[i] = free.velocity[b];
    }
    return;
  }
  // J at the start of the step (apply records a nonlinear mapping's linearisation there).
  mapping->apply(start.position, position);
  mapping->apply_j(free.velocity, free_velocity);
  for (std::size_t i = 0; i < n; ++i) free_position[i] = position[i] + h * free_velocity[i];
}

template <class Real>
void ConstraintRows<Real>::add(int row, const ConstraintPoints<Real>& points, std::size_t i, const Vec3<Real>& c) {
  if (points.unsimulated) return;
  if (points.constraint_force) kept_.push_back({row, points.constraint_force.get(), i, c});
  auto& entries = entries_[points.object];
  if (!points.mapping) {
    entries.push_back({row, points.blocks[i], c});
    return;
  }
  points.mapping->row_blocks(i, row_blocks_);
  for (const auto& [block, j] : row_blocks_) entries.push_back({row, block, j.transpose() * c});
}

template <class Real>
void ConstraintRows<Real>::store_constraint_forces(const Real* lambda, Real h) const {
  // SOFA: Hᵀλ on the state, then scaled by 1/h as the next step begins.
  for (const KeptEntry& e : kept_) (*e.sink)[e.point] += e.value * lambda[e.row];
  const Real inverse_h = Real(1) / h;
  std::vector<std::vector<Vec3<Real>>*> sinks;
  for (const KeptEntry& e : kept_) {
    if (std::find(sinks.begin(), sinks.end(), e.sink) == sinks.end()) sinks.push_back(e.sink);
  }
  for (auto* sink : sinks) {
    for (auto& f : *sink) f *= inverse_h;
  }
}

template <class Real>
Eigen::SparseMatrix<Real> ConstraintRows<Real>::transposed(std::size_t o, Index points) const {
  std::vector<Eigen::Triplet<Real>> triplets;
  triplets.reserve(3 * entries_[o].size());
  for (const Entry& e : entries_[o]) {
    for (int k = 0; k < 3; ++k) {
      if (e.value[k] != 0) triplets.emplace_back(3 * e.block + k, e.row, e.value[k]);
    }
  }
  Eigen::SparseMatrix<Real> ht(3 * points, rows_);
  ht.setFromTriplets(triplets.begin(), triplets.end());
  return ht;
}

template struct PrescribedMotion<float>;
template struct PrescribedMotion<double>;
template struct ConstraintPoints<float>;
template struct ConstraintPoints<double>;
template class ConstraintRows<float>;
template class ConstraintRows<double>;

}  // namespace fastcorot
