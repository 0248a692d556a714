// Where assembled matrices go. A force field adds 3×3 blocks at (block row, block column) of a
// larger system; the sink decides how to store them (Eigen triplets here; a solver's own block
// matrix later). Rows and columns are scalar indices: block (i, j) of a field placed at `offset`
// covers rows offset + 3i .. offset + 3i + 2.
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/SparseCore>

#include <vector>

namespace fastcorot {

template <class Real>
class MatrixSink {
 public:
  virtual ~MatrixSink() = default;
  // Adds `block` to rows row..row+2 and columns col..col+2.
  virtual void add_block(Index row, Index col, const Mat3<Real>& block) = 0;
};

// Collects every entry as an Eigen triplet (duplicates are summed by setFromTriplets).
template <class Real>
class TripletSink final : public MatrixSink<Real> {
 public:
  void add_block(Index row, Index col, const Mat3<Real>& block) override {
    for (Index i = 0; i < 3; ++i) {
      for (Index j = 0; j < 3; ++j) triplets.emplace_back(row + i, col + j, block(i, j));
    }
  }

  // A size×size sparse matrix of the collected entries.
  Eigen::SparseMatrix<Real> to_sparse(Index size) const {
    Eigen::SparseMatrix<Real> matrix(size, size);
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    return matrix;
  }

  std::vector<Eigen::Triplet<Real>> triplets;
};

}  // namespace fastcorot
