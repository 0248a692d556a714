// SubsetMultiMapping<Real>: SOFA's SubsetMultiMapping<Vec3, Vec3> as the mechanics use it. The
// child's point i is point j_i of input k_i (`indexPairs`: k_i j_i per point), each input being a
// mapping onto the solver's degrees of freedom: a simulated state's own points (a subset), a state
// mapped from one (Identity, Subset, Barycentric) or points a rigid body carries (RigidMapping).
// So the child can join points of a deformable object and points carried by rigid bodies, as
// SOFA's MeshSplittingEngine.scn and STLIB's rigidified parts do. J's rows are the inputs' rows
// (SOFA builds one Jacobian per input with a 1 per row: composed with the input's own J here);
// Jᵀ gathers each child force onto its input point and carries it up through that input's Jᵀ.
// Design: docs/mechanical-graph.md.
#pragma once

#include "fastcorot/mapping/mechanical_mapping.h"

#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace fastcorot {

template <class Real>
class SubsetMultiMapping final : public MechanicalMapping<Real> {
 public:
  // pairs[i] = (input k, point j of input k). Throws fastcorot::Error when an input or point is
  // out of range.
  SubsetMultiMapping(std::vector<std::unique_ptr<MechanicalMapping<Real>>> inputs, std::vector<std::pair<std::size_t, Index>> pairs);

  std::size_t size() const override { return picked_.size(); }
  Index parent_extent() const override { return inputs_.parent_extent(); }
  void apply(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) override;
  void positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> y) const override;
  void velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> y) const override;
  void apply_j(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> dy) const override;
  void apply_jt(std::span<const Vec3<Real>> f, std::span<Vec3<Real>> parent) const override;
  void row_blocks(std::size_t i, std::vector<std::pair<Index, Mat3<Real>>>& out) const override;
  std::vector<double> model_values() const override;

 private:
  void pick(std::span<Vec3<Real>> y) const;

  std::vector<std::size_t> picked_;  // child point i = stacked point picked_[i] (filled by inputs_' initialiser)
  StackedMapping<Real> inputs_;      // every input's points, one after the other
  mutable std::vector<Vec3<Real>> stacked_;
};

}  // namespace fastcorot
