#include "fastcorot/sim/precomputed_linear_solver.h"

#include "fastcorot/core/error.h"
#include "carried_bits.h"

namespace fastcorot {

template <class Real>
LinearSolveReport PrecomputedLinearSolver<Real>::solve(const MechanicalSystem<Real>& system,
                                                       const MatrixFactors<Real>& factors,
                                                       std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) {
  const auto n = static_cast<std::size_t>(system.size());
  if (initial_.nonZeros() == 0) {
    Eigen::SparseMatrix<Real> matrix = system.assemble(factors);
    matrix.makeCompressed();
    if (!factorisation_.factorise(matrix)) {
      throw make_error("PrecomputedLinearSolver: the system matrix of the first step could not be factorised "
                       "(singular: is every point held by a mass or an element?)");
    }
    initial_ = std::move(matrix);
  }
  if (static_cast<std::size_t>(initial_.rows()) != 3 * n || rhs.size() != n || x.size() != n) {
    throw make_error("PrecomputedLinearSolver: a system of ", n, " points; its precomputed matrix has ",
                     initial_.rows() / 3, " (the points cannot change after the first step)");
  }
  factorisation_.solve(rhs.data()->data(), x.data()->data(), static_cast<Index>(3 * n));
  return {};
}

template <class Real>
std::vector<std::int64_t> PrecomputedLinearSolver<Real>::carried_state() const {
  std::vector<std::int64_t> state{initial_.rows()};
  carried_bits::push_matrix(state, initial_);
  return state;
}

template <class Real>
void PrecomputedLinearSolver<Real>::check_carried_state(const std::vector<std::int64_t>& state) const {
  const std::span<const std::int64_t> values(state);
  if (values.size() < 2 || values[0] < 0) {
    throw make_error("PrecomputedLinearSolver: expected the matrix size and the matrix to restore, got ", values.size(),
                     " values");
  }
  const std::size_t length = 1 + carried_bits::matrix_length(values.subspan(1), values[0], "PrecomputedLinearSolver");
  if (values.size() != length) {
    throw make_error("PrecomputedLinearSolver: expected ", length, " values to restore, got ", values.size());
  }
  carried_bits::read_matrix<Real>(values.subspan(1), values[0], "PrecomputedLinearSolver");
}

template <class Real>
void PrecomputedLinearSolver<Real>::restore_carried_state(const std::vector<std::int64_t>& state) {
  check_carried_state(state);
  const std::span<const std::int64_t> values(state);
  Eigen::SparseMatrix<Real> matrix = carried_bits::read_matrix<Real>(values.subspan(1), values[0], "PrecomputedLinearSolver");
  if (matrix.nonZeros() > 0 && !factorisation_.factorise(matrix)) {
    throw make_error("PrecomputedLinearSolver: the restored matrix could not be factorised");
  }
  initial_ = std::move(matrix);
}

template class PrecomputedLinearSolver<float>;
template class PrecomputedLinearSolver<double>;

}  // namespace fastcorot
