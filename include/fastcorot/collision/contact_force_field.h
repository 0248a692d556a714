// What the contact force fields (PenaltyContactForceField, StickContactForceField,
// ExplicitContactForces) share as ForceField's: they act on the points of one object, have no
// elements of their own (no rotations, nothing to follow in a topology change, no model values for
// checkpoints' fingerprints: the contact pipeline gives them their contacts at every step), and
// their add_force_only is add_force (their linearisation is that of their contacts).
#pragma once

#include "fastcorot/fem/force_field.h"

#include <memory>
#include <utility>
#include <vector>

namespace fastcorot {

template <class Real>
class ContactForceField : public ForceField<Real> {
 public:
  const TetMesh& mesh() const override { return *mesh_; }
  void add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override { this->add_force(x, f); }
  std::vector<Mat3<Real>> rotations() const override { return {}; }
  void check_new_tetrahedra(std::span<const Tetrahedron>) const override {}
  void apply(const TopologyChange&) override {}
  std::vector<double> model_values() const override { return {}; }
  void set_threads(int threads) override { threads_ = threads; }
  int threads() const override { return threads_; }
  void set_phase_times(PhaseTimes*) override {}

 protected:
  // `mesh`: the object's points (with no tetrahedra).
  explicit ContactForceField(std::shared_ptr<const TetMesh> mesh) : mesh_(std::move(mesh)) {}

  std::shared_ptr<const TetMesh> mesh_;
  int threads_ = 1;
};

}  // namespace fastcorot
