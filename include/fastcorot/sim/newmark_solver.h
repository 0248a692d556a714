// NewmarkSolver<Real>: SOFA's NewmarkImplicitSolver, the Newmark-beta scheme on accelerations with
// Rayleigh damping, as SOFA writes it. With a_t carried from the previous step (at the first
// step, a_0 = M^-1 P f(x_0, v_0)) and K, f taken at x_t:
//   b = f + [h(1-g) rK + h^2 (1-2 beta)/2] K a_t - h(1-g) rM M a_t      (only when rM, rK != 0 or beta != 1/2)
//         + (rK + h) K v_t - rM M v_t,  projected;
//   [(1 + h g rM) M - (h^2 beta + h g rK) K] a_{t+h} = b;
//   x += h v + h^2 (1/2 - beta) a_t + h^2 beta a_{t+h};  v += h (1-g) a_t + h g a_{t+h};
//   v *= exp(-h vdamping).
#pragma once

#include "fastcorot/sim/ode_solver.h"

#include <vector>

namespace fastcorot {

template <class Real>
class NewmarkSolver final : public OdeSolver<Real> {
 public:
  struct Parameters {
    Real rayleigh_stiffness = 0;
    Real rayleigh_mass = 0;
    Real velocity_damping = 0;
    Real gamma = Real(0.5);
    Real beta = Real(0.25);
  };
  // For a system of `points` points. Throws fastcorot::Error for negative or non-finite coefficients.
  NewmarkSolver(Parameters parameters, Index points);
  StepReport step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) override;

  // a_t, carried between steps: a flag saying whether it is set, then the bits of its 3 #points values.
  std::vector<std::int64_t> carried_state() const override;
  void restore_carried_state(const std::vector<std::int64_t>& state) override;

 private:
  Parameters parameters_;
  bool started_ = false;
  std::vector<Vec3<Real>> acceleration_, next_, rhs_, force_;
};

}  // namespace fastcorot
