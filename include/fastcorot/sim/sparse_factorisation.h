// SparseFactorisation<Real>: the LDLᵀ factorisation of an assembled system matrix (BlockLDLT: 3×3
// blocks, AMD ordering of the points) that keeps its symbolic analysis (ordering, elimination tree)
// while the sparsity pattern stays the same, which it does from step to step unless the topology or
// the fixed points change. Used by the sparse direct solver, the preconditioned CG's direct
// preconditioner and the constraint corrections.
#pragma once

#include "fastcorot/core/types.h"

#include "fastcorot/sim/block_ldlt.h"

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

  // Cᵀ A⁻¹ C for the last factorised A and sparse columns C (A's size × r), dense r × r, by
  // sparse triangular solves on the elimination-tree paths of C's nonzeros (BlockLDLT::compliance):
  // what constraint corrections need for H A⁻¹ Hᵀ (C = Hᵀ). Columns on up to `threads` threads,
  // the same bits for any count.
  Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> compliance(const Matrix& columns, int threads = 1) const;

 private:
  BlockLDLT<Real> ldlt_;
  std::vector<typename Matrix::StorageIndex> analysed_outer_, analysed_inner_;
};

}  // namespace fastcorot
