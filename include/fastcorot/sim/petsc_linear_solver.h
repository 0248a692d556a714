// The assembled system solved by PETSc (the PETScLinearSolver scene component): a Krylov solver
// (KSP) with a preconditioner (PC), by default conjugate gradients with PETSc's algebraic multigrid
// GAMG, told the rigid-body modes of the rest shape (its near-null space, which elasticity needs
// for mesh-independent convergence). PETSc's options database (the command line's -ksp_* and
// -pc_* options) overrides the component's settings, as in any PETSc program.
//
// The matrix is assembled from the same 3x3 blocks as MechanicalSystem::assemble, in the same
// order, into PETSc's compressed rows; its pattern, and GAMG's aggregates and interpolation with it,
// are built at the first solve and reused while the pattern holds (same points, tetrahedra and
// fixed points). The coarse operators (GAMG's Galerkin products, most of its set-up) are
// recomputed from the current matrix every rebuild_every solves: the corotational stiffness changes
// only with the rotations, so a preconditioner a few steps old still preconditions well, and every
// solve meets its tolerance against the current matrix all the same. In a distributed run (sim/distribution.h) the matrix and
// vectors are MPI objects with each rank's owned points as its rows.
#pragma once

#include "fastcorot/sim/linear_solver.h"

#include <memory>
#include <string>

namespace fastcorot {

class Distribution;

class PetscLinearSolver final : public LinearSolver<double> {
 public:
  struct Parameters {
    std::string ksp = "cg";    // PETSc KSPType
    std::string pc = "gamg";   // PETSc PCType
    double tolerance = 1e-8;   // relative residual |b - A x| / |b| at which the solve stops
    int max_iterations = 1000;
    bool near_null_space = true;  // give the preconditioner the rigid-body modes
    // Rebuild the preconditioner from the current matrix every this many solves; in between it
    // is the last one built (the solve still meets the tolerance against the current matrix).
    int rebuild_every = 10;
  };

  // Initialises PETSc if it is not yet. Throws fastcorot::Error for a bad parameter, and in a
  // build without PETSc.
  explicit PetscLinearSolver(Parameters parameters);
  ~PetscLinearSolver() override;

  // Throws fastcorot::Error naming PETSc's reason when the solve does not converge (a negative
  // KSPConvergedReason: too many iterations, a breakdown, an indefinite preconditioner), or for an
  // unknown solver or preconditioner type.
  LinearSolveReport solve(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                          std::span<const Vec3<double>> rhs, std::span<Vec3<double>> x) override;

  // The solves since the preconditioner was last rebuilt, so that a resumed run rebuilds it on the
  // same solves as the uninterrupted one. A resumed run still builds GAMG's interpolation from the
  // matrix of its first solve (the uninterrupted one from its first solve's): it matches the
  // uninterrupted run to the solver's tolerance, not bitwise.
  std::vector<std::int64_t> carried_state() const override;
  void restore_carried_state(const std::vector<std::int64_t>& state) override;

  // Makes the solver distributed (before the first solve): rows and vectors follow `distribution`.
  void distribute(std::shared_ptr<const Distribution> distribution);

  const Parameters& parameters() const { return parameters_; }
  // How many times the matrix pattern and the preconditioner's hierarchy were built (for tests
  // and the docs' claim that they are reused).
  int pattern_builds() const;
  // Bytes held by PETSc's matrix on this rank after the last solve (0 before).
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  Parameters parameters_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fastcorot
