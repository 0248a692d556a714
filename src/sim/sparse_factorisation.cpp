#include "fastcorot/sim/sparse_factorisation.h"

#include "fastcorot/core/error.h"

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
    ldlt_.analyse(matrix);
    analysed_outer_.assign(outer, outer + matrix.outerSize() + 1);
    analysed_inner_.assign(inner, inner + matrix.nonZeros());
  }
  return ldlt_.factorise(matrix);
}

template <class Real>
void SparseFactorisation<Real>::solve(const Real* b, Real* x, Index size) const {
  if (size != ldlt_.size()) {
    throw make_error("sparse factorisation: a right-hand side of " + std::to_string(size) + " values for a " +
                     std::to_string(ldlt_.size()) + "-unknown system");
  }
  ldlt_.solve(b, x);
}

template <class Real>
Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> SparseFactorisation<Real>::compliance(const Matrix& columns, int threads) const {
  return ldlt_.compliance(columns, threads);
}

template class SparseFactorisation<float>;
template class SparseFactorisation<double>;

}  // namespace fastcorot
