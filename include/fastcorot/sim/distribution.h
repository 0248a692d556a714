// One object of a distributed run (`mpirun -np N fastcorot run scene.scn`, docs/scaling.md) across
// the MPI ranks. Every rank reads the whole scene; the tetrahedra are then partitioned with METIS
// (rank 0 partitions, every rank gets the same parts) and each rank keeps only its own part's
// elements: its force fields' per-element data (rest shape, rotations, stiffness) and the masses
// they give shrink to that part. A point belongs to the lowest rank whose tetrahedra touch it (rank 0
// for a point no tetrahedron touches); the other ranks touching it hold a ghost copy. Forces and
// products are partial sums at shared points until sum_shared() completes them through PETSc's
// ghosted vectors, after which every copy holds the same bits; the PETSc solver's rows are each
// rank's own points, numbered rank by rank. Outputs gather the state on rank 0 (gather()).
#pragma once

#include "fastcorot/sim/mechanical_system.h"
#include "fastcorot/sim/simulation.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

class Distribution final : public PointExchange<double> {
 public:
  // Partitions `mesh` (the tetrahedra of `system`'s force fields) over the ranks and lays out the
  // points; collective. Throws fastcorot::Error (on every rank) for more ranks than tetrahedra.
  Distribution(const MechanicalSystem<double>& system, const TetMesh& mesh);
  ~Distribution() override;

  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  // The part (rank) of each tetrahedron of the mesh as it was partitioned.
  std::span<const int> element_parts() const { return element_part_; }
  bool owns(Index point) const { return owner_[static_cast<std::size_t>(point)] == rank_; }
  // This rank's points in PETSc's order (its rows are first_row() .. first_row() + size - 1).
  std::span<const Index> owned_points() const { return owned_; }
  std::span<const Index> ghost_points() const { return ghosts_; }
  std::int64_t first_row() const { return first_row_; }
  std::int64_t total_points() const { return static_cast<std::int64_t>(owner_.size()); }
  // PETSc's block row of every point of the object.
  std::span<const std::int64_t> rows() const { return row_; }
  // Per owned point: how many 3x3 blocks its block row has in the columns of this rank's own points
  // and in the others' (PETSc's preallocation), from the whole mesh.
  std::span<const std::int64_t> diagonal_blocks() const { return diagonal_blocks_; }
  std::span<const std::int64_t> off_diagonal_blocks() const { return off_diagonal_blocks_; }

  void sum_shared(std::span<Vec3<double>> values) const override;
  // The two halves of sum_shared (collective): each owned point gets the sum of every rank's copy
  // (ghost copies are left as they were); each ghost copy gets its owner's value.
  void add_to_owners(std::span<Vec3<double>> values) const;
  void fill_ghosts(std::span<Vec3<double>> values) const;
  double sum(double value) const override;
  // Every point's value, from its owner, into `full` on rank 0 (#points long there; ignored
  // elsewhere). Collective.
  void gather(std::span<const Vec3<double>> values, std::span<Vec3<double>> full) const;
  // What sum_shared sends from this rank: ghost points times 3 doubles, twice (there and back).
  std::size_t bytes_sent_per_exchange() const { return 2 * ghosts_.size() * 3 * sizeof(double); }

 private:
  struct Ghosts;
  int rank_ = 0, ranks_ = 1;
  std::vector<int> element_part_;
  std::vector<int> owner_;
  std::vector<Index> owned_, ghosts_;
  std::vector<std::int64_t> row_;
  std::int64_t first_row_ = 0;
  std::vector<std::int64_t> diagonal_blocks_, off_diagonal_blocks_;
  std::unique_ptr<Ghosts> ghost_vector_;
};

// Distributes `object` over the ranks of this run (collective): partitions its mesh, removes the
// other ranks' tetrahedra from its system (the masses that follow the mesh follow; other masses
// and constant forces stay with the points' owners), installs the exchange, and hands the layout to
// its PETScLinearSolver. Rank 0 keeps the whole mesh as object.mesh for the outputs. Throws
// fastcorot::Error when the object is not one a distributed run can take (it names what: the
// solver, couplings, topological changes, a consistent mass on another mesh).
std::shared_ptr<Distribution> distribute(SimulatedObject<double>& object);

}  // namespace fastcorot
