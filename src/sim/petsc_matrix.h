// The PETSc solver's assembled matrix (petsc_linear_solver.h): the system matrix of
// MechanicalSystem::assemble as a PETSc AIJ matrix (block size 3), one process or distributed.
//
// Its pattern is built once per pattern of the system (points, held points, tetrahedra) and its
// values are written in place: the same 3x3 blocks as assemble() (mass, then each force field's),
// added in the same order, with held (fixed or isolated) points' rows and columns cleared and 1 on
// their diagonal. On one process the blocks go straight into PETSc's compressed rows; in a
// distributed run (sim/distribution.h) each rank adds its tetrahedra's blocks into its local rows
// and PETSc sends those of rows owned elsewhere. Systems with partial projections or couplings go
// through assemble() itself (one process).
#pragma once

#include "fastcorot/sim/mechanical_system.h"

#include <petscmat.h>

#include <memory>
#include <vector>

namespace fastcorot {

class Distribution;

class PetscMatrix {
 public:
  // `distribution` null or of one rank: one process.
  explicit PetscMatrix(std::shared_ptr<const Distribution> distribution);
  ~PetscMatrix();
  PetscMatrix(const PetscMatrix&) = delete;
  PetscMatrix& operator=(const PetscMatrix&) = delete;

  // The pattern of `system`'s matrix (values zero), and the rigid-body modes of its rest shape as
  // the near-null space when `near_null_space`.
  void build(const MechanicalSystem<double>& system, bool near_null_space);
  // Writes the values of m M + b B + k K at the system's last linearisation.
  void fill(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors);
  // Pattern and values from assemble() (partial projections, couplings; one process).
  void build_general(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                     bool near_null_space);

  Mat mat() const { return matrix_; }
  bool distributed() const;
  MPI_Comm comm() const;
  // This rank's rows: its points in PETSc's order (all points on one process), three rows each.
  PetscInt owned() const;
  Index owned_point(PetscInt k) const;
  // Whether each point of the system is held (its row is the identity).
  const std::vector<bool>& held() const { return held_; }
  std::size_t memory_bytes() const;

 private:
  struct BlockRows;
  void release();
  void set_near_null_space(const MechanicalSystem<double>& system);
  void add_entries(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                   PetscScalar* values) const;
  PetscInt row_of(Index point) const;

  std::shared_ptr<const Distribution> distribution_;
  Mat matrix_ = nullptr;
  std::vector<bool> held_;
  std::unique_ptr<BlockRows> rows_;
  std::vector<PetscScalar> values_;  // distributed runs: the local rows before they go to PETSc
};

}  // namespace fastcorot
