// ConstraintDrawer<Real>: what a Lagrangian constraint uses to say what it shows
// (LagrangianConstraint::draw, filling sim/constraint_stage.h's ConstraintDrawing). A constraint
// adds the points it acts on, writes each of its rows' coefficients on them again (as in build), and
// the drawer turns those into forces with the last step's impulses: f += c λ_row / dt. Points are
// placed where the objects stand now (mapped points through their mapping). Design:
// docs/constraints.md ("Seeing it"), docs/rendering.md.
#pragma once

#include "fastcorot/constraint/constraint_points.h"
#include "fastcorot/sim/constraint_stage.h"

#include <map>
#include <span>
#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
class ConstraintDrawer {
 public:
  // `impulses`: the last step's λ, one per row (empty before the first step); `dt` the step.
  ConstraintDrawer(std::span<const SimulatedObject<Real>> objects, std::span<const Real> impulses, Real dt,
                   ConstraintDrawing& drawing);
  // Starts the next constraint (`where` names it); the points added until the next call are its.
  void begin(const std::string& where);
  // Adds point i of `points` where it is now; returns its index in the drawing.
  std::size_t point(const ConstraintPoints<Real>& points, std::size_t i, bool active = true);
  // Adds a point at `position` (one the constraint placed itself, as a contact's).
  std::size_t point_at(const Vec3<Real>& position, bool active = true);
  // Drawn point p gets row `row`'s force, c λ_row / dt (nothing for a row the last step did not have).
  void force(std::size_t p, int row, const Vec3<Real>& c);
  // Drawn points a and b are tied (a segment joins them).
  void pair(std::size_t a, std::size_t b) { drawing_.pairs.push_back({a, b}); }

 private:
  std::span<const SimulatedObject<Real>> objects_;
  std::span<const Real> impulses_;
  Real dt_;
  ConstraintDrawing& drawing_;
  std::map<const ConstraintPoints<Real>*, std::vector<Vec3<Real>>> mapped_;  // each mapped set's points now
};

}  // namespace fastcorot
