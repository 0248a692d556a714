#include "fastcorot/sim/sparse_factorisation.h"

#include <algorithm>

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
Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> SparseFactorisation<Real>::compliance(const Matrix& columns) const {
  Matrix z = ldlt_.permutationP() * columns;
  ldlt_.matrixL().solveInPlace(z);
  z.prune(Real(0));
  const Matrix scaled = ldlt_.vectorD().cwiseInverse().asDiagonal() * z;
  const Matrix product = Matrix(z.transpose()) * scaled;
  return Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>(product);
}

template class SparseFactorisation<float>;
template class SparseFactorisation<double>;

}  // namespace fastcorot
