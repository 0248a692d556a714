// Matrix-free MINRES as SOFA's MinResLinearSolver computes it (its port of tminres, Villa, Saunders
// and Akle, with no preconditioner; docs/linear-solvers.md, "MinResLinearSolver"): for symmetric
// systems, definite or not. Like PCGLinearSolver it starts from its previous solution x0 (zero
// before the first solve: SOFA's ODE solvers hand it their solution vector, which keeps the last
// step's). With r0 = b - A x0 and beta1 = |r0| (nothing to do when it is zero), each iteration does
// one Lanczos step (one product), the QR update of the tridiagonal matrix by a plane rotation
// (gamma clamped below by the machine epsilon) and x += phi w; it then stops, as SOFA does, after
// the first iteration when beta2 / beta1 < 10 eps, or when one of these holds, with ||A|| the
// Frobenius norm estimate sqrt(sum alpha^2 + beta_k^2 + beta_(k+1)^2), phibar the residual norm
// estimate and ||x|| the norm of the current x:
//   test1 = phibar / (||A|| ||x||) <= 0 or <= tolerance,
//   test2 = sqrt(gbar^2 + dbar^2) / ||A|| <= 0 or <= tolerance,
//   the last of `iterations`, gmax / gmin >= 0.1 / eps (condition estimate), ||A|| eps ||x|| >= beta1.
// There is no `threshold` (SOFA's MinResLinearSolver has none).
#pragma once

#include "fastcorot/sim/linear_solver.h"

#include <vector>

namespace fastcorot {

template <class Real>
class MinResSolver final : public LinearSolver<Real> {
 public:
  struct Parameters {
    int iterations = 25;        // SOFA's default
    Real tolerance = Real(1e-5);  // SOFA's default
  };

  // For systems of `points` points. Throws fastcorot::Error for iterations < 1, a negative or
  // non-finite tolerance, or points < 0.
  MinResSolver(Parameters parameters, Index points);

  // Throws fastcorot::Error when the system or the vectors do not have the solver's point count.
  // The report's relative residual is MINRES's estimate phibar / |b|.
  LinearSolveReport solve(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                          std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override;

  const Parameters& parameters() const { return parameters_; }

  // The previous solution (the next solve's start), as bit patterns.
  std::vector<std::int64_t> carried_state() const override;
  void restore_carried_state(const std::vector<std::int64_t>& state) override;

 private:
  Parameters parameters_;
  std::vector<Vec3<Real>> previous_;
  std::vector<Vec3<Real>> r1_, r2_, y_, w_, w2_, v_;  // work vectors, kept to avoid allocating per solve
};

}  // namespace fastcorot
