// Matrix-free conjugate gradient with SOFA's CGLinearSolver stopping rules (docs/sofa-solvers.md §2):
// start from x = 0; at each iteration stop when |r| / |b| <= tolerance, or when the curvature
// |p^T A p| <= threshold (an absolute test) or is zero, or after `iterations` products. As in SOFA,
// the very first solve of a solver instance does not stop at its first iteration.
#pragma once

#include "fastcorot/sim/linear_solver.h"

#include <vector>

namespace fastcorot {

template <class Real>
class ConjugateGradientSolver final : public LinearSolver<Real> {
 public:
  struct Parameters {
    int iterations = 25;
    Real tolerance = Real(1e-5);
    Real threshold = Real(1e-5);
  };

  // Throws fastcorot::Error for iterations < 1 or a negative or non-finite tolerance or threshold.
  explicit ConjugateGradientSolver(Parameters parameters);
  ConjugateGradientSolver() : ConjugateGradientSolver(Parameters{}) {}

  LinearSolveReport solve(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                          std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override;

  const Parameters& parameters() const { return parameters_; }

  // The number of solves done: the first solve behaves differently (see above).
  std::vector<std::int64_t> carried_state() const override { return {solves_}; }
  void restore_carried_state(const std::vector<std::int64_t>& state) override;

 private:
  Parameters parameters_;
  std::int64_t solves_ = 0;
  std::vector<Vec3<Real>> r_, p_, q_;  // work vectors, kept to avoid allocating per solve
};

}  // namespace fastcorot
