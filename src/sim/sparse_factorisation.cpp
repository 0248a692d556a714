#include "fastcorot/sim/sparse_factorisation.h"

#include "fastcorot/core/parallel.h"

#include <algorithm>
#include <vector>

namespace fastcorot {

template <class Real>
bool SparseFactorisation<Real>::factorise(const Matrix& matrix) {
  const auto* outer = matrix.outerIndexPtr();
  const auto* inner = matrix.innerIndexPtr();
  const bool same_pattern = analysed_outer_.size() == static_cast<std::size_t>(matrix.outerSize() + 1) &&
                            analysed_inner_.size() == static_cast<std::size_t>(matrix.nonZeros()) &&
                            std::equal(analysed_outer_.begin(), analysed_outer_.end(), outer) &&
                            std::equal(analysed_inner_.begin(), analysed_inner_.end(), inner);
  if (!same_pattern) {
    ldlt_.analyzePattern(matrix);
    analysed_outer_.assign(outer, outer + matrix.outerSize() + 1);
    analysed_inner_.assign(inner, inner + matrix.nonZeros());
  }
  ldlt_.factorize(matrix);
  return ldlt_.info() == Eigen::Success;
}

template <class Real>
void SparseFactorisation<Real>::solve(const Real* b, Real* x, Index size) const {
  const Eigen::Map<const Eigen::Matrix<Real, Eigen::Dynamic, 1>> rhs(b, size);
  Eigen::Map<Eigen::Matrix<Real, Eigen::Dynamic, 1>> solution(x, size);
  solution = ldlt_.solve(rhs);
}

template <class Real>
Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> SparseFactorisation<Real>::compliance(const Matrix& columns, int threads) const {
  // Eigen's LDLᵀ keeps L's strictly lower part, columns with rows in increasing order; D apart.
  const auto& l = ldlt_.matrixL().nestedExpression();
  const auto n = static_cast<Index>(l.rows());
  const auto r = static_cast<Index>(columns.cols());
  const auto* lp = l.outerIndexPtr();
  const auto* li = l.innerIndexPtr();
  const auto* lx = l.valuePtr();
  const auto& d = ldlt_.vectorD();
  const auto& order = ldlt_.permutationP().indices();  // (P b)[order[i]] = b[i]
  // The elimination tree: a column's parent is its first row below the diagonal.
  std::vector<Index> parent(static_cast<std::size_t>(n), -1);
  for (Index j = 0; j < n; ++j) {
    if (lp[j] < lp[j + 1]) parent[static_cast<std::size_t>(j)] = static_cast<Index>(li[lp[j]]);
  }
  // Z's columns in groups of kGroup (constraint rows come in threes on one point, whose reaches
  // nearly coincide): each group solved on the union of its reaches (sorted rows), the kGroup
  // right-hand sides side by side so that each entry of L is loaded once for all of them.
  constexpr Index kGroup = 4;
  const Index groups = (r + kGroup - 1) / kGroup;
  std::vector<std::vector<Index>> reach(static_cast<std::size_t>(groups));
  std::vector<std::vector<Real>> value(static_cast<std::size_t>(groups));  // kGroup values per reached row
  run_tasks(threads, static_cast<int>(groups), [&](int g) {
    std::vector<Real> x(static_cast<std::size_t>(kGroup * n), Real(0));
    std::vector<char> marked(static_cast<std::size_t>(n), 0);
    auto& rows = reach[static_cast<std::size_t>(g)];
    for (Index c = g * kGroup; c < std::min(r, (g + 1) * kGroup); ++c) {
      for (typename Matrix::InnerIterator it(columns, c); it; ++it) {
        Index k = static_cast<Index>(order[it.row()]);
        x[static_cast<std::size_t>(kGroup * k + (c - g * kGroup))] += it.value();
        while (k >= 0 && !marked[static_cast<std::size_t>(k)]) {
          marked[static_cast<std::size_t>(k)] = 1;
          rows.push_back(k);
          k = parent[static_cast<std::size_t>(k)];
        }
      }
    }
    // Ascending order is a topological order of the reach (L is lower triangular).
    std::sort(rows.begin(), rows.end());
    // The kGroup values of a row as one packet (Eigen's vector code whatever the optimiser decides:
    // gcc's -O3 turned the plain loop into scalar code, twice as slow as -O2's vectors).
    // L's arrays as locals: the stores below could otherwise alias the captured pointers, which
    // the compiler would then reload on every entry.
    using Packet = Eigen::Matrix<Real, kGroup, 1>;
    const auto* const outer = lp;
    const auto* const inner = li;
    const Real* const entries = lx;
    Real* const work = x.data();
    for (Index j : rows) {
      const Packet column = Eigen::Map<const Packet>(work + kGroup * j);
      if ((column.array() == 0).all()) continue;
      const auto end = outer[j + 1];
      for (auto p = outer[j]; p < end; ++p) Eigen::Map<Packet>(work + kGroup * inner[p]) -= entries[p] * column;
    }
    auto& values = value[static_cast<std::size_t>(g)];
    values.reserve(kGroup * rows.size());
    for (Index j : rows) {
      for (Index c = 0; c < kGroup; ++c) values.push_back(x[static_cast<std::size_t>(kGroup * j + c)]);
    }
  });
  // W = Zᵀ D⁻¹ Z on the rows some column reaches (Z dense there: a product Eigen blocks well).
  std::vector<Index> where(static_cast<std::size_t>(n), -1);
  std::vector<Index> used;
  for (const auto& rows : reach) {
    for (Index j : rows) {
      if (where[static_cast<std::size_t>(j)] < 0) {
        where[static_cast<std::size_t>(j)] = 0;
        used.push_back(j);
      }
    }
  }
  std::sort(used.begin(), used.end());
  for (std::size_t q = 0; q < used.size(); ++q) where[static_cast<std::size_t>(used[q])] = static_cast<Index>(q);
  Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> z = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>::Zero(
      static_cast<Eigen::Index>(used.size()), r);
  Eigen::Matrix<Real, Eigen::Dynamic, 1> inverse_d(static_cast<Eigen::Index>(used.size()));
  for (std::size_t q = 0; q < used.size(); ++q) inverse_d[static_cast<Eigen::Index>(q)] = Real(1) / d[used[q]];
  for (Index g = 0; g < groups; ++g) {
    const auto& rows = reach[static_cast<std::size_t>(g)];
    const auto& values = value[static_cast<std::size_t>(g)];
    for (Index c = g * kGroup; c < std::min(r, (g + 1) * kGroup); ++c) {
      for (std::size_t q = 0; q < rows.size(); ++q) {
        z(where[static_cast<std::size_t>(rows[q])], c) = values[kGroup * q + static_cast<std::size_t>(c - g * kGroup)];
      }
    }
  }
  Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> w = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>::Zero(r, r);
  if ((inverse_d.array() > 0).all()) {
    // A positive D (a positive definite A, as implicit Euler's is): W = (D^-1/2 Z)ᵀ (D^-1/2 Z), a
    // symmetric rank update (half the product), its upper triangle copied from the lower.
    const Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> scaled = inverse_d.cwiseSqrt().asDiagonal() * z;
    w.template selfadjointView<Eigen::Lower>().rankUpdate(scaled.transpose());
    for (Index a = 0; a < r; ++a) {
      for (Index b = a + 1; b < r; ++b) w(a, b) = w(b, a);
    }
  } else {
    w = z.transpose() * (inverse_d.asDiagonal() * z);
    for (Index a = 0; a < r; ++a) {
      for (Index b = 0; b < a; ++b) w(a, b) = w(b, a);
    }
  }
  return w;
}

template class SparseFactorisation<float>;
template class SparseFactorisation<double>;

}  // namespace fastcorot
