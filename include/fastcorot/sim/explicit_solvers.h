// Explicit time integrators (SOFA's ODESolver/Forward): EulerExplicitSolver (symplectic or not)
// and RungeKutta4Solver, on a MechanicalSystem. The acceleration is a = M^-1 P f: a division per
// point for a lumped mass, a solve of M a = P f with the object's linear solver for a consistent
// one (SOFA's MeshMatrixMass without lumping), as SOFA does.
#pragma once

#include "fastcorot/sim/ode_solver.h"

#include <vector>

namespace fastcorot {

template <class Real>
class ExplicitEulerSolver final : public OdeSolver<Real> {
 public:
  // symplectic (SOFA's default): v += h a, then x += h v; otherwise x += h v, then v += h a.
  explicit ExplicitEulerSolver(bool symplectic) : symplectic_(symplectic) {}
  StepReport step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) override;

 private:
  bool symplectic_;
  std::vector<Vec3<Real>> force_, acceleration_;
};

template <class Real>
class RungeKutta4Solver final : public OdeSolver<Real> {
 public:
  // The classical fourth-order Runge-Kutta scheme on (x, v): four accelerations at t, t + h/2
  // (twice) and t + h, combined with weights 1/6, 1/3, 1/3, 1/6 (SOFA's RungeKutta4Solver).
  StepReport step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) override;

 private:
  std::vector<Vec3<Real>> force_, x0_, v0_, xs_;
  std::vector<Vec3<Real>> k_velocity_[4], k_acceleration_[4];
};

// a = M^-1 P f(x, v) (what SOFA's computeAcc does; v empty: the state's velocities); returns the
// linear solves' report (none for a lumped mass). Throws fastcorot::Error when the system has no
// mass. `force` is a work vector.
template <class Real>
StepReport explicit_acceleration(MechanicalSystem<Real>& system, LinearSolver<Real>& solver,
                                 std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v,
                                 std::vector<Vec3<Real>>& force, std::span<Vec3<Real>> acceleration);

}  // namespace fastcorot
