#include "fastcorot/sim/sparse_direct_solver.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

template <class Real>
LinearSolveReport SparseDirectSolver<Real>::solve(const MechanicalSystem<Real>& system,
                                                  const MatrixFactors<Real>& factors,
                                                  std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) {
  const PhaseTimer timer(system.timer_slot(&PhaseTimes::solver_vectors));  // assembly and factorisation
  const Eigen::SparseMatrix<Real>& matrix = system.assemble(factors);  // compressed
  // The pattern depends only on the topology and the fixed points: one analysis serves every step.
  factored_ = false;
  if (!factorisation_.factorise(matrix)) {
    throw make_error("sparse direct solver: the system matrix could not be factorised (singular: is "
                     "every point held by a mass or an element?)");
  }
  factored_ = true;
  factorisation_.solve(rhs.data()->data(), x.data()->data(), static_cast<Index>(3 * rhs.size()));
  return {};
}

template <class Real>
LinearSolveReport SparseDirectSolver<Real>::solve_again(const MechanicalSystem<Real>& system,
                                                        const MatrixFactors<Real>& factors,
                                                        std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) {
  if (!factored_) return solve(system, factors, rhs, x);
  factorisation_.solve(rhs.data()->data(), x.data()->data(), static_cast<Index>(3 * rhs.size()));
  return {};
}

template class SparseDirectSolver<float>;
template class SparseDirectSolver<double>;

}  // namespace fastcorot
