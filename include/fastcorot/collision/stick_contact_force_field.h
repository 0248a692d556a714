// StickContactForceField<Real>: SOFA's StickContactForceField response (Sofa/Component/Collision/
// Response/Contact: BarycentricStickContact.inl, a VectorSpringForceField between the contact
// points) on one simulated object. A spring joins point y₁ (side 1) and point y₂ (side 2), each a
// weighted sum of the object's blocks through J₁, J₂ (an empty J: a still obstacle's point), with
// rest vector R (the detection's second point minus its first when made), stiffness ks = ks₁ + ks₂
// and damping kd = cf₁ + cf₂ (the models' contactStiffness and contactFriction):
//   f = ks (y₂ − y₁ − R) + kd (v₂ − v₁);  f₁ += f,  f₂ −= f  (through J₁ᵀ, J₂ᵀ),
// the relative velocity taken at the step's start, and the stiffness −ks I on (y₂ − y₁) (the damping
// stays out of the matrix, as in SOFA). The points move with the object as y = y_t + J (x − x_t).
// Design: docs/collision.md (§2.5).
#pragma once

#include "fastcorot/collision/contact_force_field.h"
#include "fastcorot/collision/contact_jacobian.h"

#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
struct StickSpring {
  ContactBlocks<Real> side1, side2;                               // J's row blocks on the object's blocks
  Vec3<Real> y1 = Vec3<Real>::Zero(), y2 = Vec3<Real>::Zero();    // the points at the step's start
  Vec3<Real> rest = Vec3<Real>::Zero();                            // R
  Vec3<Real> relative_velocity = Vec3<Real>::Zero();               // v₂ − v₁ at the step's start
  Real stiffness = 0;                                              // ks
  Real damping = 0;                                                // kd
};

template <class Real>
class StickContactForceField final : public ContactForceField<Real> {
 public:
  explicit StickContactForceField(std::shared_ptr<const TetMesh> mesh) : ContactForceField<Real>(std::move(mesh)) {}
  // This step's springs, their points at the object's positions `x` (copied: the linearisation
  // point). Throws fastcorot::Error for a block outside the object, a non-finite value or a
  // negative stiffness or damping.
  void set_springs(std::vector<StickSpring<Real>> springs, std::span<const Vec3<Real>> x);
  const std::vector<StickSpring<Real>>& springs() const { return springs_; }
  std::string component() const override { return "StickContactForceField"; }
  std::string method_name() const override { return "stick contacts"; }
  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  // ½ ks |y₂ − y₁ − R|² over the springs.
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  // The springs persist from step to step (SOFA keeps them alive while detection finds nothing).
  std::string unsaved_state() const override { return springs_.empty() ? std::string() : "stick contact springs"; }
  std::size_t memory_bytes() const override;

 private:
  using ContactForceField<Real>::mesh_;
  using ContactForceField<Real>::threads_;
  std::vector<StickSpring<Real>> springs_;
  std::vector<Vec3<Real>> x_t_;
};

}  // namespace fastcorot
