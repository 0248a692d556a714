#include "fastcorot/sim/warp_preconditioner.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/rotation_finder.h"
#include "carried_bits.h"

namespace fastcorot {

template <class Real>
WarpPreconditioner<Real>::WarpPreconditioner(Parameters parameters)
    : parameters_(parameters), counter_(parameters.assembling_rate) {
  if (parameters_.assembling_rate < 1) {
    throw make_error("RotationMatrixSystem: assemblingRate = ", parameters_.assembling_rate, ": must be at least 1");
  }
}

template <class Real>
void WarpPreconditioner<Real>::build(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors) {
  const auto points = static_cast<std::size_t>(system.size());
  if (++counter_ >= parameters_.assembling_rate) {
    Eigen::SparseMatrix<Real> matrix = system.assemble(factors);
    matrix.makeCompressed();
    if (!factorisation_.factorise(matrix)) {
      throw make_error("WarpPreconditioner: the system matrix could not be factorised "
                       "(singular: is every point held by a mass or an element?)");
    }
    assembled_ = std::move(matrix);
    counter_ = 0;
    rotations_.assign(points, Mat3<Real>::Identity());
    return;
  }
  auto found = find_rotations(system, initial_rotations_);
  if (found) {
    rotations_ = std::move(*found);
  } else {
    rotations_.assign(points, Mat3<Real>::Identity());
  }
}

template <class Real>
void WarpPreconditioner<Real>::apply(const Real* r, Real* z, Index size) const {
  const std::size_t points = rotations_.size();
  if (static_cast<std::size_t>(size) != 3 * points || assembled_.rows() != size) {
    throw make_error("WarpPreconditioner: applied to ", size, " values; built for ", 3 * points);
  }
  turned_.resize(3 * points);
  solved_.resize(3 * points);
  using Vec = Eigen::Map<const Vec3<Real>>;
  for (std::size_t i = 0; i < points; ++i) {
    Eigen::Map<Vec3<Real>>(turned_.data() + 3 * i) = rotations_[i].transpose() * Vec(r + 3 * i);
  }
  factorisation_.solve(turned_.data(), solved_.data(), size);
  for (std::size_t i = 0; i < points; ++i) {
    Eigen::Map<Vec3<Real>>(z + 3 * i) = rotations_[i] * Vec(solved_.data() + 3 * i);
  }
}

template <class Real>
std::vector<std::int64_t> WarpPreconditioner<Real>::carried_state() const {
  // The counter, the point count, the rotations, the assembled matrix.
  std::vector<std::int64_t> state{counter_, static_cast<std::int64_t>(rotations_.size())};
  for (const auto& block : rotations_) {
    for (int c = 0; c < 9; ++c) state.push_back(carried_bits::to_bits(block.data()[c]));
  }
  carried_bits::push_matrix(state, assembled_);
  return state;
}

template <class Real>
void WarpPreconditioner<Real>::check_carried_state(std::span<const std::int64_t> state) const {
  if (state.size() < 3 || state[0] < 0 || state[0] > parameters_.assembling_rate || state[1] < 0) {
    throw make_error("WarpPreconditioner: expected its counter, point count, rotations and matrix to restore, got ",
                     state.size(), " values");
  }
  const auto points = static_cast<std::size_t>(state[1]);
  if (state.size() < 2 + 9 * points + 1) throw make_error("WarpPreconditioner: too few values to restore: ", state.size());
  const auto matrix = state.subspan(2 + 9 * points);
  const std::size_t length = 2 + 9 * points + carried_bits::matrix_length(matrix, 3 * state[1], "WarpPreconditioner");
  if (state.size() != length) {
    throw make_error("WarpPreconditioner: expected ", length, " values to restore, got ", state.size());
  }
  carried_bits::read_matrix<Real>(matrix, 3 * state[1], "WarpPreconditioner");
}

template <class Real>
void WarpPreconditioner<Real>::restore_carried_state(std::span<const std::int64_t> state) {
  check_carried_state(state);
  const auto points = static_cast<std::size_t>(state[1]);
  std::vector<Mat3<Real>> rotations(points);
  std::size_t k = 2;
  for (auto& block : rotations) {
    for (int c = 0; c < 9; ++c) block.data()[c] = carried_bits::from_bits<Real>(state[k++]);
  }
  Eigen::SparseMatrix<Real> matrix = carried_bits::read_matrix<Real>(state.subspan(k), 3 * state[1], "WarpPreconditioner");
  if (matrix.nonZeros() > 0 && !factorisation_.factorise(matrix)) {
    throw make_error("WarpPreconditioner: the restored matrix could not be factorised");
  }
  counter_ = static_cast<int>(state[0]);
  rotations_ = std::move(rotations);
  assembled_ = std::move(matrix);
}

template class WarpPreconditioner<float>;
template class WarpPreconditioner<double>;

}  // namespace fastcorot
