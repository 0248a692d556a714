// SoftRobots' SurfacePressureConstraint<Vec3> (SoftRobots/component/constraint/SurfacePressureConstraint,
// model/SurfacePressureModel): a cavity bounded by triangles and quads of a state (usually mapped on
// a deformable body), inflated as one Lagrangian row that imposes its pressure (valueType pressure,
// the default) or its volume growth (volumeGrowth). Design: docs/softrobots.md.
//
// Volume: V(x) = |Σ_t n_x(t) (p_0 + p_1 + p_2)_x / 6| over the triangles (a quad as (0, 1, 2) and
// (0, 2, 3)), n(t) = (p_1 - p_0) × (p_2 - p_0) (the divergence theorem along x, in SoftRobots'
// order of operations). The row, at the step's start positions, is the surface's area vectors
// shared among their vertices: ½ (p_1 - p_0) × (p_2 - p_0) / 3 on each vertex of a triangle,
// (½ (p_1 - p_0) × (p_3 - p_0) + ½ (p_3 - p_2) × (p_1 - p_2)) / 4 on each of a quad's, negated with
// flipNormal: ∂V/∂x for normals facing out of the cavity, so that a positive λ inflates it.
// Violation: δ_free = J (x_free - x) + V(x) - V_0 (V_0 the volume as the scene is built): the growth.
// Resolution, command c = value[valueIndex]:
//   pressure: c limited to within maxPressureVariation of the current pressure output, to
//     [minPressure, maxPressure]; each sweep λ = c unless W_aa c + d exceeds maxVolumeGrowth (then λ
//     moves to it); SoftRobots' test of minVolumeGrowth is overwritten by λ = c, and so it is here;
//   volumeGrowth: c limited to within maxVolumeGrowthVariation of the current volumeGrowth, to
//     [minVolumeGrowth, maxVolumeGrowth]; each sweep λ -= (d - c) / W_aa, clamped to [minPressure,
//     maxPressure].
// λ is an impulse (SOFA's λ = h F): the pressure is λ / dt. Outputs as SoftRobots has them:
// cavityVolume = V at the last step's start, volumeGrowth = cavityVolume - initialCavityVolume and
// pressure = λ (set after the solve).
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"

#include <array>
#include <optional>

namespace fastcorot {

template <class Real>
class SurfacePressureConstraint final : public LagrangianConstraint<Real> {
 public:
  enum class ValueType { pressure, volume_growth };
  struct Parameters {
    std::vector<std::array<Index, 3>> triangles;
    std::vector<std::array<Index, 4>> quads;
    bool flip_normal = false;
    std::vector<Real> value{Real(0)};
    std::size_t value_index = 0;
    ValueType value_type = ValueType::pressure;
    // Bounds (unset: none).
    std::optional<Real> max_pressure, min_pressure, max_pressure_variation, max_volume_growth, min_volume_growth,
        max_volume_growth_variation;
  };
  struct Outputs {
    Real initial_volume = 0;
    Real volume = 0;
    Real volume_growth = 0;
    Real pressure = 0;
  };

  // `initial_positions`: the state's positions as the scene is built (the initial volume). Throws
  // fastcorot::Error naming an index out of range, a surface with no triangle or quad, an empty
  // `value` or a valueIndex beyond it, or a bound that is not finite.
  SurfacePressureConstraint(std::string where, ConstraintPoints<Real> points, std::span<const Vec3<Real>> initial_positions,
                            Parameters parameters);

  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&points_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;

  // Scripts read value, valueIndex, initialCavityVolume and the outputs (cavityVolume, volumeGrowth,
  // pressure), and write the first two, between steps.
  std::vector<std::string> live_data() const override;
  std::vector<double> read_live(const std::string& name) const override;
  void write_live(const std::string& name, std::span<const double> values) override;

  // The cavity's volume at positions x (of the whole state).
  Real volume(std::span<const Vec3<Real>> x) const;
  Parameters& parameters() { return parameters_; }
  const Parameters& parameters() const { return parameters_; }
  void check_parameters() const;
  const Outputs& outputs() const { return *outputs_; }
  // The last build's row, one coefficient per point of the state (zero where the surface is not).
  const std::vector<Vec3<Real>>& row() const { return row_; }

 private:
  Real command(Real& low, Real& high) const;

  ConstraintPoints<Real> points_;
  Parameters parameters_;
  std::shared_ptr<Outputs> outputs_ = std::make_shared<Outputs>();
  std::vector<Vec3<Real>> row_;
  std::vector<std::size_t> touched_;  // the points the surface reaches, in increasing order
};

}  // namespace fastcorot
