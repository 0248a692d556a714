// SOFA's StickContactConstraint response (Sofa/Component/Collision/Response/Contact:
// StickContactConstraint.inl), under FreeMotionAnimationLoop: for one pair of collision models, a
// BilateralLagrangianConstraint<Vec3> whose pairs are the contacts' two points, each at rest as
// found (rest = P − Q, the second model's point minus the first's), three rows per contact
// (−I on Q, +I on P), solved by BilateralResolution3 with SOFA's warm start per contact index. The
// collision layer sets the contacts at the step's start (ContactPipeline): made again from every
// step that finds the pair, and kept, their points following the bodies, while a step finds
// nothing (SOFA's keepAlive, true by default). Design: docs/collision.md.
#pragma once

#include "fastcorot/constraint/unilateral_lagrangian_constraint.h"

#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
struct StickContact {
  ContactSide<Real> first, second;  // Q (the first model's point), P (the second's), at the step's start
  Vec3<Real> rest = Vec3<Real>::Zero();  // P − Q when the contact was found
};

template <class Real>
class StickContactConstraint final : public LagrangianConstraint<Real> {
 public:
  explicit StickContactConstraint(std::string where) : LagrangianConstraint<Real>(std::move(where)) {}

  void set_contacts(std::vector<StickContact<Real>> contacts) { contacts_ = std::move(contacts); }
  const std::vector<StickContact<Real>>& contacts() const { return contacts_; }

  std::vector<ConstraintPoints<Real>*> point_sets() override { return {}; }
  void prepare(std::span<const SimulatedObject<Real>> objects, Real dt) override;
  void build(ConstraintRows<Real>& rows) override;
  // Position order: P_f − Q_f − rest (P_f = P + h J v_free); velocity order: v_P − v_Q + (P − Q − rest)/h.
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  void draw(ConstraintDrawer<Real>& drawer) const override;  // constraint_drawing.cpp

 private:
  std::vector<StickContact<Real>> contacts_;
  std::vector<std::array<ContactSideMotion<Real>, 2>> motion_;  // Q's, P's
  std::vector<Vec3<Real>> previous_;  // SOFA's prevForces: one warm start per contact index
};

}  // namespace fastcorot
