#include "fastcorot/sim/ssor_preconditioner.h"

#include "fastcorot/core/error.h"
#include "carried_bits.h"

#include <cmath>

namespace fastcorot {

template <class Real>
SSORPreconditioner<Real>::SSORPreconditioner(Parameters parameters) : parameters_(parameters) {
  if (!(parameters_.omega > 0 && parameters_.omega < 2)) {
    throw make_error("SSORPreconditioner: omega = ", parameters_.omega, ": must be in (0, 2)");
  }
}

template <class Real>
void SSORPreconditioner<Real>::set_matrix(const Eigen::SparseMatrix<Real>& matrix) {
  rows_ = matrix;
  rows_.makeCompressed();
  const Index n = static_cast<Index>(rows_.rows());
  inverse_diagonal_.assign(static_cast<std::size_t>(n), Real(1));
  for (Index j = 0; j < n; ++j) {
    Real diagonal = 0;
    bool row_is_zero = true;
    for (typename Eigen::SparseMatrix<Real, Eigen::RowMajor>::InnerIterator it(rows_, j); it; ++it) {
      if (it.value() != 0) row_is_zero = false;
      if (it.col() == j) diagonal = it.value();
    }
    if (row_is_zero) continue;  // a point with neither mass nor element: z_j = r_j omega (= 0)
    if (diagonal == 0 || !std::isfinite(diagonal)) {
      throw make_error("SSORPreconditioner: the system matrix's diagonal entry of point ", j / 3, ", axis ",
                       "xyz"[j % 3], " is ", diagonal, " (cannot be inverted)");
    }
    inverse_diagonal_[static_cast<std::size_t>(j)] = Real(1) / diagonal;
  }
}

template <class Real>
void SSORPreconditioner<Real>::build(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors) {
  set_matrix(system.assemble(factors));
}

template <class Real>
void SSORPreconditioner<Real>::apply(const Real* r, Real* z, Index size) const {
  const Index n = static_cast<Index>(rows_.rows());
  if (size != n) throw make_error("SSORPreconditioner: applied to ", size, " values; its matrix has ", n, " rows");
  const Real w = parameters_.omega;
  const Index* starts = rows_.outerIndexPtr();
  const Index* columns = rows_.innerIndexPtr();
  const Real* values = rows_.valuePtr();
  // (D/w + U) t = r, from the last row up; a row's columns are sorted, so its upper part is a tail.
  for (Index j = n - 1; j >= 0; --j) {
    Index k = starts[j];
    const Index end = starts[j + 1];
    while (k < end && columns[k] <= j) ++k;
    Real sum = 0;
    for (; k < end; ++k) sum += z[columns[k]] * values[k];
    z[j] = (r[j] - sum) * w * inverse_diagonal_[static_cast<std::size_t>(j)];
  }
  // (I + w D^-1 L) z = t, from the first row down, in place.
  for (Index j = 0; j < n; ++j) {
    Real sum = 0;
    for (Index k = starts[j]; k < starts[j + 1] && columns[k] < j; ++k) sum += z[columns[k]] * values[k];
    z[j] -= sum * w * inverse_diagonal_[static_cast<std::size_t>(j)];
  }
  if (parameters_.scale_by_two_minus_omega && w != Real(1)) {
    for (Index j = 0; j < n; ++j) z[j] *= 2 - w;
  }
}

template <class Real>
std::vector<std::int64_t> SSORPreconditioner<Real>::carried_state() const {
  // The size, then the matrix (as compressed columns: the transpose of the rows, which is what
  // Eigen's conversion gives back).
  std::vector<std::int64_t> state{rows_.rows()};
  carried_bits::push_matrix(state, Eigen::SparseMatrix<Real>(rows_));
  return state;
}

template <class Real>
void SSORPreconditioner<Real>::check_carried_state(std::span<const std::int64_t> state) const {
  if (state.size() < 2 || state[0] < 0 || state[0] % 3 != 0) {
    throw make_error("SSORPreconditioner: expected the matrix size and the matrix to restore, got ", state.size(), " values");
  }
  const std::size_t length = 1 + carried_bits::matrix_length(state.subspan(1), state[0], "SSORPreconditioner");
  if (state.size() != length) {
    throw make_error("SSORPreconditioner: expected ", length, " values to restore, got ", state.size());
  }
  carried_bits::read_matrix<Real>(state.subspan(1), state[0], "SSORPreconditioner");
}

template <class Real>
void SSORPreconditioner<Real>::restore_carried_state(std::span<const std::int64_t> state) {
  check_carried_state(state);
  Eigen::SparseMatrix<Real> matrix = carried_bits::read_matrix<Real>(state.subspan(1), state[0], "SSORPreconditioner");
  if (matrix.nonZeros() == 0) {
    rows_ = Eigen::SparseMatrix<Real, Eigen::RowMajor>();
    inverse_diagonal_.clear();
    return;
  }
  set_matrix(matrix);
}

template class SSORPreconditioner<float>;
template class SSORPreconditioner<double>;

}  // namespace fastcorot
