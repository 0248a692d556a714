// ConstraintStage<Real>: what SOFA's FreeMotionAnimationLoop adds to a time step. Each object first
// takes its free motion (its ODE solver's step, unconstrained); then the stage builds the
// Lagrangian constraints' problem on those free positions, solves it and corrects the positions and
// velocities of the objects it involves. The stage itself lives in the constraint layer
// (include/fastcorot/constraint/, design: docs/constraints.md); Simulation only calls it.
#pragma once

#include "fastcorot/sim/mechanical_state.h"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace fastcorot {

template <class Real>
struct SimulatedObject;

// What the constraint part of one step did, for summaries and --json.
struct ConstraintReport {
  int rows = 0;              // constraint rows (the size of the problem)
  int iterations = 0;        // of the constraint solver
  double error = 0;          // its final error, in its own measure
  double tolerance = 0;      // what it had to reach (scaled by the row count where SOFA scales it)
  bool converged = true;
  double compliance_seconds = 0;  // building W = H A⁻¹ Hᵀ
  double solve_seconds = 0;       // the constraint solver
};

// What the constraints show in pictures and the viewer (SOFA draws its Lagrangian constraints under
// VisualStyle's showInteractionForceFields): the points they act on, where those are now, and the
// force each constraint applies there, Σ over its rows of coefficient × λ_row / dt (H's row written
// on the point, so mapped points get their force before Jᵀ carries it down); pairs a constraint ties
// (bilateral) are joined. Filled by ConstraintStage::draw, each constraint through its own draw.
struct ConstraintDrawing {
  struct Point {
    Vec3<double> position = Vec3<double>::Zero();  // world, as the objects stand now
    Vec3<double> force = Vec3<double>::Zero();     // zero before the first step or while inactive
    std::size_t constraint = 0;                    // index into `constraints`
    bool active = true;                            // false: an inactive constraint (SOFA: green)
  };
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 2>> pairs;  // indices into points
  std::vector<std::string> constraints;           // each constraint's where(), in row order
};

template <class Real>
class ConstraintStage {
 public:
  virtual ~ConstraintStage() = default;
  // After every object's free motion: `objects` hold the free positions and velocities (a rigid's
  // free rotation still in its angular block), `start` what each held when the step began (the
  // same order). Corrects them in place. `time` is the step's start time. Throws
  // fastcorot::Error for what cannot be solved (naming it).
  virtual ConstraintReport correct(std::span<SimulatedObject<Real>> objects, std::span<const MechanicalState<Real>> start,
                                   Real dt, double time) = 0;
  // The last step's impulses λ, one per row (SOFA's constraintForces: force × dt).
  virtual std::span<const Real> constraint_forces() const = 0;
  // Appends what the constraints show, from the objects as they stand now and the last step's
  // impulses over `dt` (the step they were computed with). Nothing by default.
  virtual void draw(std::span<const SimulatedObject<Real>> objects, Real dt, ConstraintDrawing& drawing) const {
    (void)objects;
    (void)dt;
    (void)drawing;
  }
  // The constraint solver's name, for messages.
  virtual const char* solver_name() const = 0;
};

}  // namespace fastcorot
