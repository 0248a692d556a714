// FreeMotionAnimationLoop<Real>: SOFA's FreeMotionAnimationLoop after the free motion
// (FreeMotionAnimationLoop.cpp, GenericConstraintSolver.cpp): the constraints' rows H at the step's
// start, their violations on the free motion, W = Σ corrections' compliance, the constraint
// solver, then each object corrected by its corrections. The free velocities are first projected
// (SOFA's projectResponse(v_free): points a movement holds have none) and the free positions are
// SOFA's x_free = x + dt v_free. Objects that no row reaches keep that free motion, so a scene
// without constraints runs as under the default loop, except that a velocity damping then acts on
// the positions one step later and a projection applied twice (planes, lines) may differ in the
// last bits, as in SOFA. In velocity order every object ends at x = x_start + dt v, SOFA's rule for
// all states.
// Design: docs/constraints.md.
#pragma once

#include "fastcorot/constraint/constraint_corrections.h"
#include "fastcorot/constraint/constraint_problem.h"
#include "fastcorot/constraint/constraint_solvers.h"
#include "fastcorot/constraint/lagrangian_constraints.h"
#include "fastcorot/sim/constraint_stage.h"

#include <memory>
#include <vector>

namespace fastcorot {

template <class Real>
class FreeMotionAnimationLoop final : public ConstraintStage<Real> {
 public:
  struct Parameters {
    bool solve_velocity_constraint_first = false;  // SOFA's ConstraintOrder VEL
  };
  FreeMotionAnimationLoop(Parameters parameters, std::unique_ptr<ConstraintSolver<Real>> solver);

  // In row order (SOFA's scene-graph order).
  std::vector<std::shared_ptr<LagrangianConstraint<Real>>> constraints;
  std::vector<std::unique_ptr<ConstraintCorrection<Real>>> corrections;
  // Objects that rows may touch with no correction of theirs (contacts with a body that has none,
  // warned when the scene is built): as in SOFA, W lacks their compliance and nothing corrects them.
  // Rows on any other uncorrected object are an error.
  std::vector<std::size_t> uncorrected;

  ConstraintReport correct(std::span<SimulatedObject<Real>> objects, std::span<const MechanicalState<Real>> start, Real dt,
                           double time) override;

  std::span<const Real> constraint_forces() const override { return {forces_.data(), static_cast<std::size_t>(forces_.size())}; }
  const char* solver_name() const override { return solver_->name(); }
  // Each constraint's draw, in row order, with the last step's impulses (constraint_drawing.cpp).
  void draw(std::span<const SimulatedObject<Real>> objects, Real dt, ConstraintDrawing& drawing) const override;
  const ConstraintSolver<Real>& solver() const { return *solver_; }
  ConstraintOrder order() const {
    return parameters_.solve_velocity_constraint_first ? ConstraintOrder::velocity : ConstraintOrder::position_and_velocity;
  }
  // The problem of the last step (W, δ_free, λ), for tests and diagnostics.
  const ConstraintProblem<Real>& problem() const { return problem_; }

 private:
  Parameters parameters_;
  std::unique_ptr<ConstraintSolver<Real>> solver_;
  ConstraintProblem<Real> problem_;
  DenseVector<Real> forces_;
};

// P, the projection SOFA's projective constraints apply to a vector of `system` (zero on fixed,
// isolated and moving points, the partial projectors elsewhere), as a sparse 3n × 3n matrix: the
// columns of Hᵀ are projected by it (SOFA's MechanicalProjectJacobianMatrixVisitor). Throws
// fastcorot::Error for pair couplings (AttachProjectiveConstraint), which are not a per-point projection.
template <class Real>
Eigen::SparseMatrix<Real> projection_matrix(const MechanicalSystem<Real>& system);

}  // namespace fastcorot
