#include "fastcorot/sim/distribution.h"

#include "block_pattern.h"
#include "fastcorot/core/error.h"
#include "fastcorot/sim/ode_solver.h"
#include "fastcorot/sim/petsc_linear_solver.h"
#include "fastcorot/sim/petsc_runtime.h"
#include "petsc_check.h"

#include <metis.h>
#include <petscvec.h>

#include <algorithm>
#include <limits>

namespace fastcorot {

// PETSc's ghosted vector for sum_shared (owned points then ghosts, 3 values each) and the
// scatter of a global vector to rank 0 for gather().
struct Distribution::Ghosts {
  Vec ghosted = nullptr;
  Vec global = nullptr, on_zero = nullptr;
  VecScatter to_zero = nullptr;
  ~Ghosts() {
    if (to_zero) VecScatterDestroy(&to_zero);
    if (on_zero) VecDestroy(&on_zero);
    if (global) VecDestroy(&global);
    if (ghosted) VecDestroy(&ghosted);
  }
};

namespace {

// METIS's parts of the tetrahedra (elements sharing a face are neighbours), on rank 0, sent to all.
std::vector<int> partition_tetrahedra(const TetMesh& mesh, int parts) {
  const Index elements = mesh.num_tetrahedra();
  std::vector<int> part(static_cast<std::size_t>(elements), 0);
  if (parts == 1) return part;
  if (process_rank() == 0) {
    std::vector<idx_t> start(static_cast<std::size_t>(elements) + 1), vertices;
    vertices.reserve(4 * static_cast<std::size_t>(elements));
    for (Index t = 0; t < elements; ++t) {
      for (Index v : mesh.tetrahedra()[static_cast<std::size_t>(t)]) vertices.push_back(static_cast<idx_t>(v));
      start[static_cast<std::size_t>(t) + 1] = static_cast<idx_t>(vertices.size());
    }
    idx_t ne = static_cast<idx_t>(elements), nn = static_cast<idx_t>(mesh.num_points()), common = 3,
          nparts = static_cast<idx_t>(parts), cut = 0;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1;  // the same parts on every run
    std::vector<idx_t> element_part(static_cast<std::size_t>(elements)), point_part(static_cast<std::size_t>(nn));
    const int status = METIS_PartMeshDual(&ne, &nn, start.data(), vertices.data(), nullptr, nullptr, &common, &nparts,
                                          nullptr, options, &cut, element_part.data(), point_part.data());
    if (status != METIS_OK) part.assign(part.size(), -1);
    else std::copy(element_part.begin(), element_part.end(), part.begin());
  }
  MPI_Bcast(part.data(), static_cast<int>(part.size()), MPI_INT, 0, PETSC_COMM_WORLD);
  if (!part.empty() && part.front() < 0) throw make_error("METIS could not partition the ", elements, " tetrahedra into ", parts, " parts");
  return part;
}

}  // namespace

Distribution::Distribution(const MechanicalSystem<double>& system, const TetMesh& mesh)
    : rank_(process_rank()), ranks_(process_count()) {
  const Index elements = mesh.num_tetrahedra();
  if (elements < ranks_) {
    throw make_error("distributed run on ", ranks_, " ranks: the mesh has only ", elements,
                     " tetrahedra (at most one rank per tetrahedron; run on fewer ranks)");
  }
  element_part_ = partition_tetrahedra(mesh, ranks_);
  const std::size_t n = static_cast<std::size_t>(system.size());
  owner_.assign(n, std::numeric_limits<int>::max());
  std::vector<bool> local(n, false);
  for (Index t = 0; t < elements; ++t) {
    const int part = element_part_[static_cast<std::size_t>(t)];
    for (Index v : mesh.tetrahedra()[static_cast<std::size_t>(t)]) {
      auto& owner = owner_[static_cast<std::size_t>(v)];
      owner = std::min(owner, part);
      if (part == rank_) local[static_cast<std::size_t>(v)] = true;
    }
  }
  for (auto& owner : owner_) {
    if (owner == std::numeric_limits<int>::max()) owner = 0;
  }
  // Rows rank by rank, each rank's points in increasing index.
  std::vector<std::int64_t> first(static_cast<std::size_t>(ranks_) + 1, 0);
  for (int owner : owner_) ++first[static_cast<std::size_t>(owner) + 1];
  for (int r = 0; r < ranks_; ++r) first[static_cast<std::size_t>(r) + 1] += first[static_cast<std::size_t>(r)];
  first_row_ = first[static_cast<std::size_t>(rank_)];
  row_.resize(n);
  std::vector<std::int64_t> next(first.begin(), first.end() - 1);
  for (std::size_t p = 0; p < n; ++p) {
    row_[p] = next[static_cast<std::size_t>(owner_[p])]++;
    if (owner_[p] == rank_) owned_.push_back(static_cast<Index>(p));
    else if (local[p]) ghosts_.push_back(static_cast<Index>(p));
  }
  // Preallocation from the whole mesh: an owned row has blocks from other ranks' tetrahedra too.
  const std::vector<std::vector<Index>> pattern = sim_detail::block_pattern(system, sim_detail::held_points(system));
  for (Index p : owned_) {
    std::int64_t diagonal = 0, off = 0;
    for (Index q : pattern[static_cast<std::size_t>(p)]) (owner_[static_cast<std::size_t>(q)] == rank_ ? diagonal : off) += 1;
    diagonal_blocks_.push_back(diagonal);
    off_diagonal_blocks_.push_back(off);
  }
  ghost_vector_ = std::make_unique<Ghosts>();
  std::vector<PetscInt> ghost_rows;
  for (Index g : ghosts_) ghost_rows.push_back(static_cast<PetscInt>(row_[static_cast<std::size_t>(g)]));
  const PetscInt owned = static_cast<PetscInt>(owned_.size());
  petsc_check(VecCreateGhostBlock(PETSC_COMM_WORLD, 3, 3 * owned, PETSC_DECIDE, static_cast<PetscInt>(ghost_rows.size()),
                                  ghost_rows.data(), &ghost_vector_->ghosted),
              "ghosted vector");
  petsc_check(VecCreateMPI(PETSC_COMM_WORLD, 3 * owned, PETSC_DECIDE, &ghost_vector_->global), "vector");
  petsc_check(VecScatterCreateToZero(ghost_vector_->global, &ghost_vector_->to_zero, &ghost_vector_->on_zero), "scatter");
}

Distribution::~Distribution() = default;

namespace {

enum class Part { owned, ghosts, both };
enum class Direction { into_vector, out_of_vector };

// Copies the values of `part` of the points between `values` and the local form of a ghosted
// vector (owned points, then ghosts, three values each).
void copy_ghosted(Vec ghosted, std::span<Vec3<double>> values, const std::vector<Index>& owned,
                  const std::vector<Index>& ghosts, Part part, Direction direction) {
  Vec local = nullptr;
  petsc_check(VecGhostGetLocalForm(ghosted, &local), "ghosted vector");
  PetscScalar* a = nullptr;
  VecGetArray(local, &a);
  const auto copy = [&](const std::vector<Index>& points, std::size_t k) {
    for (Index p : points) {
      Vec3<double>& value = values[static_cast<std::size_t>(p)];
      for (int d = 0; d < 3; ++d) {
        if (direction == Direction::into_vector) a[3 * k + static_cast<std::size_t>(d)] = value[d];
        else value[d] = a[3 * k + static_cast<std::size_t>(d)];
      }
      ++k;
    }
  };
  if (part != Part::ghosts) copy(owned, 0);
  if (part != Part::owned) copy(ghosts, owned.size());
  VecRestoreArray(local, &a);
  VecGhostRestoreLocalForm(ghosted, &local);
}

void scatter(Vec ghosted, InsertMode mode, ScatterMode direction) {
  petsc_check(VecGhostUpdateBegin(ghosted, mode, direction), "ghost exchange");
  petsc_check(VecGhostUpdateEnd(ghosted, mode, direction), "ghost exchange");
}

}  // namespace

void Distribution::sum_shared(std::span<Vec3<double>> values) const {
  add_to_owners(values);
  fill_ghosts(values);
}

void Distribution::add_to_owners(std::span<Vec3<double>> values) const {
  if (ranks_ == 1) return;
  Vec ghosted = ghost_vector_->ghosted;
  copy_ghosted(ghosted, values, owned_, ghosts_, Part::both, Direction::into_vector);
  scatter(ghosted, ADD_VALUES, SCATTER_REVERSE);
  copy_ghosted(ghosted, values, owned_, ghosts_, Part::owned, Direction::out_of_vector);
}

void Distribution::fill_ghosts(std::span<Vec3<double>> values) const {
  if (ranks_ == 1) return;
  Vec ghosted = ghost_vector_->ghosted;
  copy_ghosted(ghosted, values, owned_, ghosts_, Part::owned, Direction::into_vector);
  scatter(ghosted, INSERT_VALUES, SCATTER_FORWARD);
  copy_ghosted(ghosted, values, owned_, ghosts_, Part::ghosts, Direction::out_of_vector);
}

double Distribution::sum(double value) const {
  if (ranks_ == 1) return value;
  double total = 0;
  MPI_Allreduce(&value, &total, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return total;
}

void Distribution::gather(std::span<const Vec3<double>> values, std::span<Vec3<double>> full) const {
  Ghosts& g = *ghost_vector_;
  PetscScalar* a = nullptr;
  VecGetArray(g.global, &a);
  for (std::size_t k = 0; k < owned_.size(); ++k) {
    const Vec3<double>& value = values[static_cast<std::size_t>(owned_[k])];
    for (int d = 0; d < 3; ++d) a[3 * k + static_cast<std::size_t>(d)] = value[d];
  }
  VecRestoreArray(g.global, &a);
  petsc_check(VecScatterBegin(g.to_zero, g.global, g.on_zero, INSERT_VALUES, SCATTER_FORWARD), "gather");
  petsc_check(VecScatterEnd(g.to_zero, g.global, g.on_zero, INSERT_VALUES, SCATTER_FORWARD), "gather");
  if (rank_ != 0) return;
  const PetscScalar* all = nullptr;
  VecGetArrayRead(g.on_zero, &all);
  for (std::size_t p = 0; p < row_.size(); ++p) {
    const auto at = static_cast<std::size_t>(3 * row_[p]);
    full[p] = {all[at], all[at + 1], all[at + 2]};
  }
  VecRestoreArrayRead(g.on_zero, &all);
}

std::shared_ptr<Distribution> distribute(SimulatedObject<double>& object) {
  MechanicalSystem<double>& system = object.system;
  const std::string& name = object.path;
  auto* solver = dynamic_cast<PetscLinearSolver*>(object.linear_solver.get());
  if (!solver) {
    throw make_error(name, ": a distributed run needs PETScLinearSolver as the object's linear solver (docs/scaling.md)");
  }
  if (!dynamic_cast<ImplicitEulerSolver<double>*>(object.ode_solver.get())) {
    throw make_error(name, ": a distributed run integrates with EulerImplicitSolver only (run other solvers on one process)");
  }
  if (!object.mesh || system.force_fields.empty()) throw make_error(name, ": a distributed run needs tetrahedra to share out");
  TetMesh& mesh = *object.mesh;
  for (const auto& field : system.force_fields) {
    if (&field->mesh() != &mesh) {
      throw make_error(name, ": ", field->component(), " is on other elements than the object's tetrahedra; a distributed "
                       "run shares out one mesh");
    }
  }
  if (!system.projections.empty() || !system.couplings.empty() || !system.motions.empty() || !system.linear_movements.empty()) {
    throw make_error(name, ": partial, attached or moving projective constraints are not supported in a distributed run");
  }
  if (!object.topology_scripts.empty()) throw make_error(name, ": topological changes are not supported in a distributed run");
  const bool follows = system.mass.size() == 0 || system.mass.follows(mesh);
  if (!follows && !system.mass.is_lumped()) {
    throw make_error(name, ": a consistent mass that does not come from the tetrahedra is not supported in a distributed run");
  }
  auto distribution = std::make_shared<Distribution>(system, mesh);
  const int rank = distribution->rank();
  // Point-wise masses and forces stay with each point's owner; masses of the tetrahedra follow them.
  if (!follows) {
    std::vector<double> masses(system.mass.vertex_masses().begin(), system.mass.vertex_masses().end());
    for (std::size_t p = 0; p < masses.size(); ++p) {
      if (!distribution->owns(static_cast<Index>(p))) masses[p] = 0;
    }
    system.mass = Mass<double>::lumped(std::move(masses));
  }
  for (auto& constant : system.constant_forces) {
    ConstantForce<double> kept;
    for (std::size_t i = 0; i < constant.indices.size(); ++i) {
      if (distribution->owns(constant.indices[i])) {
        kept.indices.push_back(constant.indices[i]);
        kept.forces.push_back(constant.forces[i]);
      }
    }
    constant = std::move(kept);
  }
  std::shared_ptr<TetMesh> whole = rank == 0 ? std::make_shared<TetMesh>(mesh) : nullptr;
  std::vector<Index> others;
  for (std::size_t t = 0; t < distribution->element_parts().size(); ++t) {
    if (distribution->element_parts()[t] != rank) others.push_back(static_cast<Index>(t));
  }
  system.remove_tetrahedra(mesh, others);
  system.exchange = distribution;
  solver->distribute(distribution);
  if (whole) object.mesh = whole;
  return distribution;
}

}  // namespace fastcorot
