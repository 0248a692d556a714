#include "fastcorot/softrobots/position_constraint.h"

#include "actuator_command.h"
#include "actuator_resolution.h"
#include "fastcorot/core/error.h"

#include <cmath>
#include <limits>

namespace fastcorot {

template <class Real>
PositionConstraint<Real>::PositionConstraint(std::string where, ConstraintPoints<Real> points, std::span<const Vec3<Real>> initial_positions,
                                             Parameters parameters)
    : LagrangianConstraint<Real>(std::move(where)), points_(std::move(points)), parameters_(std::move(parameters)) {
  try {
    check_parameters();
    int used = 0;
    for (std::size_t j = 0; j < 3; ++j) {
      if (!parameters_.use_directions[j]) continue;
      ++used;
      const Real norm = parameters_.directions[j].norm();
      if (!(norm > 0) || !std::isfinite(norm)) throw make_error("directions[", j, "] is zero or not finite");
      parameters_.directions[j] /= norm;
      if (!std::isfinite(parameters_.weight[j])) throw make_error("weight[", j, "] is not finite");
    }
    if (used != 1) {
      throw make_error(used == 0 ? "useDirections keeps no direction" : "useDirections keeps more than one direction",
                       ": SoftRobots makes one resolution per point, not per row, so only one direction is resolved as it is "
                       "meant (give each direction its own PositionConstraint)");
    }
    for (const Index i : parameters_.indices) {
      if (i < 0 || static_cast<std::size_t>(i) >= points_.size() || static_cast<std::size_t>(i) >= initial_positions.size()) {
        throw make_error("indices: ", i, " is out of range: the state has ", points_.size(), " points");
      }
      x0_.push_back(initial_positions[static_cast<std::size_t>(i)]);
    }
  } catch (const Error& error) {
    throw make_error(this->where(), ": ", error.what());
  }
}

template <class Real>
void PositionConstraint<Real>::check_parameters() const {
  const auto& p = parameters_;
  if (p.indices.empty()) throw make_error("indices is empty");
  softrobots_detail::check_command(p.value, p.value_index);
  for (const auto& bound : {p.max_force, p.min_force, p.max_positive_displacement, p.max_negative_displacement}) {
    if (bound && !std::isfinite(*bound)) throw make_error("a bound is not finite");
  }
}

template <class Real>
void PositionConstraint<Real>::build(ConstraintRows<Real>& rows) {
  row_directions_.clear();
  for (std::size_t j = 0; j < 3; ++j) {
    if (parameters_.use_directions[j]) row_directions_.push_back(parameters_.directions[j] * parameters_.weight[j]);
  }
  this->rows_ = static_cast<int>(parameters_.indices.size() * row_directions_.size());
  this->first_row_ = rows.add_rows(this->rows_);
  int row = this->first_row_;
  for (const Index i : parameters_.indices) {
    for (const Vec3<Real>& direction : row_directions_) rows.add(row++, points_, static_cast<std::size_t>(i), direction);
  }
}

template <class Real>
void PositionConstraint<Real>::violation(ConstraintOrder, Real, Real* dfree) const {
  int row = this->first_row_;
  for (std::size_t k = 0; k < parameters_.indices.size(); ++k) {
    const auto i = static_cast<std::size_t>(parameters_.indices[k]);
    const Vec3<Real> moved = points_.free_position[i] - points_.position[i];
    const Vec3<Real> displaced = points_.position[i] - x0_[k];
    for (const Vec3<Real>& direction : row_directions_) dfree[row++] = direction.dot(moved) + direction.dot(displaced);
  }
}

template <class Real>
void PositionConstraint<Real>::add_resolutions(ConstraintProblem<Real>& problem) {
  const auto& p = parameters_;
  Real c = p.value[p.value_index];
  constexpr Real kLargest = std::numeric_limits<Real>::max();
  Real low = -kLargest, high = kLargest;
  using Resolution = softrobots_detail::ActuatorResolution<Real>;
  auto command = Resolution::Command::motion;
  if (p.value_type == ValueType::displacement) {
    if (p.max_positive_displacement && c > *p.max_positive_displacement) c = *p.max_positive_displacement;
    if (p.max_negative_displacement && c < -*p.max_negative_displacement) c = -*p.max_negative_displacement;
  } else {
    command = Resolution::Command::impulse;
    if (p.max_force && c > *p.max_force) c = *p.max_force;
    if (p.min_force && c < *p.min_force) c = *p.min_force;
    if (p.max_negative_displacement) low = -*p.max_negative_displacement;
    if (p.max_positive_displacement) high = *p.max_positive_displacement;
  }
  for (int row = 0; row < this->rows_; ++row) {
    std::function<void(Real)> store = [](Real) {};
    if (row == 0) store = [force = force_](Real lambda) { *force = lambda; };
    problem.add_block(std::make_unique<Resolution>(command, c, low, high, std::move(store)));
  }
}

template <class Real>
std::vector<std::string> PositionConstraint<Real>::live_data() const {
  return {"value", "valueIndex", "force", "displacement"};
}

template <class Real>
std::vector<double> PositionConstraint<Real>::read_live(const std::string& name) const {
  if (name == "value") return std::vector<double>(parameters_.value.begin(), parameters_.value.end());
  if (name == "valueIndex") return {static_cast<double>(parameters_.value_index)};
  if (name == "force") return {static_cast<double>(*force_)};
  if (name == "displacement") return {0.0};
  return LagrangianConstraint<Real>::read_live(name);
}

template <class Real>
void PositionConstraint<Real>::write_live(const std::string& name, std::span<const double> values) {
  if (name == "force" || name == "displacement") {
    throw make_error(this->where(), ": ", name, " is an output (read-only while the simulation runs)");
  }
  if (name != "value" && name != "valueIndex") return LagrangianConstraint<Real>::write_live(name, values);
  softrobots_detail::write_checked(this->where(), parameters_, [&] {
    softrobots_detail::write_command(name, values, parameters_.value, parameters_.value_index);
  }, [&] { check_parameters(); });
}

template class PositionConstraint<float>;
template class PositionConstraint<double>;

}  // namespace fastcorot
