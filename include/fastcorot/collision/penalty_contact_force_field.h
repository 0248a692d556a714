// PenaltyContactForceField<Real>: SOFA's PenalityContactForceField (Sofa/Component/Collision/
// Response/Contact: PenalityContactForceField.inl, BarycentricPenalityContact.inl) on one simulated
// object, its contacts replaced at every step by the collision pipeline. A contact joins point y₁
// (side 1) and point y₂ (side 2), each a weighted sum of the object's blocks through J₁, J₂ (an
// empty J: a still obstacle's point), along the unit normal n from y₁ to y₂, with distance d and
// stiffness k:
//   pen = d − (y₂ − y₁)·n;  when pen > 0:  f₁ −= k pen n,  f₂ += k pen n  (through J₁ᵀ, J₂ᵀ),
// and the stiffness −k n nᵀ on (y₂ − y₁) for the contacts pushing at the last add_force. The points
// move with the object as y = y_t + J (x − x_t) from where the contacts were made (exact for the
// linear mappings, and for implicit Euler's one force evaluation at x_t). Design:
// docs/collision.md (§2.5, §5).
#pragma once

#include "fastcorot/collision/contact_force_field.h"
#include "fastcorot/collision/contact_jacobian.h"

#include <memory>
#include <utility>
#include <vector>

namespace fastcorot {

template <class Real>
struct PenaltyContact {
  std::vector<std::pair<Index, Mat3<Real>>> side1, side2;  // J's row blocks on the object's blocks
  Vec3<Real> y1 = Vec3<Real>::Zero(), y2 = Vec3<Real>::Zero();  // the points where the contact was made
  Vec3<Real> normal = Vec3<Real>::UnitX();
  Real distance = 0;   // d
  Real stiffness = 0;  // k
};

template <class Real>
class PenaltyContactForceField final : public ContactForceField<Real> {
 public:
  explicit PenaltyContactForceField(std::shared_ptr<const TetMesh> mesh) : ContactForceField<Real>(std::move(mesh)) {}

  // This step's contacts, made at the object's positions `x` (copied: the linearisation point).
  // Throws fastcorot::Error for a block outside the object, a non-finite value or a negative k.
  void set_contacts(std::vector<PenaltyContact<Real>> contacts, std::span<const Vec3<Real>> x);
  const std::vector<PenaltyContact<Real>>& contacts() const { return contacts_; }
  // Each contact's force on side 2 at the last add_force (k pen n, zero when not pushing).
  const std::vector<Vec3<Real>>& forces() const { return forces_; }

  std::string component() const override { return "PenalityContactForceField"; }
  std::string method_name() const override { return "penalty contacts"; }

  void add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) override;
  void add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df, Real k_factor, Real b_factor = 0) const override;
  void add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset = 0, Real b_factor = 0) const override;
  void add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor, Real b_factor = 0) const override;
  // ½ k pen² over the contacts pushing at x.
  Real potential_energy(std::span<const Vec3<Real>> x) const override;
  // Contacts are found again from the positions at every step's start: nothing to save.
  std::string unsaved_state() const override { return {}; }
  std::size_t memory_bytes() const override;

 private:
  using ContactForceField<Real>::mesh_;
  using ContactForceField<Real>::threads_;
  // y of one side at x (the linearised point).
  Vec3<Real> point(const ContactBlocks<Real>& side, const Vec3<Real>& y_t, std::span<const Vec3<Real>> x) const;

  std::vector<PenaltyContact<Real>> contacts_;
  // The products' form of each contact's Jacobians: a contact acts along its normal n only, so
  // J dx enters as n · (J₂ dx − J₁ dx) = Σ_b g_b · dx_b with g_b = ±J_bᵀ n (− on side 1), and
  // comes back as g_b times a number. Contact c's entries are [normal_begin_[c], normal_begin_[c + 1]).
  std::vector<Index> normal_begin_, normal_block_;
  std::vector<Vec3<Real>> normal_row_;
  std::vector<Vec3<Real>> x_t_;
  std::vector<char> active_;
  std::vector<Vec3<Real>> forces_;
};

}  // namespace fastcorot
