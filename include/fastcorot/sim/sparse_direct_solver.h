// Sparse direct solve of the assembled system (SOFA's EigenSimplicialLDLT, SparseLDLSolver and
// SparseCholeskySolver): LDL^T factorisation with Eigen's SimplicialLDLT. The symbolic analysis
// (fill-reducing ordering, elimination tree) is reused while the sparsity pattern is unchanged.
#pragma once

#include "fastcorot/sim/linear_solver.h"
#include "fastcorot/sim/sparse_factorisation.h"

namespace fastcorot {

template <class Real>
class SparseDirectSolver final : public LinearSolver<Real> {
 public:
  // Throws fastcorot::Error when the matrix is singular or not positive definite enough to factor.
  LinearSolveReport solve(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                          std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override;
  // With the factorisation of the last solve (no assembly).
  LinearSolveReport solve_again(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                                std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override;
  const SparseFactorisation<Real>* factorisation() const override { return factored_ ? &factorisation_ : nullptr; }

 private:
  SparseFactorisation<Real> factorisation_;
  bool factored_ = false;
};

}  // namespace fastcorot
