// Linear solvers for the systems (m M + b B + k K) x = rhs that ODE solvers pose on a
// MechanicalSystem. Iterative solvers use the matrix-free product; direct ones assemble.
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/sim/mechanical_system.h"
#include "fastcorot/sim/sparse_factorisation.h"

#include <cstdint>
#include <span>
#include <vector>

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

  // Solves A x = rhs for another right-hand side with the matrix of the last solve() (constraint
  // corrections ask for several per step), leaving what the solver carries to its next solve()
  // as it was (warm starts, counters); by default a new solve() between saving and restoring it.
  virtual LinearSolveReport solve_again(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                                        std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) {
    const std::vector<std::int64_t> carried = carried_state();
    const LinearSolveReport report = solve(system, factors, rhs, x);
    restore_carried_state(carried);
    return report;
  }
  // The factorisation of the last solve() for direct solvers (null for the others): constraint
  // corrections compute H A⁻¹ Hᵀ with sparse triangular solves on it.
  virtual const SparseFactorisation<Real>* factorisation() const { return nullptr; }

  // What the solver carries from one solve to the next that changes later results, as integers
  // (empty when nothing): checkpoints save it so that a resumed run continues bitwise. Work
  // vectors overwritten by every solve and caches that do not change results are not part of it.
  virtual std::vector<std::int64_t> carried_state() const { return {}; }
  // Restores what carried_state() returned; throws fastcorot::Error when it does not fit.
  virtual void restore_carried_state(const std::vector<std::int64_t>& state) {
    if (!state.empty())
      throw make_error("this linear solver carries no state; got ", state.size(), " values");
  }
  // Throws fastcorot::Error, saying what does not fit, where restore_carried_state(state) would for
  // its shape; changes nothing (checkpoints check every object before restoring any). By default
  // the state must have the length carried_state() has now.
  virtual void check_carried_state(const std::vector<std::int64_t>& state) const {
    const std::size_t expected = carried_state().size();
    if (state.size() != expected) throw make_error("expected ", expected, " values, got ", state.size());
  }
};

}  // namespace fastcorot
