// SOFA's PrecomputedLinearSolver: the system matrix of the first solve, A0 (with the projective
// constraints), is inverted once and every solve, that one included, returns x = A0^-1 b; the
// matrix is never assembled again (SOFA turns its linear system's assembly off). SOFA stores the
// dense inverse, computed column by column with a sparse Cholesky factorisation (scaled by the ODE
// solver's position factor and back); here A0 is factorised once (LDL^T) and each solve runs the
// two triangular solves: the same x to round-off, without 9 #V^2 numbers.
#pragma once

#include "fastcorot/sim/linear_solver.h"
#include "fastcorot/sim/sparse_factorisation.h"

#include <Eigen/SparseCore>

namespace fastcorot {

template <class Real>
class PrecomputedLinearSolver final : public LinearSolver<Real> {
 public:
  // Throws fastcorot::Error when A0 cannot be factorised, or when a later system or the vectors do
  // not have A0's size.
  LinearSolveReport solve(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                          std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override;

  // A solve changes nothing it carries: solve_again is a plain solve with A0.
  LinearSolveReport solve_again(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                                std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override {
    return solve(system, factors, rhs, x);
  }
  // A0's factorisation, once the first solve made it (W through it: constraint corrections).
  const SparseFactorisation<Real>* factorisation() const override { return initial_.size() > 0 ? &factorisation_ : nullptr; }

  // A0 (empty before the first solve): a resumed run factorises it again.
  const Eigen::SparseMatrix<Real>& initial_matrix() const { return initial_; }
  std::vector<std::int64_t> carried_state() const override;
  void check_carried_state(const std::vector<std::int64_t>& state) const override;
  void restore_carried_state(const std::vector<std::int64_t>& state) override;

 private:
  Eigen::SparseMatrix<Real> initial_;
  SparseFactorisation<Real> factorisation_;
};

}  // namespace fastcorot
