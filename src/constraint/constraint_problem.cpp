#include "fastcorot/constraint/constraint_problem.h"

#include "fastcorot/core/error.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>

namespace fastcorot {

template <class Real>
void BilateralResolution3<Real>::init(int line, const DenseMatrix<Real>& w, Real* f) {
  const Mat3<Real> block = w.template block<3, 3>(line, line);
  // SOFA inverts the block by cofactors (type::invertMatrix); a singular block (a row no
  // correction reaches) gives zero rather than infinities, and the row stays unsolved.
  const Real det = block.determinant();
  inverse_ = det != 0 ? Mat3<Real>(block.inverse()) : Mat3<Real>::Zero();
  if (previous_) {
    for (int i = 0; i < 3; ++i) f[line + i] = (*previous_)[i];
  }
}

template <class Real>
void BilateralResolution3<Real>::resolve(int line, const DenseMatrix<Real>&, const Real* d, Real* f, const Real*) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) f[line + i] -= d[line + j] * inverse_(i, j) * load_;
  }
}

template <class Real>
void BilateralResolution3<Real>::store(int line, const Real* f) {
  if (previous_) {
    for (int i = 0; i < 3; ++i) (*previous_)[i] = f[line + i];
  }
}

template <class Real>
void BilateralResolutionN<Real>::init(int line, const DenseMatrix<Real>& w, Real*) {
  const int n = this->lines();
  block_.compute(Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>(w.block(line, line, n, n)));
}

template <class Real>
void BilateralResolutionN<Real>::resolve(int line, const DenseMatrix<Real>&, const Real* d, Real* f, const Real*) {
  const int n = this->lines();
  const Eigen::Map<const DenseVector<Real>> violation(d + line, n);
  Eigen::Map<DenseVector<Real>> force(f + line, n);
  force -= block_.solve(violation);
}

template <class Real>
void UnilateralResolution<Real>::resolve(int line, const DenseMatrix<Real>& w, const Real* d, Real* f, const Real*) {
  f[line] -= d[line] / w(line, line);
  if (f[line] < 0) f[line] = 0;
}

template <class Real>
void ConstraintProblem<Real>::clear(int rows) {
  w.setZero(rows, rows);
  dfree.setZero(rows);
  f.setZero(rows);
  d.setZero(rows);
  resolutions.clear();
  first_line.clear();
  span_begin.clear();
  spans.clear();
}

template <class Real>
void ConstraintProblem<Real>::add_block(std::unique_ptr<ConstraintResolution<Real>> resolution) {
  first_line.push_back(first_line.empty() ? 0 : first_line.back() + resolutions.back()->lines());
  resolutions.push_back(std::move(resolution));
}

template <class Real>
void ConstraintProblem<Real>::check_blocks() const {
  const int covered = first_line.empty() ? 0 : first_line.back() + resolutions.back()->lines();
  if (covered != size()) throw make_error("constraint problem: the blocks cover ", covered, " rows of ", size());
}

template <class Real>
void ConstraintProblem<Real>::find_column_spans() {
  // A gap this short costs less to multiply through than to step over.
  constexpr int kShortestGap = 16;
  const int n = size();
  span_begin.assign(1, 0);
  spans.clear();
  for (std::size_t b = 0; b < resolutions.size(); ++b) {
    const int first = first_line[b], lines = resolutions[b]->lines();
    int open = -1, last_nonzero = -1;
    for (int c = 0; c < n; ++c) {
      bool nonzero = false;
      for (int l = first; l < first + lines && !nonzero; ++l) nonzero = w(l, c) != 0;
      if (!nonzero) continue;
      if (open >= 0 && c - last_nonzero > kShortestGap) {
        spans.push_back({open, last_nonzero + 1});
        open = -1;
      }
      if (open < 0) open = c;
      last_nonzero = c;
    }
    if (open >= 0) spans.push_back({open, last_nonzero + 1});
    span_begin.push_back(static_cast<int>(spans.size()));
  }
}

template <class Real>
Real ConstraintProblem<Real>::row_times_lambda(int row, std::size_t block) const {
  Real sum = 0;
  for (int k = span_begin[block]; k < span_begin[block + 1]; ++k) {
    const auto [begin, end] = spans[static_cast<std::size_t>(k)];
    sum += w.row(row).segment(begin, end - begin).dot(f.segment(begin, end - begin));
  }
  return sum;
}

template class BilateralResolution3<float>;
template class BilateralResolution3<double>;
template class BilateralResolutionN<float>;
template class BilateralResolutionN<double>;
template class UnilateralResolution<float>;
template class UnilateralResolution<double>;
template struct ConstraintProblem<float>;
template struct ConstraintProblem<double>;

}  // namespace fastcorot
