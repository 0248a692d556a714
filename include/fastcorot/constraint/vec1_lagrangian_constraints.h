// SOFA's Lagrangian constraints that exist only on one-coordinate (Vec1) states
// (Sofa/Component/Constraint/Lagrangian/Model: UniformLagrangianConstraint.inl,
// StopperLagrangianConstraint.inl). Here a Vec1 state is a mapped state whose value sits in the x
// coordinate of its points (DistanceMapping's edge extensions: mapping/distance_mapping.h), so
// rows are e_x on a point, carried to the simulated points through the mapping's Jᵀ.
// Design: docs/constraints.md.
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"

namespace fastcorot {

// UniformLagrangianConstraint<Vec1>: every coordinate of every point held at zero (or at its rest
// value with constrain_to_rest): one row per coordinate, e_j on the point. Violations, x the
// state's positions at the step's start, x_f and v_f after the free motion, r the rest positions:
//   position order  x_f - r (or x_f),  velocity order  v_f + (1/dt)(x - r) (or v_f + (1/dt) x).
// Resolutions: iterative, one bilateral row each (λ -= d / W_jj, no warm start); else one block of
// all rows solved by an LDLᵀ of its part of W (SOFA's BilateralConstraintResolutionNDof).
template <class Real>
class UniformLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  struct Parameters {
    int coordinates = 1;  // of the state's points: 1 for Vec1
    bool iterative = true;
    bool constrain_to_rest = false;  // SOFA's constrainToRestPos
  };
  // Throws fastcorot::Error for coordinates outside [1, 3] or rest positions that are not one per point.
  UniformLagrangianConstraint(std::string where, ConstraintPoints<Real> points, Parameters parameters);
  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&points_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  const Parameters& parameters() const { return parameters_; }

 private:
  ConstraintPoints<Real> points_;
  Parameters parameters_;
};

// StopperLagrangianConstraint<Vec1>: point `index`'s value kept within [min, max]: one row, e_x on
// the point; violation its free value x_f in either order (SOFA too, though in velocity order its
// mapped free positions are stale: docs/constraints.md); the resolution starts from
// λ = 0 each step and sets λ = (max - δ) / W_jj above max, (min - δ) / W_jj below min, else 0, δ
// the row's violation without its own impulse.
template <class Real>
class StopperLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  struct Parameters {
    Index index = 0;
    Real min = -100;
    Real max = 100;
  };
  // Throws fastcorot::Error for an index out of range or min > max.
  StopperLagrangianConstraint(std::string where, ConstraintPoints<Real> points, Parameters parameters);
  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&points_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  // Scripts change the bounds between steps.
  Parameters& parameters() { return parameters_; }

 private:
  ConstraintPoints<Real> points_;
  Parameters parameters_;
};

// SOFA's StopperLagrangianConstraintResolution1Dof.
template <class Real>
class StopperResolution final : public ConstraintResolution<Real> {
 public:
  StopperResolution(Real min, Real max) : ConstraintResolution<Real>(1), min_(min), max_(max) {}
  void init(int line, const DenseMatrix<Real>& w, Real* f) override;
  void resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real* dfree) override;

 private:
  Real min_, max_;
  Real w_ = 0, inverse_w_ = 0;
};

}  // namespace fastcorot
