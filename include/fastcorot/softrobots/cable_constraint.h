// SoftRobots' CableConstraint<Vec3> (SoftRobots/component/constraint/CableConstraint, model/CableModel):
// a cable through points of a state (usually mapped on a deformable body), pulled from a fixed
// point, as one Lagrangian row that imposes either the cable's shortening (valueType displacement)
// or its impulse (valueType force). Design: docs/softrobots.md.
//
// Length, for points p_0 .. p_{n-1} (the `indices`) and pull point P:
//   L(x) = |p_0 - P| + Σ_{k≥1} |p_k - p_{k-1}|   (without a pull point, P is p_0: the first term is 0).
// The row is -∂L/∂x at the step's start positions (û(v) = v / |v|, zero vectors left as they are):
//   one point with a pull point:     û(P - p_0) on p_0;
//   two points, no pull point:       û(p_1 - p_0) on p_0, -û(p_1 - p_0) on p_1;
//   otherwise (the others slide):    first p_0: û(P - p_0) - û(p_0 - p_1) (no pull point: -û(p_0 - p_1)),
//                                    middle p_k: û(p_{k-1} - p_k) - û(p_k - p_{k+1}), last: û(p_{n-2} - p_{n-1}).
// Violation: δ_free = J (x_free - x) + L_0 - L(x), to first order L_0 - L(x_free): the cable's
// shortening since L_0 (cableInitialLength, by default the length at the rest positions), measured
// on positions in both constraint orders, as SoftRobots measures it.
// Resolution, command c = value[valueIndex]:
//   displacement: c limited to [displacement ∓ maxDispVariation], to ≤ maxPositiveDisp and
//     ≥ -maxNegativeDisp; each sweep λ -= (d - c) / W_aa, then clamped to [minForce, maxForce];
//   force: c clamped to [minForce, maxForce]; each sweep with δ = W_aa c + d: below -maxNegativeDisp
//     λ -= (d + maxNegativeDisp) / W_aa, above maxPositiveDisp λ -= (d - maxPositiveDisp) / W_aa,
//     else λ = c. λ is an impulse (SOFA's λ = h F): the tension is c / dt.
// Outputs as SoftRobots has them: cableLength = L at the last step's start (updated as the violation
// is measured), displacement = L_0 - cableLength and force = λ (both set after the solve).
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"

#include <optional>

namespace fastcorot {

template <class Real>
class CableConstraint final : public LagrangianConstraint<Real> {
 public:
  enum class ValueType { displacement, force };
  struct Parameters {
    std::vector<Index> indices;  // the cable's points, from the pulled one on
    Vec3<Real> pull_point = Vec3<Real>::Zero();
    bool has_pull_point = true;
    std::optional<Real> initial_length;  // cableInitialLength; unset: the length at the rest positions
    std::vector<Real> value{Real(0)};
    std::size_t value_index = 0;
    ValueType value_type = ValueType::displacement;
    // Bounds (unset: none).
    std::optional<Real> max_force, min_force, max_positive_displacement, max_negative_displacement, max_displacement_variation;
  };
  // SoftRobots' outputs.
  struct Outputs {
    Real initial_length = 0;
    Real cable_length = 0;
    Real displacement = 0;
    Real force = 0;
  };

  // `initial_positions`: the state's positions when the scene is built (for the initial cable
  // length, and the pull point when there is none). Throws fastcorot::Error naming an index out of
  // range, fewer than two points without a pull point, an empty `value` or a valueIndex beyond it,
  // or a bound that is not finite.
  CableConstraint(std::string where, ConstraintPoints<Real> points, std::span<const Vec3<Real>> initial_positions,
                  Parameters parameters);

  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&points_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  // The pull point and the cable's points joined in order, with the cable's forces on them.
  void draw(ConstraintDrawer<Real>& drawer) const override;

  // The cable's length at positions x (of the whole state).
  Real length(std::span<const Vec3<Real>> x) const;
  // Scripts read value, valueIndex, pullPoint, cableInitialLength and the outputs (cableLength,
  // displacement, force), and write the first three, between steps.
  std::vector<std::string> live_data() const override;
  std::vector<double> read_live(const std::string& name) const override;
  void write_live(const std::string& name, std::span<const double> values) override;
  // The same from C++ (check_parameters after a change).
  Parameters& parameters() { return parameters_; }
  const Parameters& parameters() const { return parameters_; }
  void check_parameters() const;
  const Outputs& outputs() const { return *outputs_; }
  // SoftRobots' reset(): cableLength back to the initial length.
  void reset() { outputs_->cable_length = outputs_->initial_length; }
  // The last build's row: (point, coefficient) pairs.
  const std::vector<std::pair<std::size_t, Vec3<Real>>>& row() const { return row_; }

 private:
  // The command and its bounds for this step's resolution.
  Real command(Real& low, Real& high) const;

  ConstraintPoints<Real> points_;
  Parameters parameters_;
  bool sliding_ = false;  // more than one point after the pulled one (SoftRobots' m_hasSlidingPoint)
  std::shared_ptr<Outputs> outputs_ = std::make_shared<Outputs>();  // shared with the resolution that stores λ
  std::vector<std::pair<std::size_t, Vec3<Real>>> row_;
};

}  // namespace fastcorot
