// SOFA's WarpPreconditioner on its RotationMatrixSystem, for PCGLinearSolver: a direct solver
// (here the LDL^T factorisation, as SparseLDLSolver and SOFA's other exact direct solvers) of a
// matrix A_a assembled at some builds, applied in the rotated frame, z = R A_a^-1 R^T r, R block
// diagonal with one 3×3 block per point. RotationMatrixSystem keeps a counter, set to its
// assemblingRate at the start: at each build it adds one, and when the counter reaches the rate it
// assembles A_a from the current system matrix (with the projective constraints), which the direct
// solver factorises again, sets the counter to 0 and R to the identity; at the builds in between it
// takes R from the rotation finder (rotation_finder.h: the first TetrahedronFEMForceField or
// HexahedronFEMForceField), the points' rotations from their rest frames, the matrix staying A_a.
// With the rate 1 (SOFA's default) every build assembles and P is the exact inverse.
#pragma once

#include "fastcorot/sim/preconditioning_solver.h"
#include "fastcorot/sim/sparse_factorisation.h"

#include <Eigen/SparseCore>

#include <vector>

namespace fastcorot {

template <class Real>
class WarpPreconditioner final : public PreconditioningSolver<Real> {
 public:
  struct Parameters {
    int assembling_rate = 1;  // RotationMatrixSystem's assemblingRate (SOFA's default 1)
  };

  // Throws fastcorot::Error for assembling_rate < 1.
  explicit WarpPreconditioner(Parameters parameters);

  std::string_view component() const override { return "WarpPreconditioner"; }
  // Throws fastcorot::Error when the assembled matrix cannot be factorised.
  void build(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors) override;
  // Throws fastcorot::Error when `size` is not 3 × the points of the last build.
  void apply(const Real* r, Real* z, Index size) const override;

  // The counter, R and A_a.
  std::vector<std::int64_t> carried_state() const override;
  void check_carried_state(std::span<const std::int64_t> state) const override;
  void restore_carried_state(std::span<const std::int64_t> state) override;

  const Parameters& parameters() const { return parameters_; }
  std::span<const Mat3<Real>> rotations() const { return rotations_; }

 private:
  Parameters parameters_;
  int counter_;
  std::vector<Mat3<Real>> rotations_;
  Eigen::SparseMatrix<Real> assembled_;
  SparseFactorisation<Real> factorisation_;
  std::vector<Mat3<Real>> initial_rotations_;  // HexahedronFEMForceField's, computed once
  mutable std::vector<Real> turned_, solved_;
};

}  // namespace fastcorot
