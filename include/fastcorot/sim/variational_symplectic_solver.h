// VariationalSymplecticSolver<Real>: SOFA's VariationalSymplecticSolver, a variational midpoint
// integrator on positions and momenta p (carried between steps; p = M v at the first step).
// Implicit form, Newton iterations on the position increment r (from r = 0, at most `steps`,
// while |r_i - r_{i-1}| / |x_k| > newtonError, at least one):
//   [(4/h^2 + 4 rM/h) M - (1 + 4 rK/h) K] r_i = P (f(x_k + r_{i-1}) - K r_{i-1} + (2/h) p),
// K and f at x_k + r_{i-1}; then v = (2/h) r, p' = (h/2) P f(x_k + r) + M v, x = x_k + h v.
// Explicit form (explicitIntegration): a = P [M^-1 (f + p/h) - rM v], v = h a, x += h v, p' = M v.
#pragma once

#include "fastcorot/sim/ode_solver.h"

#include <vector>

namespace fastcorot {

template <class Real>
class VariationalSymplecticSolver final : public OdeSolver<Real> {
 public:
  struct Parameters {
    Real newton_error = Real(0.01);
    int newton_steps = 5;
    Real rayleigh_stiffness = 0;
    Real rayleigh_mass = 0;
    bool explicit_integration = false;
  };
  // For a system of `points` points. Throws fastcorot::Error for negative or non-finite values.
  VariationalSymplecticSolver(Parameters parameters, Index points);
  StepReport step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) override;

  // The momentum p (a flag saying whether it is set, then the bits of its values).
  std::vector<std::int64_t> carried_state() const override;
  void restore_carried_state(const std::vector<std::int64_t>& state) override;

 private:
  Parameters parameters_;
  bool started_ = false;
  std::vector<Vec3<Real>> momentum_, force_, rhs_, increment_, previous_, start_;
};

}  // namespace fastcorot
