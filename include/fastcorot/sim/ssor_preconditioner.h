// SOFA's SSORPreconditioner (symmetric successive over-relaxation) on the assembled system matrix
// A = D + L + U (diagonal, strictly lower and upper parts, with the projective constraints: a fixed
// point's rows and columns cleared, its diagonal 1), for PCGLinearSolver. z = P r in two sweeps
// over the scalar rows, as SOFA's CompressedRowSparseMatrix solve does them:
//   backward, j = n-1 .. 0:  z_j = (r_j - sum_(i>j) A_ji z_i) · omega / A_jj
//   forward,  j = 0 .. n-1:  z_j -= (sum_(i<j) A_ji z_i) · omega / A_jj
// then z *= 2 - omega when omega != 1; that is P = (2 - omega) (D/omega + L)^-1 (D/omega) (D/omega + U)^-1.
// SOFA's block form (template CompressedRowSparseMatrixMat3x3d) does the same sweeps but leaves
// out the final 2 - omega scaling (`scale_by_two_minus_omega` false).
#pragma once

#include "fastcorot/sim/preconditioning_solver.h"

#include <Eigen/SparseCore>

#include <vector>

namespace fastcorot {

template <class Real>
class SSORPreconditioner final : public PreconditioningSolver<Real> {
 public:
  struct Parameters {
    Real omega = 1;  // SOFA's default
    bool scale_by_two_minus_omega = true;  // false: SOFA's 3x3-block form
  };

  // Throws fastcorot::Error when omega is not in (0, 2).
  explicit SSORPreconditioner(Parameters parameters);

  std::string_view component() const override { return "SSORPreconditioner"; }
  // Assembles A and inverts its diagonal. Throws fastcorot::Error naming the point and axis of a
  // zero or non-finite diagonal entry in a row that is not all zero (an all-zero row, a point with
  // neither mass nor element, gets 1: P leaves it alone).
  void build(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors) override;
  // Throws fastcorot::Error when `size` is not the size of the built matrix.
  void apply(const Real* r, Real* z, Index size) const override;

  // The assembled matrix (empty before the first build).
  std::vector<std::int64_t> carried_state() const override;
  void check_carried_state(std::span<const std::int64_t> state) const override;
  void restore_carried_state(std::span<const std::int64_t> state) override;

  const Parameters& parameters() const { return parameters_; }
  const Eigen::SparseMatrix<Real, Eigen::RowMajor>& matrix() const { return rows_; }

 private:
  void set_matrix(const Eigen::SparseMatrix<Real>& matrix);

  Parameters parameters_;
  Eigen::SparseMatrix<Real, Eigen::RowMajor> rows_;
  std::vector<Real> inverse_diagonal_;
};

}  // namespace fastcorot
