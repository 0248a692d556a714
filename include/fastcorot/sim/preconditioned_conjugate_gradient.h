// Preconditioned conjugate gradient as SOFA's PCGLinearSolver computes it (docs/sofa-solvers.md §2.4),
// with the preconditioners of SOFA's JacobiPreconditioner (the inverse of the system matrix's
// diagonal) and BlockJacobiPreconditioner (the inverses of its 3×3 diagonal blocks), built from the
// matrix of the current step without assembling it, or a sparse direct solver (SparseLDLSolver and
// the others as preconditioner: the LDL^T factorisation of the assembled matrix, P = A^-1 at the
// step it was built, reused for update_step solves), or SOFA's PrecomputedWarpPreconditioner
// (P = R A0^-1 R^T: A0 the assembled matrix of the first solve, factorised once, R the block
// diagonal of TetrahedronFEMForceField's point rotations, node_rotations.h, taken again every
// update_step solves; the identity without such a force field), or a preconditioning solver of its
// own (Preconditioner::solver: SSORPreconditioner, WarpPreconditioner; preconditioning_solver.h),
// built on the same schedule:
//   r = b - A x0, z = P r, rho = r . z; while iteration <= iterations and rho > tolerance · b . b:
//   q = A w, alpha = rho / w . q, x += alpha w, r -= alpha q, z = P r, beta = (r . z) / rho, w = z + beta w
// with w = z first. Unlike CGLinearSolver it starts from its previous solution x0 (zero before the
// first solve): SOFA's ODE solvers hand it their solution vector, which keeps the last step's.
// The stopping test is on r . P r, not |r|, against tolerance · |b|^2 (not squared).
#pragma once

#include "fastcorot/sim/linear_solver.h"
#include "fastcorot/sim/preconditioning_solver.h"
#include "fastcorot/sim/sparse_factorisation.h"

#include <memory>
#include <string_view>
#include <vector>

namespace fastcorot {

enum class Preconditioner { none, jacobi, block_jacobi, sparse_ldlt, precomputed_warp, solver };

// "none", "jacobi", "block_jacobi", "sparse_ldlt", "precomputed_warp", "solver".
std::string_view preconditioner_name(Preconditioner preconditioner);

template <class Real>
class PreconditionedConjugateGradientSolver final : public LinearSolver<Real> {
 public:
  struct Parameters {
    int iterations = 25;
    Real tolerance = Real(1e-5);
    Preconditioner preconditioner = Preconditioner::block_jacobi;
    // The preconditioner is rebuilt at the first solve and then every `update_step` solves (SOFA's
    // update_step / assemblingRate); in between it keeps the blocks of an earlier matrix.
    int update_step = 1;
    // precomputed_warp: false leaves R out (P = A0^-1), SOFA's use_rotations.
    bool warp_rotations = true;
    // Preconditioner::solver: the preconditioning solver (its component names it in messages).
    std::shared_ptr<PreconditioningSolver<Real>> solver;
  };

  // For systems of `points` points. Throws fastcorot::Error for iterations < 1, update_step < 1, a
  // negative or non-finite tolerance, points < 0, or Preconditioner::solver without a solver.
  PreconditionedConjugateGradientSolver(Parameters parameters, Index points);

  // Throws fastcorot::Error when the system does not have the solver's point count, when a
  // diagonal block (block_jacobi) or entry (jacobi) of the system matrix is singular or not finite,
  // naming the point, or when the assembled matrix cannot be factorised (sparse_ldlt,
  // precomputed_warp). A point whose
  // diagonal block is all zero (no mass, no element: its row of the matrix is zero) gets the
  // identity.
  LinearSolveReport solve(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                          std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override;
  // With the preconditioner of the last solve, from a zero guess; the solve count and the
  // previous solution (the next solve's guess) are left as they were.
  LinearSolveReport solve_again(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                                std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) override;

  const Parameters& parameters() const { return parameters_; }
  // The inverse blocks P applies (zero before the first solve).
  std::span<const Mat3<Real>> preconditioner_blocks() const { return inverse_; }

  // The solve count, the previous solution and, when the preconditioner outlives a solve
  // (update_step > 1, or always for precomputed_warp), its blocks or the assembled matrix it
  // factorised (and the warp's rotations), or the preconditioning solver's state, all as bit patterns: a resumed run continues bitwise
  // (the factorisation of the same matrix is the same).
  std::vector<std::int64_t> carried_state() const override;
  void restore_carried_state(const std::vector<std::int64_t>& state) override;
  // Its length depends on whether a matrix has been factorised yet (sparse_ldlt, update_step > 1).
  void check_carried_state(const std::vector<std::int64_t>& state) const override;

 private:
  void build_preconditioner(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors);
  // Whether the carried state holds the factorised matrix, the warp's rotations, the blocks.
  bool carries_matrix() const;
  bool carries_rotations() const;
  bool carries_blocks() const;
  // The factorised matrix in carried state (what follows the previous solution), checked; an empty
  // matrix when none had been factorised.
  Eigen::SparseMatrix<Real> carried_matrix(std::span<const std::int64_t> state) const;

  Parameters parameters_;
  std::int64_t solves_ = 0;
  bool reuse_preconditioner_ = false;  // solve_again
  std::vector<Vec3<Real>> previous_;  // the last solution: the next solve's start
  std::vector<Mat3<Real>> inverse_;   // P, one block per point (Jacobi, block-Jacobi)
  SparseFactorisation<Real> factorisation_;  // P = A^-1 (sparse_ldlt)
  Eigen::SparseMatrix<Real> factorised_;     // its A, kept for checkpoints when it outlives a solve
  std::vector<Mat3<Real>> rotations_;        // R (precomputed_warp), one block per point
  std::vector<Vec3<Real>> r_, w_, q_, s_, t_;
};

}  // namespace fastcorot
