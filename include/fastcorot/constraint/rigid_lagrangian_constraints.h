// SOFA's FixedLagrangianConstraint<Rigid3> and BilateralLagrangianConstraint<Rigid3>
// (Sofa/Component/Constraint/Lagrangian/Model/FixedLagrangianConstraint.cpp,
// BilateralLagrangianConstraint.cpp): six rows per rigid or pair, three on the centres' blocks and
// three on the rotations' blocks, each triple one 3-row bilateral block. Design: docs/constraints.md.
//
// A rigid's pose after the free motion is its orientation at the step's start turned by the
// rotation its angular block holds until the correction (state/rigid_blocks.h), as SOFA's x + dt v.
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"
#include "fastcorot/state/rigid_blocks.h"

#include <array>
#include <memory>
#include <utility>

namespace fastcorot {

// SOFA's Quat::toEulerVector: roll, pitch, yaw (x, y, z) of q normalised as SOFA normalises,
// atan2(2(w x + y z), 1 - 2(x² + y²)), asin(2(w y - z x)) clamped to [-1, 1],
// atan2(2(w z + x y), 1 - 2(y² + z²)). q = Rz(yaw) Ry(pitch) Rx(roll).
template <class Real>
Vec3<Real> sofa_euler_vector(Eigen::Quaternion<Real> q);
// SOFA's Quat::quatToRotationVector: axis × angle, the angle in [0, π] (q negated when w < 0),
// from 2 asin(|v|) when w > 0.999 else 2 acos(w); zero when sin(angle / 2) is below machine epsilon.
template <class Real>
Vec3<Real> sofa_rotation_vector(Eigen::Quaternion<Real> q);
// SOFA's Quat::quatDiff(a, b): b⁻¹ ⊗ a, with a negated first when a·b < 0.
template <class Real>
Eigen::Quaternion<Real> sofa_quaternion_difference(Eigen::Quaternion<Real> a, const Eigen::Quaternion<Real>& b);

// The rigids of one Rigid3 MechanicalObject a constraint acts on: rigid i of the state has its
// centre at block linear.blocks[i] and its rotation offset at angular.blocks[i] of its object, and
// is rigid index[i] of the object's RigidBlocks.
template <class Real>
struct RigidConstraintFrames {
  ConstraintPoints<Real> linear, angular;
  std::shared_ptr<const RigidBlocks<Real>> rigids;
  std::vector<std::size_t> index;
  std::vector<RigidCoord<Real>> rest;     // rest poses (restPosition)
  std::vector<RigidCoord<Real>> initial;  // poses when the scene was built (SOFA's init)

  std::size_t size() const { return index.size(); }
  // Rigid i where the step began and after the free motion (once the loop has prepared the points).
  RigidCoord<Real> start_pose(std::size_t i) const;
  RigidCoord<Real> free_pose(std::size_t i) const;
};

// FixedLagrangianConstraint<Rigid3>: rigid indices[k] held at its rest pose. Rows 6k..6k+2 the axes
// on its centre, 6k+3..6k+5 the axes on its rotation; violations c_free - c_rest and
// sofa_euler_vector(q_free ⊗ q_rest⁻¹); two BilateralResolution3 per rigid, each warm-started.
template <class Real>
class RigidFixedLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  // Throws fastcorot::Error naming an index out of range.
  RigidFixedLagrangianConstraint(std::string where, RigidConstraintFrames<Real> frames, std::vector<Index> indices);
  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&frames_.linear, &frames_.angular}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  // Each held rigid's centre and the force holding it (constraint_drawing.cpp).
  void draw(ConstraintDrawer<Real>& drawer) const override;
  const RigidConstraintFrames<Real>& frames() const { return frames_; }

 private:
  RigidConstraintFrames<Real> frames_;
  std::vector<Index> indices_;
  std::vector<std::pair<Vec3<Real>, Vec3<Real>>> previous_;
};

// BilateralLagrangianConstraint<Rigid3>: rigid first[k] of object 1 (pose P) tied to rigid
// second[k] of object 2 (pose Q). Rows 6k..6k+2: -e on P's centre, +e on Q's; 6k+3..6k+5: the same
// on the rotations. Violations on the free poses: Q.c - P.c and P.rotate(rotation vector of
// quatDiff(Q.q, P.q)), minus rest[k] (6 numbers: linear, angular) when given. With
// keep_orientation_difference, P is first displaced by the initial difference (centre + (Q.c - P.c)
// at init, in the world frame; orientation P.q ⊗ quatDiff(Q.q, P.q) at init) and rest is ignored.
// As SOFA's Rigid3 specialisation: always the position violation, no warm start, no load, no
// activate (the builder warns when they are set).
template <class Real>
class RigidBilateralLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  struct Parameters {
    std::vector<Index> first, second;  // as many pairs as the shorter list
    std::vector<std::array<Real, 6>> rest;
    bool keep_orientation_difference = false;
  };
  // Throws fastcorot::Error naming an index out of range or a rest value that is not finite.
  RigidBilateralLagrangianConstraint(std::string where, RigidConstraintFrames<Real> first, RigidConstraintFrames<Real> second,
                                     Parameters parameters);
  std::vector<ConstraintPoints<Real>*> point_sets() override {
    return {&first_.linear, &first_.angular, &second_.linear, &second_.angular};
  }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  std::size_t pairs() const { return std::min(parameters_.first.size(), parameters_.second.size()); }
  // Each pair's centres joined, with the forces of the linear rows (constraint_drawing.cpp).
  void draw(ConstraintDrawer<Real>& drawer) const override;
  const Parameters& parameters() const { return parameters_; }
  // A script's new rest values (finite, checked by the caller), subtracted from the violation as
  // SOFA does (also beside keepOrientationDifference's initial difference).
  void set_rest(std::vector<std::array<Real, 6>> rest) { parameters_.rest = std::move(rest); }

 private:
  RigidConstraintFrames<Real> first_, second_;
  Parameters parameters_;
  std::vector<RigidCoord<Real>> initial_difference_;
};

}  // namespace fastcorot
