// SoftRobots' PositionConstraint<Vec3> (SoftRobots/component/constraint/PositionConstraint,
// model/PositionModel): points of a state moved along chosen directions, by one Lagrangian row per
// point and direction, imposing a displacement from where they were at init (valueType
// displacement) or an impulse (valueType force). Design: docs/softrobots.md.
//
// Rows: for point i of `indices` and each direction j that useDirections keeps, w_j u_j on point i
// (u_j: directions[j] normalised, the axes by default; w_j: weight[j]). Violation:
// δ_free = J (x_free - x) + w_j u_j · (x_i - x0_i), x0 the positions at init.
// Resolution, command c = value[valueIndex], each row on its own:
//   displacement: c limited to ≤ maxPositiveDisp and ≥ -maxNegativeDisp; λ -= (d - c) / W_aa, not
//     bounded (SoftRobots computes the force bounds and drops them: its std::clamp's result is unused);
//   force: c clamped to [minForce, maxForce]; with δ = W_aa c + d below -maxNegativeDisp
//     λ -= (d + maxNegativeDisp) / W_aa, above maxPositiveDisp λ -= (d - maxPositiveDisp) / W_aa, else λ = c.
// SoftRobots makes one resolution per point, not per row: with more than one direction its rows and
// resolutions do not line up, so one direction at most is accepted here. Outputs: force = λ of the
// first row; displacement stays 0 (SoftRobots never sets it).
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"

#include <array>
#include <memory>
#include <optional>

namespace fastcorot {

template <class Real>
class PositionConstraint final : public LagrangianConstraint<Real> {
 public:
  enum class ValueType { displacement, force };
  struct Parameters {
    std::vector<Index> indices{0};
    std::array<Vec3<Real>, 3> directions{Vec3<Real>::UnitX(), Vec3<Real>::UnitY(), Vec3<Real>::UnitZ()};
    std::array<bool, 3> use_directions{true, true, true};
    std::array<Real, 3> weight{1, 1, 1};
    std::vector<Real> value{Real(0)};
    std::size_t value_index = 0;
    ValueType value_type = ValueType::displacement;
    std::optional<Real> max_force, min_force, max_positive_displacement, max_negative_displacement;  // unset: none
  };

  // `initial_positions`: the state's positions at init (x0). Throws fastcorot::Error naming an index
  // out of range, no direction or more than one, a zero direction, or a bad command.
  PositionConstraint(std::string where, ConstraintPoints<Real> points, std::span<const Vec3<Real>> initial_positions,
                     Parameters parameters);

  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&points_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;

  // Scripts read value, valueIndex and the outputs (force, displacement), and write the first two.
  std::vector<std::string> live_data() const override;
  std::vector<double> read_live(const std::string& name) const override;
  void write_live(const std::string& name, std::span<const double> values) override;
  const Parameters& parameters() const { return parameters_; }
  // λ of the first row after the last solve.
  Real force() const { return *force_; }

 private:
  void check_parameters() const;

  ConstraintPoints<Real> points_;
  Parameters parameters_;
  std::vector<Vec3<Real>> x0_;              // the points' positions at init, one per index
  std::vector<Vec3<Real>> row_directions_;  // w_j u_j of each row, per point in order
  std::shared_ptr<Real> force_ = std::make_shared<Real>(0);
};

}  // namespace fastcorot
