// SOFA's SlidingLagrangianConstraint<Vec3> (Sofa/Component/Constraint/Lagrangian/Model/
// SlidingLagrangianConstraint.inl): point `sliding_point` of object 1 slides, without friction, on
// the segment from point `axis_1` to point `axis_2` of object 2. Design: docs/constraints.md.
//
// Rows, from the positions at the step's start (P the sliding point, A and B the segment's ends):
//   A and B apart (|B - A| >= machine epsilon), a the unit axis (B - A) / |B - A|:
//     0: n, P's offset from its projection A + ((P - A)·a) a, normalised (when P is on the line,
//        (1, 0, 0) × a, or (1, 1, 0) × a when that is zero), +n on P, -n (1 - β) on A, -n β on B;
//     1: n × a, normalised, on the same points with the same weights;
//     2: +a on P, -a on A (unilateral: P stays beyond A);
//     3: -a on P, +a on B (unilateral: P stays before B);
//     β = (P - A)·a / |B - A| clamped to [0, 1].
//   Violations on the free positions: rows 0 and 1 (P - (β B + (1 - β) A))·dir, row 2 (P - A)·a,
//   row 3 (P - B)·(-a). Resolutions: one bilateral row each for 0 and 1, one unilateral each for 2
//   and 3 (no warm start).
//   A and B together: three bilateral rows, the axes, +e on P and -e on A; violation P - A.
// As in SOFA the violation does not depend on the constraint order (positions in both).
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"

#include <array>

namespace fastcorot {

template <class Real>
class SlidingLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  struct Parameters {
    Index sliding_point = 0;  // in object 1
    Index axis_1 = 0;         // in object 2
    Index axis_2 = 0;         // in object 2
  };
  // Throws fastcorot::Error naming an index out of range.
  SlidingLagrangianConstraint(std::string where, ConstraintPoints<Real> first, ConstraintPoints<Real> second,
                              Parameters parameters);
  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&first_, &second_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  // The sliding point and the segment's ends, the segment joined (constraint_drawing.cpp).
  void draw(ConstraintDrawer<Real>& drawer) const override;

  const Parameters& parameters() const { return parameters_; }
  // The last build's row directions on the sliding point (4, or 3 when A and B coincide) and β.
  // SOFA's `force` output is Σ directions[r] λ_r.
  const std::vector<Vec3<Real>>& directions() const { return directions_; }
  Real barycentric_coordinate() const { return beta_; }

 private:
  bool collapsed() const { return directions_.size() == 3; }

  ConstraintPoints<Real> first_, second_;
  Parameters parameters_;
  std::vector<Vec3<Real>> directions_;
  Real beta_ = 0;
};

}  // namespace fastcorot
