// SoftRobots' UnilateralPlaneConstraint<Vec3> (SoftRobots/component/constraint/UnilateralPlaneConstraint):
// point p_0 of a state kept on one side of the plane through its points p_1, p_2, p_3, by one
// unilateral Lagrangian row. Design: docs/softrobots.md.
//
// n = (p_2 - p_1) × (p_3 - p_1) at the step's start positions, negated with flipNormal, NOT
// normalised in the row: n on p_0 and -n/3 on each of p_1, p_2, p_3. The violation is
// δ_free = J (x_free - x) + (p_0 - p_1)·n / |n|, whose gap term is normalised while J is not: as in
// SoftRobots, consistent only when |n| is near 1 (a larger |n| corrects a crossing by less than
// it is, a smaller one by more; at rest on the plane the point stays on it either way). Resolution:
// λ ← max(0, λ - d / W_aa), from 0 each step.
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"

#include <array>

namespace fastcorot {

template <class Real>
class UnilateralPlaneConstraint final : public LagrangianConstraint<Real> {
 public:
  struct Parameters {
    std::array<Index, 4> indices{};  // the point, then three points of the plane
    bool flip_normal = false;
  };
  // Throws fastcorot::Error naming an index out of range.
  UnilateralPlaneConstraint(std::string where, ConstraintPoints<Real> points, Parameters parameters);

  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&points_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  // The last build's normal (n, unnormalised).
  const Vec3<Real>& normal() const { return normal_; }

 private:
  ConstraintPoints<Real> points_;
  Parameters parameters_;
  Vec3<Real> normal_ = Vec3<Real>::Zero();
};

}  // namespace fastcorot
