// What the Lagrangian constraints show: ConstraintDrawer, each constraint's draw and the loop's.
// SOFA's BilateralLagrangianConstraint::draw shows its pairs' points (magenta, green when
// inactive); fastcorot adds the segment between each pair and, for every constraint, the force its
// rows apply at each point. SOFA's FixedLagrangianConstraint draws nothing; here it shows its
// points and their holding forces too.
#include "fastcorot/constraint/constraint_drawing.h"
#include "fastcorot/constraint/rigid_lagrangian_constraints.h"
#include "fastcorot/constraint/sliding_lagrangian_constraint.h"
#include "fastcorot/constraint/unilateral_lagrangian_constraint.h"

#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/constraint/stick_contact_constraint.h"
#include "fastcorot/sim/simulation.h"

namespace fastcorot {

template <class Real>
ConstraintDrawer<Real>::ConstraintDrawer(std::span<const SimulatedObject<Real>> objects, std::span<const Real> impulses,
                                         Real dt, ConstraintDrawing& drawing)
    : objects_(objects), impulses_(impulses), dt_(dt), drawing_(drawing) {}

template <class Real>
void ConstraintDrawer<Real>::begin(const std::string& where) {
  drawing_.constraints.push_back(where);
}

template <class Real>
std::size_t ConstraintDrawer<Real>::point(const ConstraintPoints<Real>& points, std::size_t i, bool active) {
  Vec3<Real> position;
  if (points.mapping) {
    auto [it, added] = mapped_.try_emplace(&points);
    if (added) {
      it->second.resize(points.mapping->size());
      points.mapping->positions(objects_[points.object].system.state.position, it->second);
    }
    position = it->second[i];
  } else if (i < points.blocks.size()) {
    position = objects_[points.object].system.state.position[static_cast<std::size_t>(points.blocks[i])];
  } else {
    position = points.position[i];  // points of no simulated object: they stay where they were put
  }
  return point_at(position, active);
}

template <class Real>
std::size_t ConstraintDrawer<Real>::point_at(const Vec3<Real>& position, bool active) {
  ConstraintDrawing::Point p;
  p.position = position.template cast<double>();
  p.constraint = drawing_.constraints.empty() ? 0 : drawing_.constraints.size() - 1;
  p.active = active;
  drawing_.points.push_back(p);
  return drawing_.points.size() - 1;
}

template <class Real>
void ConstraintDrawer<Real>::force(std::size_t p, int row, const Vec3<Real>& c) {
  if (row < 0 || static_cast<std::size_t>(row) >= impulses_.size() || !(dt_ > 0)) return;
  const double lambda = static_cast<double>(impulses_[static_cast<std::size_t>(row)]);
  drawing_.points[p].force += c.template cast<double>() * (lambda / static_cast<double>(dt_));
}

namespace {

// Points a and b of a pair joined, with the forces of the three rows from `row` (-axis on a,
// +axis on b: the bilateral rows of Vec3 points and of Rigid3 centres); no forces when row < 0
// (rows not built for the pairs drawn).
template <class Real>
void tie(ConstraintDrawer<Real>& drawer, std::size_t a, std::size_t b, int row) {
  drawer.pair(a, b);
  if (row < 0) return;
  for (int axis = 0; axis < 3; ++axis) {
    drawer.force(a, row + axis, -Vec3<Real>::Unit(axis));
    drawer.force(b, row + axis, Vec3<Real>::Unit(axis));
  }
}

}  // namespace

template <class Real>
void FixedLagrangianConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  // Rows of the last build: 3 per index, +axis on the point (build()).
  const bool built = this->rows_ == static_cast<int>(3 * indices_.size());
  for (std::size_t k = 0; k < indices_.size(); ++k) {
    const std::size_t p = drawer.point(points_, static_cast<std::size_t>(indices_[k]));
    if (!built) continue;
    for (int a = 0; a < 3; ++a) drawer.force(p, this->first_row_ + static_cast<int>(3 * k) + a, Vec3<Real>::Unit(a));
  }
}

template <class Real>
void BilateralLagrangianConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  // Rows of the last build: 3 per pair, -axis on the first point and +axis on the second; none
  // while inactive. A script may have changed the pairs since: forces only when they still match.
  const bool built = this->rows_ > 0 && this->rows_ == static_cast<int>(3 * pairs());
  for (std::size_t k = 0; k < pairs(); ++k) {
    const std::size_t a = drawer.point(first_, static_cast<std::size_t>(parameters_.first[k]), parameters_.active);
    const std::size_t b = drawer.point(second_, static_cast<std::size_t>(parameters_.second[k]), parameters_.active);
    tie(drawer, a, b, built ? this->first_row_ + static_cast<int>(3 * k) : -1);
  }
}

template <class Real>
void SlidingLagrangianConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  const std::size_t p = drawer.point(first_, static_cast<std::size_t>(parameters_.sliding_point));
  const std::size_t a = drawer.point(second_, static_cast<std::size_t>(parameters_.axis_1));
  const std::size_t b = drawer.point(second_, static_cast<std::size_t>(parameters_.axis_2));
  drawer.pair(a, b);
  // Rows of the last build (directions_ on P): collapsed, +e on P and -e on A; otherwise rows 0 and
  // 1 across the axis, -(1 - β) and -β of it on A and B; row 2 -a on A; row 3 +a on B.
  if (this->rows_ != static_cast<int>(directions_.size())) return;
  for (int r = 0; r < this->rows_; ++r) {
    const int row = this->first_row_ + r;
    const Vec3<Real>& d = directions_[static_cast<std::size_t>(r)];
    drawer.force(p, row, d);
    if (collapsed() || r == 2) {
      drawer.force(a, row, -d);
    } else if (r == 3) {
      drawer.force(b, row, -d);
    } else {
      drawer.force(a, row, -(1 - beta_) * d);
      drawer.force(b, row, -beta_ * d);
    }
  }
}

template <class Real>
void RigidFixedLagrangianConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  // Rows of the last build: 6 per rigid, the first 3 the axes on its centre (the torque rows are
  // not drawn).
  const bool built = this->rows_ == static_cast<int>(6 * indices_.size());
  for (std::size_t k = 0; k < indices_.size(); ++k) {
    const std::size_t p = drawer.point(frames_.linear, static_cast<std::size_t>(indices_[k]));
    if (!built) continue;
    for (int a = 0; a < 3; ++a) drawer.force(p, this->first_row_ + static_cast<int>(6 * k) + a, Vec3<Real>::Unit(a));
  }
}

template <class Real>
void RigidBilateralLagrangianConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  const bool built = this->rows_ == static_cast<int>(6 * pairs());
  for (std::size_t k = 0; k < pairs(); ++k) {
    const std::size_t a = drawer.point(first_.linear, static_cast<std::size_t>(parameters_.first[k]));
    const std::size_t b = drawer.point(second_.linear, static_cast<std::size_t>(parameters_.second[k]));
    tie(drawer, a, b, built ? this->first_row_ + static_cast<int>(6 * k) : -1);
  }
}

template <class Real>
void UnilateralLagrangianConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  const int per_contact = rows_per_contact();
  const bool built = this->rows_ == per_contact * static_cast<int>(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const auto& c = contacts_[k];
    const std::size_t q = drawer.point_at(c.first.position);
    const std::size_t p = drawer.point_at(c.second.position);
    drawer.pair(q, p);
    if (!built) continue;
    Vec3<Real> axes[3] = {c.normal, Vec3<Real>::Zero(), Vec3<Real>::Zero()};
    if (per_contact == 3) tangents(c.normal, axes[1], axes[2]);
    for (int a = 0; a < per_contact; ++a) {
      const int row = this->first_row_ + per_contact * static_cast<int>(k) + a;
      drawer.force(q, row, -axes[a]);
      drawer.force(p, row, axes[a]);
    }
  }
}

template <class Real>
void StickContactConstraint<Real>::draw(ConstraintDrawer<Real>& drawer) const {
  const bool built = this->rows_ == 3 * static_cast<int>(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const std::size_t q = drawer.point_at(contacts_[k].first.position);
    const std::size_t p = drawer.point_at(contacts_[k].second.position);
    drawer.pair(q, p);
    if (!built) continue;
    for (int a = 0; a < 3; ++a) {
      const int row = this->first_row_ + 3 * static_cast<int>(k) + a;
      drawer.force(q, row, -Vec3<Real>::Unit(a));
      drawer.force(p, row, Vec3<Real>::Unit(a));
    }
  }
}

template <class Real>
void FreeMotionAnimationLoop<Real>::draw(std::span<const SimulatedObject<Real>> objects, Real dt,
                                         ConstraintDrawing& drawing) const {
  ConstraintDrawer<Real> drawer(objects, constraint_forces(), dt, drawing);
  for (const auto& constraint : constraints) {
    drawer.begin(constraint->where());
    constraint->draw(drawer);
  }
}

template class ConstraintDrawer<float>;
template class ConstraintDrawer<double>;
template void FixedLagrangianConstraint<float>::draw(ConstraintDrawer<float>&) const;
template void FixedLagrangianConstraint<double>::draw(ConstraintDrawer<double>&) const;
template void BilateralLagrangianConstraint<float>::draw(ConstraintDrawer<float>&) const;
template void BilateralLagrangianConstraint<double>::draw(ConstraintDrawer<double>&) const;
template void SlidingLagrangianConstraint<float>::draw(ConstraintDrawer<float>&) const;
template void SlidingLagrangianConstraint<double>::draw(ConstraintDrawer<double>&) const;
template void RigidFixedLagrangianConstraint<float>::draw(ConstraintDrawer<float>&) const;
template void RigidFixedLagrangianConstraint<double>::draw(ConstraintDrawer<double>&) const;
template void RigidBilateralLagrangianConstraint<float>::draw(ConstraintDrawer<float>&) const;
template void RigidBilateralLagrangianConstraint<double>::draw(ConstraintDrawer<double>&) const;
template void UnilateralLagrangianConstraint<double>::draw(ConstraintDrawer<double>&) const;
template void StickContactConstraint<double>::draw(ConstraintDrawer<double>&) const;
template void FreeMotionAnimationLoop<float>::draw(std::span<const SimulatedObject<float>>, float, ConstraintDrawing&) const;
template void FreeMotionAnimationLoop<double>::draw(std::span<const SimulatedObject<double>>, double, ConstraintDrawing&) const;

}  // namespace fastcorot
