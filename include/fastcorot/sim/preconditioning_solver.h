// PreconditioningSolver<Real>: a preconditioner that is, as in SOFA, a linear solver on a matrix of
// its own, which PreconditionedConjugateGradientSolver (Preconditioner::solver) builds at its first
// solve and every update_step solves after (SOFA's assemblingRate of the PCG's linear system), and
// applies as z = P r once per iteration: SSORPreconditioner, WarpPreconditioner
// (ssor_preconditioner.h, warp_preconditioner.h).
#pragma once

#include "fastcorot/sim/mechanical_system.h"

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace fastcorot {

template <class Real>
class PreconditioningSolver {
 public:
  virtual ~PreconditioningSolver() = default;
  // The SOFA component it reproduces (for messages).
  virtual std::string_view component() const = 0;
  // (Re)builds P from the system matrix m M + b B + k K of this solve (with the projective
  // constraints). Throws fastcorot::Error, naming the component, when it cannot.
  virtual void build(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors) = 0;
  // z = P r over `size` coordinates (3 #V, the size of the last build); r and z do not overlap.
  virtual void apply(const Real* r, Real* z, Index size) const = 0;

  // What P carries from one build to the next and between builds, as integers (checkpoints), and
  // the check and restore of it, as LinearSolver's carried state.
  virtual std::vector<std::int64_t> carried_state() const = 0;
  virtual void check_carried_state(std::span<const std::int64_t> state) const = 0;
  virtual void restore_carried_state(std::span<const std::int64_t> state) = 0;
};

}  // namespace fastcorot
