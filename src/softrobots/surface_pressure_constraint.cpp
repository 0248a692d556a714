#include "fastcorot/softrobots/surface_pressure_constraint.h"

#include "actuator_command.h"
#include "actuator_resolution.h"
#include "fastcorot/core/error.h"

#include <cmath>
#include <limits>
#include <memory>

namespace fastcorot {

template <class Real>
SurfacePressureConstraint<Real>::SurfacePressureConstraint(std::string where, ConstraintPoints<Real> points,
                                                           std::span<const Vec3<Real>> initial_positions, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)), points_(std::move(points)), parameters_(std::move(parameters)) {
  const auto& p = parameters_;
  if (p.triangles.empty() && p.quads.empty()) throw make_error("no triangles or quads bound the cavity");
  const std::size_t n = std::min(points_.size(), initial_positions.size());
  std::vector<char> reached(points_.size(), 0);
  const auto check = [&](std::span<const Index> element, const char* what, std::size_t k) {
    for (const Index i : element) {
      if (i < 0 || static_cast<std::size_t>(i) >= n) {
        throw make_error(what, "[", k, "] has point ", i, ", out of range: the cavity's state has ", points_.size(), " points");
      }
      reached[static_cast<std::size_t>(i)] = 1;
    }
  };
  for (std::size_t k = 0; k < p.triangles.size(); ++k) check(p.triangles[k], "triangles", k);
  for (std::size_t k = 0; k < p.quads.size(); ++k) check(p.quads[k], "quads", k);
  for (std::size_t i = 0; i < reached.size(); ++i) {
    if (reached[i]) touched_.push_back(i);
  }
  check_parameters();
  outputs_->initial_volume = outputs_->volume = volume(initial_positions);
}

template <class Real>
void SurfacePressureConstraint<Real>::check_parameters() const {
  const auto& p = parameters_;
  softrobots_detail::check_command(p.value, p.value_index);
  for (const auto& bound : {p.max_pressure, p.min_pressure, p.max_pressure_variation, p.max_volume_growth, p.min_volume_growth,
                            p.max_volume_growth_variation}) {
    if (bound && !std::isfinite(*bound)) {
      throw make_error("a bound (maxPressure, minPressure, maxPressureVariation, maxVolumeGrowth, minVolumeGrowth, "
                       "maxVolumeGrowthVariation) is not finite");
    }
  }
}

template <class Real>
Real SurfacePressureConstraint<Real>::volume(std::span<const Vec3<Real>> x) const {
  const auto term = [&](Index a, Index b, Index c) {
    const Vec3<Real>& p0 = x[static_cast<std::size_t>(a)];
    const Vec3<Real>& p1 = x[static_cast<std::size_t>(b)];
    const Vec3<Real>& p2 = x[static_cast<std::size_t>(c)];
    return ((p1[1] - p0[1]) * (p2[2] - p0[2]) - (p2[1] - p0[1]) * (p1[2] - p0[2])) * (p0[0] + p1[0] + p2[0]) / 6;
  };
  Real total = 0;
  for (const auto& t : parameters_.triangles) total += term(t[0], t[1], t[2]);
  for (const auto& q : parameters_.quads) {
    total += term(q[0], q[1], q[2]);
    total += term(q[0], q[2], q[3]);
  }
  return total < 0 ? -total : total;
}

template <class Real>
void SurfacePressureConstraint<Real>::build(ConstraintRows<Real>& rows) {
  const auto& x = points_.position;
  const auto at = [&](Index i) -> const Vec3<Real>& { return x[static_cast<std::size_t>(i)]; };
  const Real sign = parameters_.flip_normal ? Real(-1) : Real(1);
  row_.assign(points_.size(), Vec3<Real>::Zero());
  // SoftRobots adds the quads' columns first, then the triangles'.
  for (const auto& q : parameters_.quads) {
    const Vec3<Real> first = (at(q[1]) - at(q[0])).cross(at(q[3]) - at(q[0])) / Real(2);
    const Vec3<Real> second = (at(q[3]) - at(q[2])).cross(at(q[1]) - at(q[2])) / Real(2);
    const Vec3<Real> normal = sign * (first + second);
    for (const Index i : q) row_[static_cast<std::size_t>(i)] += normal * (Real(1) / Real(4));
  }
  for (const auto& t : parameters_.triangles) {
    const Vec3<Real> normal = sign * ((at(t[1]) - at(t[0])).cross(at(t[2]) - at(t[0])) / Real(2));
    for (const Index i : t) row_[static_cast<std::size_t>(i)] += normal * (Real(1) / Real(3));
  }
  this->rows_ = 1;
  this->first_row_ = rows.add_rows(1);
  for (const std::size_t i : touched_) rows.add(this->first_row_, points_, i, row_[i]);
}

template <class Real>
void SurfacePressureConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  Real jdx = 0;
  for (const std::size_t i : touched_) jdx += row_[i].dot(points_.free_position[i] - points_.position[i]);
  outputs_->volume = volume(points_.position);
  dfree[this->first_row_] = jdx + outputs_->volume - outputs_->initial_volume;
}

template <class Real>
Real SurfacePressureConstraint<Real>::command(Real& low, Real& high) const {
  const auto& p = parameters_;
  Real c = p.value[p.value_index];
  constexpr Real kLargest = std::numeric_limits<Real>::max();
  low = -kLargest;
  high = kLargest;
  const auto limit_change = [&c](const std::optional<Real>& variation, Real now) {
    if (!variation) return;
    if (c > now && c - now > *variation) c = now + *variation;
    if (c < now && c - now < -*variation) c = now - *variation;
  };
  if (p.value_type == ValueType::volume_growth) {
    limit_change(p.max_volume_growth_variation, outputs_->volume_growth);
    if (p.max_volume_growth && c > *p.max_volume_growth) c = *p.max_volume_growth;
    if (p.min_volume_growth && c < *p.min_volume_growth) c = *p.min_volume_growth;
    if (p.min_pressure) low = *p.min_pressure;
    if (p.max_pressure) high = *p.max_pressure;
    return c;
  }
  limit_change(p.max_pressure_variation, outputs_->pressure);
  if (p.max_pressure && c > *p.max_pressure) c = *p.max_pressure;
  if (p.min_pressure && c < *p.min_pressure) c = *p.min_pressure;
  if (p.min_volume_growth) low = *p.min_volume_growth;
  if (p.max_volume_growth) high = *p.max_volume_growth;
  return c;
}

template <class Real>
void SurfacePressureConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  Real low = 0, high = 0;
  const Real c = command(low, high);
  using Resolution = softrobots_detail::ActuatorResolution<Real>;
  const auto command = parameters_.value_type == ValueType::volume_growth ? Resolution::Command::motion
                                                                          : Resolution::Command::impulse_upper_bound_only;
  problem.add_block(std::make_unique<Resolution>(command, c, low, high, [outputs = outputs_](Real lambda) {
    outputs->pressure = lambda;
    outputs->volume_growth = outputs->volume - outputs->initial_volume;
  }));
}

template <class Real>
std::vector<std::string> SurfacePressureConstraint<Real>::live_data() const {
  return {"value", "valueIndex", "initialCavityVolume", "cavityVolume", "volumeGrowth", "pressure"};
}

template <class Real>
std::vector<double> SurfacePressureConstraint<Real>::read_live(const std::string& name) const {
  const auto& p = parameters_;
  if (name == "value") return std::vector<double>(p.value.begin(), p.value.end());
  if (name == "valueIndex") return {static_cast<double>(p.value_index)};
  if (name == "initialCavityVolume") return {outputs_->initial_volume};
  if (name == "cavityVolume") return {outputs_->volume};
  if (name == "volumeGrowth") return {outputs_->volume_growth};
  if (name == "pressure") return {outputs_->pressure};
  return LagrangianConstraint<Real>::read_live(name);
}

template <class Real>
void SurfacePressureConstraint<Real>::write_live(const std::string& name, std::span<const double> values) {
  if (name == "initialCavityVolume" || name == "cavityVolume" || name == "volumeGrowth" || name == "pressure") {
    throw make_error(this->where(), ": ", name, " is an output (read-only while the simulation runs)");
  }
  if (name != "value" && name != "valueIndex") return LagrangianConstraint<Real>::write_live(name, values);
  softrobots_detail::write_checked(this->where(), parameters_, [&] { softrobots_detail::write_command(name, values, parameters_.value, parameters_.value_index); },
                                   [&] { check_parameters(); });
}

template class SurfacePressureConstraint<float>;
template class SurfacePressureConstraint<double>;

}  // namespace fastcorot
