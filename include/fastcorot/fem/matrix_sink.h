// Where assembled matrices go. A force field adds 3×3 blocks at (block row, block column) of a
// larger system; the sink decides how to store them (Eigen triplets here; a solver's own block
// matrix later). Rows and columns are scalar indices: block (i, j) of a field placed at `offset`
// covers rows offset + 3i .. offset + 3i + 2.
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/SparseCore>

#include <algorithm>
#include <utility>
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

// Eigen's setFromTriplets with the pattern of the last call remembered: when the triplets come in
// the same sequence of (row, column) as last time (a mesh's matrix step after step), their values
// go straight to their places in the stored matrix, each place taking its first value and adding
// the others in the triplets' order, as setFromTriplets sums duplicates: the same bits, without
// its sorting, transposition and allocations.
template <class Real>
class PatternedAssembly {
 public:
  const Eigen::SparseMatrix<Real>& to_sparse(const std::vector<Eigen::Triplet<Real>>& triplets, Index size) {
    const bool same = matrix_.rows() == size && entries_.size() == triplets.size() &&
                      std::equal(triplets.begin(), triplets.end(), entries_.begin(), [](const auto& t, const auto& e) {
                        return t.row() == e.first && t.col() == e.second;
                      });
    if (!same) {
      learn(triplets, size);
      return matrix_;
    }
    Real* values = matrix_.valuePtr();
    for (std::size_t k = 0; k < triplets.size(); ++k) {
      const Index slot = slot_[k];
      if (slot < 0) {
        values[-1 - slot] = triplets[k].value();
      } else {
        values[slot] += triplets[k].value();
      }
    }
    return matrix_;
  }

 private:
  void learn(const std::vector<Eigen::Triplet<Real>>& triplets, Index size) {
    matrix_.resize(size, size);
    matrix_.setFromTriplets(triplets.begin(), triplets.end());
    matrix_.makeCompressed();
    entries_.resize(triplets.size());
    slot_.resize(triplets.size());
    std::vector<bool> taken(static_cast<std::size_t>(matrix_.nonZeros()), false);
    const auto* outer = matrix_.outerIndexPtr();
    const auto* inner = matrix_.innerIndexPtr();
    for (std::size_t k = 0; k < triplets.size(); ++k) {
      const Index row = triplets[k].row(), col = triplets[k].col();
      entries_[k] = {row, col};
      const auto* at = std::lower_bound(inner + outer[col], inner + outer[col + 1], row);
      const auto slot = static_cast<Index>(at - inner);
      // The first value at a slot is written (-1 - slot), the next ones added.
      slot_[k] = taken[static_cast<std::size_t>(slot)] ? slot : -1 - slot;
      taken[static_cast<std::size_t>(slot)] = true;
    }
  }

  std::vector<std::pair<Index, Index>> entries_;
  std::vector<Index> slot_;
  Eigen::SparseMatrix<Real> matrix_;
};

}  // namespace fastcorot
