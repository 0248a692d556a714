#include "fastcorot/mapping/mechanical_mapping.h"

#include "fastcorot/state/rigid3.h"

#include <algorithm>

namespace fastcorot {

template <class Real>
void LinearMapping<Real>::row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  out.clear();
  for (std::size_t k = 0; k < static_cast<std::size_t>(PointMapping<Real>::kSlots); ++k) {
    if (map_.weights[i][k] != 0) out.emplace_back(map_.vertices[i][k], map_.weights[i][k] * Mat3<Real>::Identity());
  }
}

template <class Real>
std::vector<double> LinearMapping<Real>::model_values() const {
  std::vector<double> values{static_cast<double>(map_.size())};
  for (std::size_t i = 0; i < map_.size(); ++i) {
    for (std::size_t k = 0; k < static_cast<std::size_t>(PointMapping<Real>::kSlots); ++k) {
      if (map_.weights[i][k] == 0) continue;
      values.push_back(static_cast<double>(map_.vertices[i][k]));
      values.push_back(static_cast<double>(map_.weights[i][k]));
    }
  }
  return values;
}

template <class Real>
RigidPointMapping<Real>::RigidPointMapping(RigidPoints<Real> points)
    : points_(std::move(points)), rotated_(points_.size(), Vec3<Real>::Zero()) {}

template <class Real>
Index RigidPointMapping<Real>::parent_extent() const {
  Index extent = 0;
  for (std::size_t i = 0; i < size(); ++i) extent = std::max(extent, linear_block(i) + 2);
  return extent;
}

template <class Real>
void RigidPointMapping<Real>::apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) {
  const std::vector<RigidCoord<Real>> coords = points_.frames->coords(x);
  for (std::size_t i = 0; i < size(); ++i) {
    const RigidCoord<Real>& frame = coords[static_cast<std::size_t>(points_.rigid[i])];
    rotated_[i] = frame.rotate(points_.local[i]);
    y[i] = frame.center + rotated_[i];
  }
}

template <class Real>
void RigidPointMapping<Real>::apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const {
  for (std::size_t i = 0; i < size(); ++i) {
    const auto b = static_cast<std::size_t>(linear_block(i));
    dy[i] = dx[b] + dx[b + 1].cross(rotated_[i]);
  }
}

template <class Real>
void RigidPointMapping<Real>::apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const {
  for (std::size_t i = 0; i < size(); ++i) {
    const auto b = static_cast<std::size_t>(linear_block(i));
    parent[b] += f[i];
    parent[b + 1] += rotated_[i].cross(f[i]);
  }
}

template <class Real>
void RigidPointMapping<Real>::row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  out.clear();
  const Index b = linear_block(i);
  out.emplace_back(b, Mat3<Real>::Identity());
  out.emplace_back(b + 1, -cross_matrix(rotated_[i]));
}

template <class Real>
std::vector<double> RigidPointMapping<Real>::model_values() const {
  std::vector<double> values{static_cast<double>(size())};
  for (std::size_t i = 0; i < size(); ++i) {
    values.push_back(static_cast<double>(points_.rigid[i]));
    for (int c = 0; c < 3; ++c) values.push_back(static_cast<double>(points_.local[i][c]));
  }
  return values;
}

template class LinearMapping<float>;
template class LinearMapping<double>;
template class RigidPointMapping<float>;
template class RigidPointMapping<double>;

template <class Real>
StackedMapping<Real>::StackedMapping(std::vector<std::unique_ptr<MechanicalMapping<Real>>> parts) : parts_(std::move(parts)) {
  for (const auto& part : parts_) {
    first_.push_back(size_);
    size_ += part->size();
  }
}

template <class Real>
Index StackedMapping<Real>::parent_extent() const {
  Index extent = 0;
  for (const auto& part : parts_) extent = std::max(extent, part->parent_extent());
  return extent;
}

template <class Real>
void StackedMapping<Real>::apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) {
  for (std::size_t k = 0; k < parts_.size(); ++k) parts_[k]->apply(x, part_of(y, k));
}

template <class Real>
void StackedMapping<Real>::positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const {
  for (std::size_t k = 0; k < parts_.size(); ++k) parts_[k]->positions(x, part_of(y, k));
}

template <class Real>
void StackedMapping<Real>::velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const {
  for (std::size_t k = 0; k < parts_.size(); ++k) parts_[k]->velocities(x, v, part_of(y, k));
}

template <class Real>
void StackedMapping<Real>::apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const {
  for (std::size_t k = 0; k < parts_.size(); ++k) parts_[k]->apply_j(dx, part_of(dy, k));
}

template <class Real>
void StackedMapping<Real>::apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const {
  for (std::size_t k = 0; k < parts_.size(); ++k) parts_[k]->apply_jt(part_of(f, k), parent);
}

template <class Real>
void StackedMapping<Real>::row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const {
  std::size_t k = parts_.size() - 1;
  while (first_[k] > i) --k;
  parts_[k]->row_blocks(i - first_[k], out);
}

template <class Real>
std::vector<double> StackedMapping<Real>::model_values() const {
  std::vector<double> values;
  for (const auto& part : parts_) {
    const auto v = part->model_values();
    values.push_back(static_cast<double>(v.size()));
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

template class StackedMapping<double>;

}  // namespace fastcorot
