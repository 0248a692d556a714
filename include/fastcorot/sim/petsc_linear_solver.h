// The implicit step's linear system solved by PETSc (the PETScLinearSolver scene component): a
// Krylov solver (KSP) with a preconditioner (PC), by default conjugate gradients with PETSc's
// algebraic multigrid GAMG, told the rigid-body modes of the rest shape (its near-null space, which
// elasticity needs for mesh-independent convergence). PETSc's options database (the command line's
// -ksp_* and -pc_* options) overrides the component's settings, as in any PETSc program.
//
// The Krylov solver's operator is, by default, fastcorot's matrix-free product
// (MechanicalSystem::multiply, threaded and vectorised, in a PETSc shell matrix): the exact current
// system. The preconditioner is built from the assembled matrix (sim/petsc_matrix.h), assembled
// only when the preconditioner is (re)built: at the first solve, and when a solve needs
// rebuild_growth times the iterations that the first solve with it needed (or on a fixed
// schedule, rebuild_every). The corotational stiffness changes only with the rotations, so a
// preconditioner of an earlier step still preconditions well, and every solve meets its tolerance
// against the current system all the same. The pattern, and GAMG's aggregates and interpolation
// with it, are built at the first solve and reused while the pattern holds (same points,
// tetrahedra and held points); a rebuild recomputes GAMG's coarse operators (its Galerkin
// products). With matrix_free off, or with ksp "preonly" (the preconditioner is then the whole
// solve), the operator is the assembled matrix, assembled every solve. In a distributed run
// (sim/distribution.h) the matrices and vectors are MPI objects with each rank's owned points as
// its rows.
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
    // When the preconditioner is rebuilt from the current matrix (in between it is the last one
    // built, and the solve still meets the tolerance against the current system): after
    // rebuild_every solves (0: not on a schedule), and after a solve that needed rebuild_growth
    // times the iterations of the first solve with it, and 3 more (0: not on growth).
    int rebuild_every = 0;
    double rebuild_growth = 1.5;
    // The Krylov solver's operator is the matrix-free product (true) or the assembled matrix.
    bool matrix_free = true;
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

  // The rebuild cadence (solves since the last rebuild, the reference iterations, a rebuild
  // due), so that a resumed run rebuilds where the uninterrupted one would. A resumed run builds
  // its preconditioner (and GAMG's interpolation) at its first solve, so it matches the
  // uninterrupted run to the solver's tolerance, not bitwise.
  std::vector<std::int64_t> carried_state() const override;
  void restore_carried_state(const std::vector<std::int64_t>& state) override;

  // Makes the solver distributed (before the first solve): rows and vectors follow `distribution`.
  void distribute(std::shared_ptr<const Distribution> distribution);

  const Parameters& parameters() const { return parameters_; }
  // Whether the last solve's operator was the matrix-free product.
  bool matrix_free() const;
  // How many times the matrix pattern and the preconditioner's hierarchy were built (for tests
  // and the docs' claim that they are reused).
  int pattern_builds() const;
  // How many times the preconditioner was built or rebuilt from the current matrix.
  int preconditioner_builds() const;
  // Bytes held by PETSc's matrix on this rank after the last solve (0 before).
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  Parameters parameters_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fastcorot
