// SOFA's Lagrangian constraints (Sofa/Component/Constraint/Lagrangian/Model): each writes its rows
// of H on its points, their violations on the free motion, and one resolution per block of rows.
// Rows are numbered in the order the constraints are built, SOFA's scene-graph order.
// Design: docs/constraints.md.
#pragma once

#include "fastcorot/constraint/constraint_points.h"
#include "fastcorot/constraint/constraint_problem.h"

#include <span>
#include <string>
#include <vector>

namespace fastcorot {

// How the violations are measured (SOFA's ConstraintOrder): positions after the free motion
// (POS_AND_VEL, the default), or velocities (VEL, FreeMotionAnimationLoop's
// solveVelocityConstraintFirst).
enum class ConstraintOrder { position_and_velocity, velocity };

template <class Real>
class ConstraintDrawer;  // constraint_drawing.h
template <class Real>
struct SimulatedObject;  // sim/simulation.h

template <class Real>
class LagrangianConstraint {
 public:
  explicit LagrangianConstraint(std::string where) : where_(std::move(where)) {}
  virtual ~LagrangianConstraint() = default;
  // The component, for messages ("scene.scn:12: BilateralLagrangianConstraint").
  const std::string& where() const { return where_; }
  // The point sets it reads, for the loop to prepare each step.
  virtual std::vector<ConstraintPoints<Real>*> point_sets() = 0;
  // Before its rows are built, after the free motion (the objects hold their free states): what it
  // reads besides its point sets. Nothing by default.
  virtual void prepare(std::span<const SimulatedObject<Real>> objects, Real dt) { static_cast<void>(objects), static_cast<void>(dt); }
  // Appends its rows (none when inactive) and remembers where they start.
  virtual void build(ConstraintRows<Real>& rows) = 0;
  // Its rows' violations, into dfree (indexed by row).
  virtual void violation(ConstraintOrder order, Real dt, Real* dfree) const = 0;
  // Appends the resolutions of its blocks, in row order.
  virtual void add_resolutions(ConstraintProblem<Real>& problem) = 0;
  // Adds what it shows (its points, their forces from its rows, tied pairs) for pictures and the
  // viewer (constraint_drawing.h); nothing by default.
  virtual void draw(ConstraintDrawer<Real>& drawer) const { (void)drawer; }
  // Data scripts read, and some write, between steps (SofaPython3 controllers), by SOFA's names,
  // as numbers: none by default. read_live and write_live throw fastcorot::Error for a name not
  // listed, a datum that is only read, or values the constraint refuses (nothing changed then).
  virtual std::vector<std::string> live_data() const { return {}; }
  virtual std::vector<double> read_live(const std::string& name) const;
  virtual void write_live(const std::string& name, std::span<const double> values);
  // Its rows [first_row(), first_row() + rows()) in the last build.
  int first_row() const { return first_row_; }
  int rows() const { return rows_; }

 protected:
  int first_row_ = 0;
  int rows_ = 0;

 private:
  std::string where_;
};

// SOFA's FixedLagrangianConstraint<Vec3>: three rows (the axes) per point, δ = x_free - x_rest, each
// point's block a BilateralResolution3 warm-started from its last impulse.
template <class Real>
class FixedLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  // `indices` into `points` (checked: throws fastcorot::Error naming one out of range).
  FixedLagrangianConstraint(std::string where, ConstraintPoints<Real> points, std::vector<Index> indices);
  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&points_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  void draw(ConstraintDrawer<Real>& drawer) const override;  // constraint_drawing.cpp
  const std::vector<Index>& indices() const { return indices_; }
  const ConstraintPoints<Real>& points() const { return points_; }

 private:
  ConstraintPoints<Real> points_;
  std::vector<Index> indices_;
  std::vector<Vec3<Real>> previous_;
};

// SOFA's BilateralLagrangianConstraint<Vec3>: point first[k] of object 1 and point second[k] of
// object 2 held at x2 - x1 = rest[k] (zero when rest is shorter): three rows per pair, -I on the
// first point and +I on the second; violation x2_free - x1_free - rest (velocity order: the
// velocities' difference plus the gap over dt); each pair a BilateralResolution3 scaled by `load`
// and warm-started. Inactive: no rows.
template <class Real>
class BilateralLagrangianConstraint final : public LagrangianConstraint<Real> {
 public:
  struct Parameters {
    std::vector<Index> first, second;  // as many pairs as the shorter list
    std::vector<Vec3<Real>> rest;
    bool active = true;
    Real load = 1;  // in [0, 1]
  };
  // Throws fastcorot::Error naming an index out of range or a load outside [0, 1].
  BilateralLagrangianConstraint(std::string where, ConstraintPoints<Real> first, ConstraintPoints<Real> second,
                                Parameters parameters);
  std::vector<ConstraintPoints<Real>*> point_sets() override { return {&first_, &second_}; }
  void build(ConstraintRows<Real>& rows) override;
  void violation(ConstraintOrder order, Real dt, Real* dfree) const override;
  void add_resolutions(ConstraintProblem<Real>& problem) override;
  void draw(ConstraintDrawer<Real>& drawer) const override;  // constraint_drawing.cpp
  // Scripts change these between steps (SofaPython3 controllers).
  Parameters& parameters() { return parameters_; }
  const ConstraintPoints<Real>& first() const { return first_; }
  const ConstraintPoints<Real>& second() const { return second_; }
  std::size_t pairs() const { return std::min(parameters_.first.size(), parameters_.second.size()); }

 private:
  ConstraintPoints<Real> first_, second_;
  Parameters parameters_;
  std::vector<Vec3<Real>> previous_;
};

}  // namespace fastcorot
