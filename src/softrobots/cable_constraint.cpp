#include "fastcorot/softrobots/cable_constraint.h"

#include "fastcorot/core/error.h"
#include "actuator_command.h"
#include "actuator_resolution.h"
#include "fastcorot/constraint/constraint_drawing.h"

#include <cmath>
#include <limits>
#include <memory>

namespace fastcorot {

namespace {

// v / |v|, or v itself when its length is not above machine epsilon (SOFA's Vec::normalize).
template <class Real>
Vec3<Real> unit(const Vec3<Real>& v) {
  const Real n = v.norm();
  return n > std::numeric_limits<Real>::epsilon() ? Vec3<Real>(v / n) : v;
}

}  // namespace

template <class Real>
CableConstraint<Real>::CableConstraint(std::string where, ConstraintPoints<Real> points,
                                       std::span<const Vec3<Real>> initial_positions, Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)), points_(std::move(points)), parameters_(std::move(parameters)) {
  auto& p = parameters_;
  if (p.indices.empty()) p.indices = {0};  // SoftRobots' default (the builder warns)
  for (std::size_t k = 0; k < p.indices.size(); ++k) {
    if (p.indices[k] < 0 || static_cast<std::size_t>(p.indices[k]) >= points_.size() ||
        static_cast<std::size_t>(p.indices[k]) >= initial_positions.size()) {
      throw make_error("indices[", k, "] = ", p.indices[k], " is out of range: the cable's state has ", points_.size(), " points");
    }
  }
  if (points_.rest_position.size() != points_.size()) {
    throw make_error("the state has ", points_.size(), " points but ", points_.rest_position.size(), " rest positions");
  }
  std::size_t pulled = p.indices.size();
  if (!p.has_pull_point) {
    if (p.indices.size() < 2) throw make_error("hasPullPoint is false: at least two indices are needed (the first one pulls)");
    p.pull_point = initial_positions[static_cast<std::size_t>(p.indices[0])];
    pulled -= 1;
  }
  sliding_ = pulled > 1;
  check_parameters();
  outputs_->initial_length = p.initial_length ? *p.initial_length : length(points_.rest_position);
  outputs_->cable_length = length(initial_positions);
}

template <class Real>
void CableConstraint<Real>::check_parameters() const {
  const auto& p = parameters_;
  softrobots_detail::check_command(p.value, p.value_index);
  if (!p.pull_point.allFinite()) throw make_error("pullPoint is not finite");
  for (const auto& bound : {p.max_force, p.min_force, p.max_positive_displacement, p.max_negative_displacement,
                            p.max_displacement_variation}) {
    if (bound && !std::isfinite(*bound)) throw make_error("a bound (maxForce, minForce, maxPositiveDisp, maxNegativeDisp, maxDispVariation) is not finite");
  }
}

template <class Real>
Real CableConstraint<Real>::length(std::span<const Vec3<Real>> x) const {
  const auto& indices = parameters_.indices;
  Vec3<Real> previous = parameters_.has_pull_point ? parameters_.pull_point : x[static_cast<std::size_t>(indices[0])];
  Real total = 0;
  for (const Index i : indices) {
    const Vec3<Real>& current = x[static_cast<std::size_t>(i)];
    total += (current - previous).norm();
    previous = current;
  }
  return total;
}

template <class Real>
void CableConstraint<Real>::build(ConstraintRows<Real>& rows) {
  const auto& p = parameters_;
  const auto& x = points_.position;
  const auto at = [&](std::size_t k) -> const Vec3<Real>& { return x[static_cast<std::size_t>(p.indices[k])]; };
  const auto point = [&](std::size_t k) { return static_cast<std::size_t>(p.indices[k]); };
  row_.clear();
  if (!sliding_) {
    if (p.has_pull_point) {
      row_.emplace_back(point(0), unit<Real>(p.pull_point - at(0)));
    } else {
      const Vec3<Real> direction = unit<Real>(at(1) - at(0));
      row_.emplace_back(point(1), -direction);
      row_.emplace_back(point(0), direction);
    }
  } else {
    const std::size_t n = p.indices.size();
    for (std::size_t k = 0; k < n; ++k) {
      if (k == 0) {
        const Vec3<Real> ahead = unit<Real>(at(0) - at(1));
        row_.emplace_back(point(0), p.has_pull_point ? Vec3<Real>(unit<Real>(p.pull_point - at(0)) - ahead) : Vec3<Real>(-ahead));
      } else if (k + 1 < n) {
        row_.emplace_back(point(k), unit<Real>(at(k - 1) - at(k)) - unit<Real>(at(k) - at(k + 1)));
      } else {
        row_.emplace_back(point(k), unit<Real>(at(k - 1) - at(k)));
      }
    }
  }
  this->rows_ = 1;
  this->first_row_ = rows.add_rows(1);
  for (const auto& [i, c] : row_) rows.add(this->first_row_, points_, i, c);
}

template <class Real>
void CableConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  Real jdx = 0;
  for (const auto& [i, c] : row_) jdx += c.dot(points_.free_position[i] - points_.position[i]);
  outputs_->cable_length = length(points_.position);
  dfree[this->first_row_] = jdx + outputs_->initial_length - outputs_->cable_length;
}

template <class Real>
Real CableConstraint<Real>::command(Real& low, Real& high) const {
  const auto& p = parameters_;
  Real c = p.value[p.value_index];
  constexpr Real kLargest = std::numeric_limits<Real>::max();
  low = -kLargest;
  high = kLargest;
  if (p.value_type == ValueType::displacement) {
    if (p.max_displacement_variation) {
      const Real now = outputs_->displacement, step = *p.max_displacement_variation;
      if (c > now && c - now > step) c = now + step;
      if (c < now && c - now < -step) c = now - step;
    }
    if (p.max_positive_displacement && c > *p.max_positive_displacement) c = *p.max_positive_displacement;
    if (p.max_negative_displacement && c < -*p.max_negative_displacement) c = -*p.max_negative_displacement;
    if (p.min_force) low = *p.min_force;
    if (p.max_force) high = *p.max_force;
    return c;
  }
  if (p.max_force && c > *p.max_force) c = *p.max_force;
  if (p.min_force && c < *p.min_force) c = *p.min_force;
  if (p.max_negative_displacement) low = -*p.max_negative_displacement;
  if (p.max_positive_displacement) high = *p.max_positive_displacement;
  return c;
}

template <class Real>
void CableConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  Real low = 0, high = 0;
  const Real c = command(low, high);
  using Resolution = softrobots_detail::ActuatorResolution<Real>;
  const auto command = parameters_.value_type == ValueType::force ? Resolution::Command::impulse : Resolution::Command::motion;
  problem.add_block(std::make_unique<Resolution>(command, c, low, high, [outputs = outputs_](Real lambda) {
    outputs->force = lambda;
    outputs->displacement = outputs->initial_length - outputs->cable_length;
  }));
}

template <class Real>
void CableConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  drawer.begin(this->where());
  std::size_t previous = parameters_.has_pull_point ? drawer.point_at(parameters_.pull_point) : 0;
  bool first = parameters_.has_pull_point;
  for (const Index index : parameters_.indices) {
    const std::size_t drawn = drawer.point(points_, static_cast<std::size_t>(index));
    if (first) drawer.pair(previous, drawn);
    previous = drawn;
    first = true;
    for (const auto& [i, c] : row_) {
      if (i == static_cast<std::size_t>(index)) drawer.force(drawn, this->first_row_, c);
    }
  }
}

template <class Real>
std::vector<std::string> CableConstraint<Real>::live_data() const {
  return {"value", "valueIndex", "pullPoint", "cableInitialLength", "cableLength", "displacement", "force"};
}

template <class Real>
std::vector<double> CableConstraint<Real>::read_live(const std::string& name) const {
  const auto& p = parameters_;
  if (name == "value") return std::vector<double>(p.value.begin(), p.value.end());
  if (name == "valueIndex") return {static_cast<double>(p.value_index)};
  if (name == "pullPoint") return {p.pull_point[0], p.pull_point[1], p.pull_point[2]};
  if (name == "cableInitialLength") return {outputs_->initial_length};
  if (name == "cableLength") return {outputs_->cable_length};
  if (name == "displacement") return {outputs_->displacement};
  if (name == "force") return {outputs_->force};
  return LagrangianConstraint<Real>::read_live(name);
}

template <class Real>
void CableConstraint<Real>::write_live(const std::string& name, std::span<const double> values) {
  if (name == "cableInitialLength" || name == "cableLength" || name == "displacement" || name == "force") {
    throw make_error(this->where(), ": ", name, " is an output (read-only while the simulation runs)");
  }
  if (name != "value" && name != "valueIndex" && name != "pullPoint") return LagrangianConstraint<Real>::write_live(name, values);
  softrobots_detail::write_checked(this->where(), parameters_, [&] {
    if (softrobots_detail::write_command(name, values, parameters_.value, parameters_.value_index)) return;
    if (values.size() != 3) throw make_error("pullPoint: expected 3 numbers, got ", values.size());
    parameters_.pull_point = Vec3<Real>(static_cast<Real>(values[0]), static_cast<Real>(values[1]), static_cast<Real>(values[2]));
  }, [&] { check_parameters(); });
}

template class CableConstraint<float>;
template class CableConstraint<double>;

}  // namespace fastcorot
