#include "fastcorot/sim/block_ldlt.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/parallel.h"

#include <Eigen/OrderingMethods>

#include <algorithm>
#include <cmath>

namespace fastcorot {

namespace {

template <class Real>
using Block = Eigen::Map<Eigen::Matrix<Real, 3, 3>>;
template <class Real>
using ConstBlock = Eigen::Map<const Eigen::Matrix<Real, 3, 3>>;

// Where entry (r, c) of a 3×3 block lies among its nine column-major values.
constexpr std::int64_t at(Index r, Index c) { return 3 * c + r; }

}  // namespace

template <class Real>
void BlockLDLT<Real>::analyse(const Matrix& matrix) {
  if (matrix.rows() != matrix.cols() || matrix.rows() % 3 != 0) {
    throw make_error("block LDLᵀ: the matrix is " + std::to_string(matrix.rows()) + " × " +
                     std::to_string(matrix.cols()) + ", not square in 3×3 blocks");
  }
  if (!matrix.isCompressed()) throw make_error("block LDLᵀ: the matrix is not compressed (makeCompressed first)");
  const Index n = static_cast<Index>(matrix.rows()) / 3;
  points_ = n;
  // The points' graph (both triangles, for the ordering) from A's lower triangle.
  std::vector<Eigen::Triplet<char>> links;
  for (Index i = 0; i < n; ++i) links.emplace_back(i, i, 1);
  for (Index c = 0; c < 3 * n; ++c) {
    for (typename Matrix::InnerIterator it(matrix, c); it; ++it) {
      const auto r = static_cast<Index>(it.row());
      if (r <= c || r / 3 == c / 3) continue;
      links.emplace_back(r / 3, c / 3, 1);
      links.emplace_back(c / 3, r / 3, 1);
    }
  }
  Eigen::SparseMatrix<char> graph(n, n);
  graph.setFromTriplets(links.begin(), links.end(), [](char a, char) { return a; });
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> elimination;  // position → point
  Eigen::AMDOrdering<int>()(graph, elimination);
  order_.assign(static_cast<std::size_t>(n), 0);
  for (Index q = 0; q < n; ++q) order_[static_cast<std::size_t>(elimination.indices()[q])] = q;

  // A's upper block triangle in elimination order.
  std::vector<std::vector<Index>> column_rows(static_cast<std::size_t>(n));
  for (Index j = 0; j < n; ++j) {
    for (typename Eigen::SparseMatrix<char>::InnerIterator it(graph, j); it; ++it) {
      const Index a = order_[static_cast<std::size_t>(it.row())], b = order_[static_cast<std::size_t>(j)];
      if (a <= b) column_rows[static_cast<std::size_t>(b)].push_back(a);
    }
  }
  a_start_.assign(1, 0);
  a_rows_.clear();
  for (auto& rows : column_rows) {
    std::sort(rows.begin(), rows.end());
    a_rows_.insert(a_rows_.end(), rows.begin(), rows.end());
    a_start_.push_back(static_cast<Index>(a_rows_.size()));
  }
  a_values_.assign(9 * a_rows_.size(), Real(0));
  const auto block_of = [&](Index row, Index column) -> std::int64_t {
    const auto first = a_rows_.begin() + a_start_[static_cast<std::size_t>(column)];
    const auto last = a_rows_.begin() + a_start_[static_cast<std::size_t>(column) + 1];
    return 9 * static_cast<std::int64_t>(std::lower_bound(first, last, row) - a_rows_.begin());
  };
  // Each stored entry of A's lower triangle, and where it lands (twice inside a diagonal block).
  stored_entries_ = static_cast<std::size_t>(matrix.nonZeros());
  scatter_from_.clear();
  scatter_to_.clear();
  for (Index c = 0; c < 3 * n; ++c) {
    for (Index p = static_cast<Index>(matrix.outerIndexPtr()[c]); p < static_cast<Index>(matrix.outerIndexPtr()[c + 1]); ++p) {
      const auto r = static_cast<Index>(matrix.innerIndexPtr()[p]);
      if (r < c) continue;
      const Index a = order_[static_cast<std::size_t>(r / 3)], b = order_[static_cast<std::size_t>(c / 3)];
      const Index rr = r % 3, cc = c % 3;
      if (a == b) {
        const std::int64_t base = block_of(a, a);
        scatter_from_.push_back(p);
        scatter_to_.push_back(base + at(rr, cc));
        if (rr != cc) {
          scatter_from_.push_back(p);
          scatter_to_.push_back(base + at(cc, rr));
        }
      } else if (a < b) {  // block (a, b) is A's block (point r, point c)
        scatter_from_.push_back(p);
        scatter_to_.push_back(block_of(a, b) + at(rr, cc));
      } else {  // block (b, a) is its transpose
        scatter_from_.push_back(p);
        scatter_to_.push_back(block_of(b, a) + at(cc, rr));
      }
    }
  }

  // The elimination tree and L's column counts (each row's subtree walked once).
  parent_.assign(static_cast<std::size_t>(n), -1);
  std::vector<Index> flag(static_cast<std::size_t>(n), -1), count(static_cast<std::size_t>(n), 0);
  for (Index k = 0; k < n; ++k) {
    flag[static_cast<std::size_t>(k)] = k;
    for (Index p = a_start_[static_cast<std::size_t>(k)]; p < a_start_[static_cast<std::size_t>(k) + 1]; ++p) {
      for (Index i = a_rows_[static_cast<std::size_t>(p)]; flag[static_cast<std::size_t>(i)] != k;
           i = parent_[static_cast<std::size_t>(i)]) {
        if (parent_[static_cast<std::size_t>(i)] < 0) parent_[static_cast<std::size_t>(i)] = k;
        ++count[static_cast<std::size_t>(i)];
        flag[static_cast<std::size_t>(i)] = k;
      }
    }
  }
  l_start_.assign(1, 0);
  for (Index k = 0; k < n; ++k) l_start_.push_back(l_start_.back() + count[static_cast<std::size_t>(k)]);
  l_rows_.assign(static_cast<std::size_t>(l_start_.back()), 0);
  l_values_.assign(9 * l_rows_.size(), Real(0));
  d_inverse_.assign(9 * static_cast<std::size_t>(n), Real(0));
  pivots_.assign(3 * static_cast<std::size_t>(n), Real(0));
  u_inverse_.assign(3 * static_cast<std::size_t>(n), Real(0));
}

template <class Real>
bool BlockLDLT<Real>::factorise(const Matrix& matrix) {
  const Index n = points_;
  if (matrix.rows() != 3 * n || matrix.cols() != 3 * n || !matrix.isCompressed() ||
      static_cast<std::size_t>(matrix.nonZeros()) != stored_entries_) {
    throw make_error("block LDLᵀ: factorise takes a compressed matrix of the analysed pattern (", 3 * n, " × ", 3 * n,
                     ", ", stored_entries_, " stored entries), not ", matrix.rows(), " × ", matrix.cols(), " with ",
                     matrix.nonZeros());
  }
  std::fill(a_values_.begin(), a_values_.end(), Real(0));
  const Real* stored = matrix.valuePtr();
  for (std::size_t s = 0; s < scatter_from_.size(); ++s) {
    const Real value = stored[scatter_from_[s]];
    if (!std::isfinite(value)) {
      throw make_error("the system matrix has a non-finite entry (", value, ") in its lower triangle: a diverging or "
                       "ill-defined step");
    }
    a_values_[scatter_to_[s]] = value;
  }

  // Up-looking: row k of L solves L(0:k, 0:k) D(0:k) y = A(0:k, k) on the tree paths from the
  // column's nonzero blocks, in topological order. A block of y lies as three rows of four values
  // (the fourth zero), so that each block of L updates it with three four-wide packets.
  using Row = Eigen::Array<Real, 4, 1>;
  using Square = Eigen::Matrix<Real, 3, 3>;
  std::vector<Real> y(12 * static_cast<std::size_t>(n), Real(0));
  std::vector<Index> flag(static_cast<std::size_t>(n), -1), filled(static_cast<std::size_t>(n), 0);
  std::vector<Index> path(static_cast<std::size_t>(n)), stack(static_cast<std::size_t>(n));
  const Index* const rows = l_rows_.data();
  Real* const entries = l_values_.data();
  Real* const work = y.data();
  for (Index k = 0; k < n; ++k) {
    Index top = n;
    flag[static_cast<std::size_t>(k)] = k;
    for (Index p = a_start_[static_cast<std::size_t>(k)]; p < a_start_[static_cast<std::size_t>(k) + 1]; ++p) {
      Index i = a_rows_[static_cast<std::size_t>(p)];
      const Real* a = a_values_.data() + 9 * static_cast<std::size_t>(p);
      for (Index e = 0; e < 3; ++e) {
        for (Index c = 0; c < 3; ++c) work[12 * i + 4 * e + c] = a[at(e, c)];
      }
      Index length = 0;
      for (; flag[static_cast<std::size_t>(i)] != k; i = parent_[static_cast<std::size_t>(i)]) {
        path[static_cast<std::size_t>(length++)] = i;
        flag[static_cast<std::size_t>(i)] = k;
      }
      while (length > 0) stack[static_cast<std::size_t>(--top)] = path[static_cast<std::size_t>(--length)];
    }
    const auto take = [&](Index j) {  // y's block j as a matrix, cleared in y
      Square block;
      for (Index e = 0; e < 3; ++e) {
        for (Index c = 0; c < 3; ++c) block(e, c) = work[12 * j + 4 * e + c];
      }
      std::fill(work + 12 * j, work + 12 * (j + 1), Real(0));
      return block;
    };
    Square diagonal = take(k);
    for (Index t = top; t < n; ++t) {
      const Index j = stack[static_cast<std::size_t>(t)];
      const Row y0 = Eigen::Map<const Row>(work + 12 * j);
      const Row y1 = Eigen::Map<const Row>(work + 12 * j + 4);
      const Row y2 = Eigen::Map<const Row>(work + 12 * j + 8);
      const Square yj = take(j);
      const Index begin = l_start_[static_cast<std::size_t>(j)];
      const Index end = begin + filled[static_cast<std::size_t>(j)];
      for (Index p = begin; p < end; ++p) {
        const Real* l = entries + 9 * static_cast<std::size_t>(p);  // column-major: L(e, f) at 3 f + e
        Real* target = work + 12 * rows[p];
        Eigen::Map<Row>(target) -= l[0] * y0 + l[3] * y1 + l[6] * y2;
        Eigen::Map<Row>(target + 4) -= l[1] * y0 + l[4] * y1 + l[7] * y2;
        Eigen::Map<Row>(target + 8) -= l[2] * y0 + l[5] * y1 + l[8] * y2;
      }
      const Square lkj = yj.transpose() * ConstBlock<Real>(d_inverse_.data() + 9 * j);
      diagonal.noalias() -= lkj * yj;
      l_rows_[static_cast<std::size_t>(end)] = k;
      Block<Real>(entries + 9 * static_cast<std::size_t>(end)) = lkj;
      ++filled[static_cast<std::size_t>(j)];
    }
    // D's block as U diag(d) Uᵀ (no pivoting, its lower triangle read), and its inverse.
    const Real d0 = diagonal(0, 0);
    const Real l10 = diagonal(1, 0) / d0, l20 = diagonal(2, 0) / d0;
    const Real d1 = diagonal(1, 1) - l10 * l10 * d0;
    const Real l21 = (diagonal(2, 1) - l20 * l10 * d0) / d1;
    const Real d2 = diagonal(2, 2) - l20 * l20 * d0 - l21 * l21 * d1;
    for (const Real d : {d0, d1, d2}) {
      if (d == Real(0) || !std::isfinite(d)) return false;
    }
    Real* pivots = pivots_.data() + 3 * k;
    pivots[0] = d0, pivots[1] = d1, pivots[2] = d2;
    Real* lower = u_inverse_.data() + 3 * k;
    lower[0] = -l10, lower[1] = l10 * l21 - l20, lower[2] = -l21;
    Eigen::Matrix<Real, 3, 3> u_inverse = Eigen::Matrix<Real, 3, 3>::Identity();
    u_inverse(1, 0) = lower[0], u_inverse(2, 0) = lower[1], u_inverse(2, 1) = lower[2];
    Block<Real>(d_inverse_.data() + 9 * k) =
        u_inverse.transpose() * Eigen::Matrix<Real, 3, 1>(1 / d0, 1 / d1, 1 / d2).asDiagonal() * u_inverse;
  }
  return true;
}

template <class Real>
void BlockLDLT<Real>::solve(const Real* b, Real* x) const {
  const Index n = points_;
  using Vector = Eigen::Matrix<Real, 3, 1>;
  std::vector<Real> t(3 * static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    Eigen::Map<Vector>(t.data() + 3 * order_[static_cast<std::size_t>(i)]) = Eigen::Map<const Vector>(b + 3 * i);
  }
  for (Index j = 0; j < n; ++j) {
    const Vector tj = Eigen::Map<const Vector>(t.data() + 3 * j);
    for (Index p = l_start_[static_cast<std::size_t>(j)]; p < l_start_[static_cast<std::size_t>(j) + 1]; ++p) {
      Eigen::Map<Vector>(t.data() + 3 * l_rows_[static_cast<std::size_t>(p)]).noalias() -=
          ConstBlock<Real>(l_values_.data() + 9 * static_cast<std::size_t>(p)) * tj;
    }
  }
  for (Index j = 0; j < n; ++j) {
    const Vector tj = Eigen::Map<const Vector>(t.data() + 3 * j);
    Eigen::Map<Vector>(t.data() + 3 * j).noalias() = ConstBlock<Real>(d_inverse_.data() + 9 * j) * tj;
  }
  for (Index j = n - 1; j >= 0; --j) {
    Vector tj = Eigen::Map<const Vector>(t.data() + 3 * j);
    for (Index p = l_start_[static_cast<std::size_t>(j)]; p < l_start_[static_cast<std::size_t>(j) + 1]; ++p) {
      tj.noalias() -= ConstBlock<Real>(l_values_.data() + 9 * static_cast<std::size_t>(p)).transpose() *
                      Eigen::Map<const Vector>(t.data() + 3 * l_rows_[static_cast<std::size_t>(p)]);
    }
    Eigen::Map<Vector>(t.data() + 3 * j) = tj;
  }
  for (Index i = 0; i < n; ++i) {
    Eigen::Map<Vector>(x + 3 * i) = Eigen::Map<const Vector>(t.data() + 3 * order_[static_cast<std::size_t>(i)]);
  }
}

template <class Real>
typename BlockLDLT<Real>::DenseMatrix BlockLDLT<Real>::compliance(const Matrix& columns, int threads) const {
  const Index n = points_;
  const auto r = static_cast<Index>(columns.cols());
  if (columns.rows() != 3 * n) {
    throw make_error("block LDLᵀ: compliance of columns with ", columns.rows(), " rows for a ", 3 * n, "-unknown system");
  }
  // Z's columns in groups of kGroup (constraint rows come in threes on one point, whose paths
  // nearly coincide): each group solved on the union of its paths. A point's entries lie as three
  // packets (x, y, z) of kGroup columns each, so that each block of L updates three packets.
  constexpr Index kGroup = 8;
  using Packet = Eigen::Array<Real, kGroup, 1>;
  const Index groups = (r + kGroup - 1) / kGroup;
  std::vector<std::vector<Index>> reach(static_cast<std::size_t>(groups));
  std::vector<std::vector<Real>> value(static_cast<std::size_t>(groups));  // 3 × kGroup per reached point
  run_tasks(threads, static_cast<int>(groups), [&](int g) {
    std::vector<Real> z(static_cast<std::size_t>(3 * kGroup * n), Real(0));
    std::vector<char> marked(static_cast<std::size_t>(n), 0);
    auto& points = reach[static_cast<std::size_t>(g)];
    for (Index c = g * kGroup; c < std::min(r, (g + 1) * kGroup); ++c) {
      for (typename Matrix::InnerIterator it(columns, c); it; ++it) {
        const auto row = static_cast<Index>(it.row());
        Index k = order_[static_cast<std::size_t>(row / 3)];
        z[static_cast<std::size_t>(kGroup * (3 * k + row % 3) + (c - g * kGroup))] += it.value();
        for (; k >= 0 && !marked[static_cast<std::size_t>(k)]; k = parent_[static_cast<std::size_t>(k)]) {
          marked[static_cast<std::size_t>(k)] = 1;
          points.push_back(k);
        }
      }
    }
    std::sort(points.begin(), points.end());  // ascending is a topological order (L lower triangular)
    // L's arrays as locals: the stores could otherwise alias the members, reloaded on every entry.
    const Index* const start = l_start_.data();
    const Index* const rows = l_rows_.data();
    const Real* const entries = l_values_.data();
    Real* const work = z.data();
    for (Index j : points) {
      const Packet z0 = Eigen::Map<const Packet>(work + kGroup * 3 * j);
      const Packet z1 = Eigen::Map<const Packet>(work + kGroup * (3 * j + 1));
      const Packet z2 = Eigen::Map<const Packet>(work + kGroup * (3 * j + 2));
      if ((z0 == 0).all() && (z1 == 0).all() && (z2 == 0).all()) continue;
      for (Index p = start[j]; p < start[j + 1]; ++p) {
        const Real* l = entries + 9 * static_cast<std::size_t>(p);  // column-major: L(e, f) at 3 f + e
        Real* target = work + kGroup * 3 * rows[p];
        Eigen::Map<Packet>(target) -= l[0] * z0 + l[3] * z1 + l[6] * z2;
        Eigen::Map<Packet>(target + kGroup) -= l[1] * z0 + l[4] * z1 + l[7] * z2;
        Eigen::Map<Packet>(target + 2 * kGroup) -= l[2] * z0 + l[5] * z1 + l[8] * z2;
      }
    }
    auto& values = value[static_cast<std::size_t>(g)];
    values.reserve(3 * kGroup * points.size());
    for (Index j : points) values.insert(values.end(), work + 3 * kGroup * j, work + 3 * kGroup * (j + 1));
  });
  // W = Zᵀ D⁻¹ Z on the points some column reaches (Z dense there: a product Eigen blocks well).
  std::vector<Index> where(static_cast<std::size_t>(n), -1);
  std::vector<Index> used;
  for (const auto& points : reach) {
    for (Index j : points) {
      if (where[static_cast<std::size_t>(j)] < 0) {
        where[static_cast<std::size_t>(j)] = 0;
        used.push_back(j);
      }
    }
  }
  std::sort(used.begin(), used.end());
  for (std::size_t q = 0; q < used.size(); ++q) where[static_cast<std::size_t>(used[q])] = static_cast<Index>(q);
  const auto m = static_cast<Eigen::Index>(3 * used.size());
  if (m == 0) return DenseMatrix::Zero(r, r);  // no column has an entry
  DenseMatrix z = DenseMatrix::Zero(m, r);
  for (Index g = 0; g < groups; ++g) {
    const auto& points = reach[static_cast<std::size_t>(g)];
    const auto& values = value[static_cast<std::size_t>(g)];
    for (Index c = g * kGroup; c < std::min(r, (g + 1) * kGroup); ++c) {
      for (std::size_t q = 0; q < points.size(); ++q) {
        for (Index e = 0; e < 3; ++e) {
          z(3 * where[static_cast<std::size_t>(points[q])] + e, c) =
              values[3 * kGroup * q + static_cast<std::size_t>(kGroup * e + (c - g * kGroup))];
        }
      }
    }
  }
  bool positive = true;
  for (Index j : used) {
    for (Index e = 0; e < 3; ++e) positive = positive && pivots_[static_cast<std::size_t>(3 * j + e)] > 0;
  }
  DenseMatrix w = DenseMatrix::Zero(r, r);
  if (positive) {
    // A positive D (a positive definite A, as implicit Euler's is): D⁻¹ = Sᵀ S with S = diag(d)^-1/2
    // U⁻¹ per block, and W = (S Z)ᵀ (S Z) a symmetric rank update (half the product).
    for (std::size_t q = 0; q < used.size(); ++q) {
      const Real* d = pivots_.data() + 3 * used[q];
      const Real* lower = u_inverse_.data() + 3 * used[q];
      auto rows = z.middleRows(static_cast<Eigen::Index>(3 * q), 3);
      rows.row(2) += lower[1] * rows.row(0) + lower[2] * rows.row(1);
      rows.row(1) += lower[0] * rows.row(0);
      for (Index e = 0; e < 3; ++e) rows.row(e) /= std::sqrt(d[e]);
    }
    w.template selfadjointView<Eigen::Lower>().rankUpdate(z.transpose());
    for (Index a = 0; a < r; ++a) {
      for (Index b = a + 1; b < r; ++b) w(a, b) = w(b, a);
    }
  } else {
    DenseMatrix dz(m, r);
    for (std::size_t q = 0; q < used.size(); ++q) {
      const auto s = static_cast<Eigen::Index>(3 * q);
      dz.middleRows(s, 3).noalias() = ConstBlock<Real>(d_inverse_.data() + 9 * used[q]) * z.middleRows(s, 3);
    }
    w.noalias() = z.transpose() * dz;
    for (Index a = 0; a < r; ++a) {
      for (Index b = 0; b < a; ++b) w(a, b) = w(b, a);
    }
  }
  return w;
}

template class BlockLDLT<float>;
template class BlockLDLT<double>;

}  // namespace fastcorot
