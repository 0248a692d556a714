#include "fastcorot/sim/sparse_direct_solver.h"

#include "fastcorot/core/error.h"

#include <algorithm>

namespace fastcorot {

template <class Real>
LinearSolveReport SparseDirectSolver<Real>::solve(const MechanicalSystem<Real>& system,
                                                  const MatrixFactors<Real>& factors,
                                                  std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) {
  const PhaseTimer timer(system.timer_slot(&PhaseTimes::solver_vectors));  // assembly and factorisation
  Eigen::SparseMatrix<Real> matrix = system.assemble(factors);
  matrix.makeCompressed();
  // The pattern of the assembled matrix depends only on the topology and the fixed points, so one
  // analysis serves every step; any change of pattern triggers a new one.
  const auto* outer = matrix.outerIndexPtr();
  const auto* inner = matrix.innerIndexPtr();
  const bool same_pattern =
      analysed_outer_.size() == static_cast<std::size_t>(matrix.outerSize() + 1) &&
      analysed_inner_.size() == static_cast<std::size_t>(matrix.nonZeros()) &&
      std::equal(analysed_outer_.begin(), analysed_outer_.end(), outer) &&
      std::equal(analysed_inner_.begin(), analysed_inner_.end(), inner);
  if (!same_pattern) {
    ldlt_.analyzePattern(matrix);
    analysed_outer_.assign(outer, outer + matrix.outerSize() + 1);
    analysed_inner_.assign(inner, inner + matrix.nonZeros());
  }
  ldlt_.factorize(matrix);
  if (ldlt_.info() != Eigen::Success) {
    throw make_error("sparse direct solver: the system matrix could not be factorised (singular: is "
                     "every point held by a mass or an element?)");
  }
  const auto n = static_cast<Eigen::Index>(3 * rhs.size());
  const Eigen::Map<const Eigen::Matrix<Real, Eigen::Dynamic, 1>> b(rhs.data()->data(), n);
  Eigen::Map<Eigen::Matrix<Real, Eigen::Dynamic, 1>> solution(x.data()->data(), n);
  solution = ldlt_.solve(b);
  return {};
}

template class SparseDirectSolver<float>;
template class SparseDirectSolver<double>;

}  // namespace fastcorot
