// Time integrators (SOFA's ODE solvers) acting on a MechanicalSystem with a LinearSolver, with the
// numerics written out in docs/sofa-solvers.md:
// - ImplicitEulerSolver: SOFA's EulerImplicitSolver (backward Euler with Rayleigh damping),
// - StaticSolver: SOFA's StaticSolver driving a NewtonRaphsonSolver (with line search), or the older
//   self-contained Newton loop of StaticSolver.
#pragma once

#include "fastcorot/sim/linear_solver.h"
#include "fastcorot/sim/mechanical_system.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace fastcorot {

// What one time step did.
struct StepReport {
  int linear_solves = 0;
  int linear_iterations = 0;  // summed over the solves
};

// How a solver's last step turns a velocity change into motion, for constraint corrections (SOFA's
// getPositionIntegrationFactor and getVelocityIntegrationFactor): an impulse p changes the
// velocities by A⁻¹ p and the positions by `position` A⁻¹ p, A the matrix m M + b B + k K of
// `matrix`'s factors as the step posed it.
template <class Real>
struct IntegrationFactors {
  Real position = 0;
  Real velocity = 1;
  MatrixFactors<Real> matrix;
};

template <class Real>
class OdeSolver {
 public:
  virtual ~OdeSolver() = default;
  // Advances `system` by dt in place.
  virtual StepReport step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) = 0;

  // The factors of the last step (before the first: those a step of dt would use); nullopt for a
  // solver whose steps constraint corrections cannot follow (they refuse it).
  virtual std::optional<IntegrationFactors<Real>> integration_factors(Real dt) const {
    static_cast<void>(dt);
    return std::nullopt;
  }

  // What the solver carries from one step to the next that changes later results, as integers
  // (see LinearSolver::carried_state). Neither solver here carries any: their work vectors are
  // overwritten by every step, and StaticSolver::converged() only reports on the last step.
  virtual std::vector<std::int64_t> carried_state() const { return {}; }
  virtual void restore_carried_state(const std::vector<std::int64_t>& state) {
    if (!state.empty())
      throw make_error("this ODE solver carries no state; got ", state.size(), " values");
  }
};

template <class Real>
class ImplicitEulerSolver final : public OdeSolver<Real> {
 public:
  struct Parameters {
    Real rayleigh_stiffness = 0;
    Real rayleigh_mass = 0;
    Real velocity_damping = 0;  // SOFA's vdamping: v *= exp(-dt · vdamping) after the step
    bool first_order = false;
    bool trapezoidal = false;
  };

  // Throws fastcorot::Error for negative or non-finite coefficients.
  explicit ImplicitEulerSolver(Parameters parameters);

  // f = f(x, v); b = P h (f + (h tr + rs) K v - rm M v); A = (1 + tr h rm) M - tr h B
  // - tr h (tr h + rs) K; A dv = b; v += dv; x += h v. (first_order: b = P f,
  // A = M - tr h K, v = dv.)
  StepReport step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) override;

  // position h, velocity 1 (SOFA's EulerImplicitSolver), matrix as above.
  std::optional<IntegrationFactors<Real>> integration_factors(Real dt) const override;

 private:
  Parameters parameters_;
  std::vector<Vec3<Real>> force_, rhs_, dv_;
};

template <class Real>
class StaticSolver final : public OdeSolver<Real> {
 public:
  // SOFA's NewtonRaphsonSolver (the current StaticSolver form). Thresholds <= 0 disable a test.
  struct NewtonParameters {
    int max_iterations = 1;
    int max_line_search_iterations = 5;
    Real line_search_coefficient = Real(0.5);
    Real relative_successive_threshold = Real(1e-5);
    Real relative_initial_threshold = Real(1e-5);
    Real absolute_residual_threshold = Real(1e-5);
    Real relative_estimate_difference_threshold = 0;
    Real absolute_estimate_difference_threshold = 0;
  };
  // The older StaticSolver-only Newton loop (attributes newton_iterations, ...).
  struct LegacyParameters {
    int newton_iterations = 1;
    Real absolute_correction_threshold = Real(1e-5);
    Real relative_correction_threshold = Real(1e-5);
    Real absolute_residual_threshold = Real(1e-5);
    Real relative_residual_threshold = Real(1e-5);
    // should_diverge_when_residual_is_growing only sets a status flag in SOFA; accepted, no effect.
    bool diverge_when_residual_grows = false;
  };

  explicit StaticSolver(NewtonParameters parameters);
  explicit StaticSolver(LegacyParameters parameters);

  // Newton iterations on P f(x) = 0 with (-K) dx = P f; velocities are untouched.
  StepReport step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) override;

  // Whether the last step met a convergence test (false after running out of iterations).
  bool converged() const { return converged_; }

 private:
  StepReport newton_step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver);
  StepReport legacy_step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver);
  Real projected_residual(MechanicalSystem<Real>& system);  // |P f(x)|², leaves P f in force_

  bool legacy_ = false;
  NewtonParameters newton_;
  LegacyParameters legacy_parameters_;
  bool converged_ = false;
  std::vector<Vec3<Real>> force_, dx_;
};

}  // namespace fastcorot
