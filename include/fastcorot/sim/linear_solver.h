// Linear solvers for the systems (m M + b B + k K) x = rhs that ODE solvers pose on a
// MechanicalSystem. Iterative solvers use the matrix-free product; direct ones assemble.
#pragma once

#include "fastcorot/sim/mechanical_system.h"

#include <span>

namespace fastcorot {

// What one solve did: iterations (0 for direct solvers) and the final relative residual
// |rhs - A x| / |rhs| where the solver measures it (0 otherwise).
struct LinearSolveReport {
  int iterations = 0;
  double relative_residual = 0;
};

template <class Real>
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  // Solves A x = rhs with A = factors applied to `system`; x is overwritten.
  virtual LinearSolveReport solve(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                                  std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) = 0;
};

}  // namespace fastcorot
