// MechanicalMapping<Real>: a mapping from a parent's Vec3 blocks to a child's points as the
// mechanics use it (SOFA's Mapping::apply, applyJ, applyJT and getJs): positions go down, increments
// and velocities go down through J, forces come up through Jᵀ, and J's row blocks let assembled
// solvers project a mapped stiffness as Jᵀ K J. Two kinds:
// - LinearMapping: a PointMapping (Identity, Subset, Barycentric): J constant, its weights.
// - RigidPointMapping: points carried by rigid bodies (RigidMapping onto a system with RigidBlocks):
//   J_i = [I₃ | -[r_i]×] at the rigid's blocks, r_i the rotated offsets of the last apply (so a
//   force field calls apply at its positions before it asks for J, as SOFA's mappings do). No
//   geometric stiffness, as SOFA's RigidMapping by default (geometricStiffness 0).
// MappedForceField uses either. Design: docs/mechanical-graph.md.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/point_mapping.h"
#include "fastcorot/mapping/rigid_points.h"

#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace fastcorot {

template <class Real>
class MechanicalMapping {
 public:
  virtual ~MechanicalMapping() = default;
  virtual std::size_t size() const = 0;
  // One past the largest parent block the mapping reads.
  virtual Index parent_extent() const = 0;
  // y = map(x), recording what J depends on (a nonlinear mapping's linearisation point).
  virtual void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) = 0;
  // y = map(x) without recording (energies, outputs).
  virtual void positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const = 0;
  // v_y = J(x) v_x without recording (the velocities outputs show).
  virtual void velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const = 0;
  // dy = J dx (increments and velocities).
  virtual void apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const = 0;
  // parent += Jᵀ f.
  virtual void apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const = 0;
  // The nonzero 3×3 blocks of J's row block i: (parent block, J_ip); `out` is overwritten.
  virtual void row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const = 0;
  // What the mapping is, as numbers (for checkpoints' model hash).
  virtual std::vector<double> model_values() const = 0;
};

template <class Real>
class LinearMapping final : public MechanicalMapping<Real> {
 public:
  explicit LinearMapping(PointMapping<Real> map) : map_(std::move(map)) {}
  std::size_t size() const override { return map_.size(); }
  Index parent_extent() const override { return map_.parent_extent(); }
  void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) override { map_.apply(x, y); }
  void positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const override { map_.apply(x, y); }
  void velocities(std::span<const Vec3<Real>>, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const override {
    map_.apply(v, y);
  }
  void apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const override { map_.apply(dx, dy); }
  void apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const override { map_.apply_jt(f, parent); }
  void row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const override;
  std::vector<double> model_values() const override;

 private:
  PointMapping<Real> map_;
};

template <class Real>
class RigidPointMapping final : public MechanicalMapping<Real> {
 public:
  explicit RigidPointMapping(RigidPoints<Real> points);
  std::size_t size() const override { return points_.size(); }
  Index parent_extent() const override;
  void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) override;
  void positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const override { points_.positions(x, y); }
  void velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const override {
    points_.velocities(x, v, y);
  }
  void apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const override;
  void apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const override;
  void row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const override;
  std::vector<double> model_values() const override;

 private:
  Index linear_block(std::size_t i) const { return points_.frames->block[static_cast<std::size_t>(points_.rigid[i])]; }

  RigidPoints<Real> points_;
  std::vector<Vec3<Real>> rotated_;  // r_i of the last apply
};

// Mappings side by side: the child's points are the first mapping's, then the second's, ... (an
// interaction force field between a mapped state and another state, or two mapped states: SOFA's
// visitors bring each side's forces up through its own Jᵀ).
template <class Real>
class StackedMapping final : public MechanicalMapping<Real> {
 public:
  explicit StackedMapping(std::vector<std::unique_ptr<MechanicalMapping<Real>>> parts);
  std::size_t size() const override { return size_; }
  Index parent_extent() const override;
  void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) override;
  void positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const override;
  void velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const override;
  void apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const override;
  void apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const override;
  void row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const override;
  std::vector<double> model_values() const override;

 private:
  template <class T>
  std::span<T> part_of(std::span<T> y, std::size_t k) const {
    return y.subspan(first_[k], parts_[k]->size());
  }

  std::vector<std::unique_ptr<MechanicalMapping<Real>>> parts_;
  std::vector<std::size_t> first_;  // each part's first child point
  std::size_t size_ = 0;
};

// The mechanics' view of points that follow a system: carried by its rigids when `rigid` is set,
// else the linear `map` (how mapped states, spring ends and multi-mapping inputs are held).
template <class Real>
std::unique_ptr<MechanicalMapping<Real>> mechanical_mapping(const PointMapping<Real>& map, const std::optional<RigidPoints<Real>>& rigid) {
  if (rigid) return std::make_unique<RigidPointMapping<Real>>(*rigid);
  return std::make_unique<LinearMapping<Real>>(map);
}

}  // namespace fastcorot
