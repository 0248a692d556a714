// SparseFactorisation<Real>: the LDL^T factorisation of an assembled system matrix (Eigen's
// SimplicialLDLT, AMD ordering) that keeps its symbolic analysis (ordering, elimination tree) while
// the sparsity pattern stays the same, which it does from step to step unless the topology or the
// fixed points change. Used by the sparse direct solver and by the preconditioned CG's direct
// preconditioner.
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/SparseCholesky>

#include <vector>

namespace fastcorot {

template <class Real>
class SparseFactorisation {
 public:
  using Matrix = Eigen::SparseMatrix<Real>;

  // Factorises `matrix` (compressed), analysing its pattern first when it differs from the last
  // one. Returns false when the factorisation fails (a zero pivot: a singular matrix).
  bool factorise(const Matrix& matrix);

  // x = A^-1 b for the last factorised A; b and x hold `size` values each (they may not overlap).
  void solve(const Real* b, Real* x, Index size) const;

  // Cᵀ A⁻¹ C for the last factorised A and sparse columns C (A's size × r), dense r × r: with A
  // = Pᵀ L D Lᵀ P, Z = L⁻¹ P C by sparse triangular solves (each column touches only the
  // elimination-tree paths from its nonzeros to the root), then Zᵀ D⁻¹ Z on those paths. What
  // constraint corrections need for H A⁻¹ Hᵀ (C = Hᵀ). Columns on up to `threads` threads, the
  // same bits for any count.
  Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> compliance(const Matrix& columns, int threads = 1) const;

 private:
  Eigen::SimplicialLDLT<Matrix> ldlt_;
  std::vector<typename Matrix::StorageIndex> analysed_outer_, analysed_inner_;
};

}  // namespace fastcorot
