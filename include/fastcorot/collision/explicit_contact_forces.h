// ExplicitContactForces<Real>: the forces SOFA's explicit penalty contacts put on one simulated
// object for one step. SOFA places the PenalityContactForceField of two simulated models in the
// pipeline's node (the root, usually outside every ODE solver) and evaluates it once per step, at
// the positions the step starts from, into each state's externalForce (SolveVisitor's
// fwdInteractionForceField): a load held for the step, with no stiffness. The collision pipeline
// sets it at each step's start; the object's solve adds it to f. Design: docs/collision.md (§1, §2.5).
#pragma once

#include "fastcorot/collision/contact_force_field.h"

#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
class ExplicitContactForces final : public ContactForceField<Real> {
 public:
  explicit ExplicitContactForces(std::shared_ptr<const TetMesh> mesh) : ContactForceField<Real>(std::move(mesh)), forces_(static_cast<std::size_t>(this->mesh_->num_points()), Vec3<Real>::Zero()) {}

  // Zeroes the loads (at each step's start, before the contacts add theirs).
  void clear();
  // f += force on block `block` (throws fastcorot::Error for a block outside the object or a
  // non-finite force).
  void add(Index block, const Vec3<Real>& force);
  const std::vector<Vec3<Real>>& forces() const { return forces_; }

  std::string component() const override { return "PenalityContactForceField"; }
  std::string method_name() const override { return "explicit penalty contacts"; }
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>>, std::span<Vec3<Real>>, Real, Real = 0) const override {}
  void add_stiffness(MatrixSink<Real>&, Real, Index = 0, Real = 0) const override {}
  void add_diagonal_blocks(std::span<Mat3<Real>>, Real, Real = 0) const override {}
  // A load held for the step: -Σ f·x, as a constant force's.
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  std::size_t memory_bytes() const override { return forces_.size() * sizeof(Vec3<Real>); }

 private:
  using ContactForceField<Real>::mesh_;
  using ContactForceField<Real>::threads_;
  std::vector<Vec3<Real>> forces_;
};

}  // namespace fastcorot
