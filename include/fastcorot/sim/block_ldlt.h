// BlockLDLT<Real>: the LDLᵀ factorisation of a symmetric matrix made of 3×3 blocks, one block per
// pair of points (the system matrix of a Vec3 state). A = Pᵀ L D Lᵀ P where P orders the points
// (approximate minimum degree on the points' graph), L is unit lower triangular in 3×3 blocks and D
// is block diagonal with symmetric 3×3 blocks. The same arithmetic as a scalar LDLᵀ on the same
// order (each D block is itself factorised without pivoting), but one index per nine values and
// fixed-size 3×3 products: several times faster than a scalar simplicial factorisation for FEM
// matrices. The scalar LDLᵀ (Eigen's SimplicialLDLT) stays beside it in the tests as reference.
//
// Reads the lower triangle of A (as Eigen's SimplicialLDLT does); entries of a nonzero block that
// the pattern leaves out count as zeros.
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/Sparse>

#include <cstdint>
#include <vector>

namespace fastcorot {

template <class Real>
class BlockLDLT {
 public:
  using Matrix = Eigen::SparseMatrix<Real>;
  using DenseMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;

  // The symbolic phase for `matrix`'s pattern (compressed, square, 3k × 3k): the points' order,
  // the elimination tree, L's block pattern, and where each stored entry of A goes.
  void analyse(const Matrix& matrix);

  // The numeric phase for a matrix with the analysed pattern. Returns false when a pivot is zero
  // or not finite (a singular matrix, or one LDLᵀ cannot factorise without pivoting); throws
  // fastcorot::Error naming the value when an entry is not finite, or when the matrix is not of
  // the analysed size and entry count.
  bool factorise(const Matrix& matrix);

  // x = A⁻¹ b for the last factorised A; b and x hold size() values each (they may not overlap).
  void solve(const Real* b, Real* x) const;

  // Cᵀ A⁻¹ C for sparse columns C (size() × r), dense r × r: Z = L⁻¹ P C by sparse block
  // triangular solves (each column touches only the elimination-tree paths from its nonzero
  // points to the root), then Zᵀ D⁻¹ Z on those points. Columns on up to `threads` threads, the
  // same bits for any count.
  DenseMatrix compliance(const Matrix& columns, int threads = 1) const;

  Index size() const { return 3 * points_; }
  // Blocks of L below the diagonal (for reports and tests).
  Index factor_blocks() const { return static_cast<Index>(l_rows_.size()); }

 private:
  Index points_ = 0;
  std::vector<Index> order_;    // order_[point] = its position in the elimination order
  std::vector<Index> parent_;   // elimination tree over positions (-1 at a root)
  // A's upper block triangle in elimination order, column by column: rows ≤ column, 9 values per
  // block (column-major), filled from A's stored entries through the scatter map.
  std::vector<Index> a_start_, a_rows_;
  std::vector<Real> a_values_;
  std::vector<std::int64_t> scatter_from_, scatter_to_;
  std::size_t stored_entries_ = 0;  // A's stored entries when analysed
  // L's blocks below the diagonal, column by column (rows ascending), 9 values each.
  std::vector<Index> l_start_, l_rows_;
  std::vector<Real> l_values_;
  // Per position: D's block inverse (9 values) and its own factorisation D = U diag(d) Uᵀ with U
  // unit lower: the pivots d (3) and U⁻¹'s strictly lower entries (3: rows 1,2,2 by columns 0,0,1).
  std::vector<Real> d_inverse_, pivots_, u_inverse_;
};

}  // namespace fastcorot
