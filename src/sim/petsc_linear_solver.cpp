#include "fastcorot/sim/petsc_linear_solver.h"

#include "block_pattern.h"
#include "fastcorot/core/error.h"
#include "fastcorot/sim/distribution.h"
#include "fastcorot/sim/petsc_runtime.h"
#include "petsc_check.h"

#include <petscksp.h>

#include <algorithm>
#include <cmath>

namespace fastcorot {

namespace {

// The value of a PETSc option of the options database ("" when not given).
std::string option_value(const char* name) {
  char value[256] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, name, value, sizeof value, &set);
  return set ? std::string(value) : std::string();
}

bool option_given(const char* name) {
  PetscBool set = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, name, &set);
  return set == PETSC_TRUE;
}

// Sets the solver and preconditioner types and tolerances, then PETSc's options over them.
void configure(KSP ksp, const PetscLinearSolver::Parameters& parameters) {
  if (KSPSetType(ksp, parameters.ksp.c_str()) != 0) {
    throw make_error("unknown ksp \"", parameters.ksp, "\" (PETSc's KSP types: cg, gmres, minres, ...)");
  }
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp, &pc), "preconditioner");
  if (PCSetType(pc, parameters.pc.c_str()) != 0) {
    throw make_error("unknown pc \"", parameters.pc, "\" (PETSc's PC types: gamg, jacobi, bjacobi, ilu, ...)");
  }
  // GAMG's aggregates and interpolation depend on the pattern and the rest shape, not on the
  // rotations: they are built once per pattern and reused; the coarse operators are recomputed.
  PCGAMGSetReuseInterpolation(pc, PETSC_TRUE);
  petsc_check(KSPSetTolerances(ksp, parameters.tolerance, PETSC_DEFAULT, PETSC_DEFAULT, parameters.max_iterations),
              "tolerances");
  if (KSPSetFromOptions(ksp) != 0) {
    for (const char* name : {"-ksp_type", "-pc_type"}) {
      if (const std::string value = option_value(name); !value.empty()) {
        throw make_error("PETSc option ", name, " ", value, ": unknown type (or a package this PETSc lacks)");
      }
    }
    petsc_check(1, "the -ksp_* and -pc_* options");
  }
  KSPType type = nullptr;
  KSPGetType(ksp, &type);
  // The tolerance is on the true residual, as for the other solvers here (CG's default norm
  // would be the preconditioned one).
  if (!option_given("-ksp_norm_type") && type && std::string(type) == KSPCG) {
    petsc_check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "norm type");
  }
}

}  // namespace

// The local matrix in compressed rows of 3x3 blocks: block row i holds the blocks of columns
// block_column[block_start[i] .. block_start[i + 1]), sorted; its values are three scalar rows of
// 3k entries each (k blocks), row after row, as PETSc's AIJ format stores them.
struct BlockRows {
  std::vector<PetscInt> block_start, block_column;
  std::vector<bool> held;

  Index points() const { return static_cast<Index>(block_start.size()) - 1; }
  PetscInt blocks(Index i) const { return block_start[static_cast<std::size_t>(i) + 1] - block_start[static_cast<std::size_t>(i)]; }
  // Offset of entry (r, s) of block (i, j) in the values.
  std::size_t offset(Index i, Index j, int r, int s) const {
    const auto first = block_column.begin() + block_start[static_cast<std::size_t>(i)];
    const auto last = block_column.begin() + block_start[static_cast<std::size_t>(i) + 1];
    const auto m = std::lower_bound(first, last, static_cast<PetscInt>(j)) - first;
    return static_cast<std::size_t>(9 * block_start[static_cast<std::size_t>(i)] + r * 3 * (last - first) + 3 * m + s);
  }
};

// Adds blocks into the values of BlockRows (held rows and columns are left out, as in assemble()).
class BlockRowSink final : public MatrixSink<double> {
 public:
  BlockRowSink(const BlockRows& rows, PetscScalar* values) : rows_(rows), values_(values) {}
  void add_block(Index row, Index col, const Mat3<double>& block) override {
    const Index i = row / 3, j = col / 3;
    if (rows_.held[static_cast<std::size_t>(i)] || rows_.held[static_cast<std::size_t>(j)]) return;
    const std::size_t at = rows_.offset(i, j, 0, 0);
    const std::size_t stride = static_cast<std::size_t>(3 * rows_.blocks(i));
    for (int r = 0; r < 3; ++r) {
      for (int s = 0; s < 3; ++s) values_[at + static_cast<std::size_t>(r) * stride + static_cast<std::size_t>(s)] += block(r, s);
    }
  }

 private:
  const BlockRows& rows_;
  PetscScalar* values_;
};

struct PetscLinearSolver::Impl {
  std::shared_ptr<const Distribution> distribution;
  Mat matrix = nullptr;
  KSP ksp = nullptr;
  Vec rhs = nullptr, solution = nullptr;
  BlockRows rows;
  std::vector<PetscScalar> values;  // distributed runs: the local rows before they go to PETSc
  // What the pattern was built for: point count, held points, tetrahedra of each force field.
  std::vector<Index> pattern_key;
  int builds = 0;
  long solves_since_setup = 0;  // solves since the preconditioner was last rebuilt

  ~Impl() { release(); }
  void release() {
    if (ksp) KSPDestroy(&ksp);
    if (matrix) MatDestroy(&matrix);
    if (rhs) VecDestroy(&rhs);
    if (solution) VecDestroy(&solution);
  }
  bool distributed() const { return distribution && distribution->ranks() > 1; }
  MPI_Comm comm() const { return distributed() ? PETSC_COMM_WORLD : PETSC_COMM_SELF; }
  PetscInt owned() const {
    return distribution ? static_cast<PetscInt>(distribution->owned_points().size()) : rows.points();
  }
  Index owned_point(PetscInt k) const {
    return distribution ? distribution->owned_points()[static_cast<std::size_t>(k)] : static_cast<Index>(k);
  }
  PetscInt row_of(Index point) const {
    return distribution ? static_cast<PetscInt>(distribution->rows()[static_cast<std::size_t>(point)]) : point;
  }

  static std::vector<Index> key_of(const MechanicalSystem<double>& system) {
    std::vector<Index> key{system.size(), static_cast<Index>(system.fixed.size()),
                           static_cast<Index>(system.isolated.size())};
    key.insert(key.end(), system.fixed.begin(), system.fixed.end());
    key.insert(key.end(), system.isolated.begin(), system.isolated.end());
    for (const auto& field : system.force_fields) key.push_back(field->mesh().num_tetrahedra());
    return key;
  }

  void build(const MechanicalSystem<double>& system, const Parameters& parameters) {
    release();
    // A new pattern (after a topological change) starts the cadence again; the first one keeps
    // the count a checkpoint restored.
    if (builds++ > 0) solves_since_setup = 0;
    rows.held = sim_detail::held_points(system);
    {
      const std::vector<std::vector<Index>> pattern = sim_detail::block_pattern(system, rows.held);
      rows.block_start.assign(1, 0);
      rows.block_column.clear();
      for (const auto& columns : pattern) {
        rows.block_start.push_back(rows.block_start.back() + static_cast<PetscInt>(columns.size()));
        rows.block_column.insert(rows.block_column.end(), columns.begin(), columns.end());
      }
      rows.block_column.shrink_to_fit();
    }
    const PetscInt n = owned();
    petsc_check(MatCreate(comm(), &matrix), "matrix");
    petsc_check(MatSetSizes(matrix, 3 * n, 3 * n, PETSC_DETERMINE, PETSC_DETERMINE), "matrix size");
    petsc_check(MatSetBlockSize(matrix, 3), "matrix block size");
    if (distributed()) {
      petsc_check(MatSetType(matrix, MATMPIAIJ), "matrix type");
      std::vector<PetscInt> diagonal(distribution->diagonal_blocks().begin(), distribution->diagonal_blocks().end());
      std::vector<PetscInt> off(distribution->off_diagonal_blocks().begin(), distribution->off_diagonal_blocks().end());
      petsc_check(MatXAIJSetPreallocation(matrix, 3, diagonal.data(), off.data(), nullptr, nullptr), "preallocation");
      values.assign(static_cast<std::size_t>(9 * rows.block_start.back()), 0.0);
    } else {
      // PETSc's compressed rows are the pattern itself: values are written in place each solve.
      // The pattern goes in block row by block row (zeros), without a second copy of the indices.
      petsc_check(MatSetType(matrix, MATSEQAIJ), "matrix type");
      std::vector<PetscInt> per_row;
      per_row.reserve(3 * static_cast<std::size_t>(rows.points()));
      for (Index i = 0; i < rows.points(); ++i) {
        for (int r = 0; r < 3; ++r) per_row.push_back(3 * rows.blocks(i));
      }
      petsc_check(MatSeqAIJSetPreallocation(matrix, 0, per_row.data()), "preallocation");
      std::vector<PetscScalar> zeros;
      for (Index i = 0; i < rows.points(); ++i) {
        const PetscInt k = rows.blocks(i);
        zeros.assign(static_cast<std::size_t>(9 * k), 0.0);
        const PetscInt row = i;
        petsc_check(MatSetValuesBlocked(matrix, 1, &row, k, rows.block_column.data() + rows.block_start[static_cast<std::size_t>(i)],
                                        zeros.data(), INSERT_VALUES),
                    "matrix pattern");
      }
      petsc_check(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY), "matrix pattern");
      petsc_check(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY), "matrix pattern");
    }
    petsc_check(MatSetOption(matrix, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "matrix option");
    petsc_check(MatCreateVecs(matrix, &solution, &rhs), "vectors");
    if (parameters.near_null_space) set_near_null_space(system);
    make_ksp(parameters);
  }

  // The rigid-body modes at the rest positions (three translations, three rotations).
  void set_near_null_space(const MechanicalSystem<double>& system) {
    Vec coordinates = nullptr;
    petsc_check(VecDuplicate(rhs, &coordinates), "coordinates");
    petsc_check(VecSetBlockSize(coordinates, 3), "coordinates");
    PetscScalar* c = nullptr;
    VecGetArray(coordinates, &c);
    for (PetscInt k = 0; k < owned(); ++k) {
      const Vec3<double>& p = system.state.rest_position[static_cast<std::size_t>(owned_point(k))];
      for (int d = 0; d < 3; ++d) c[3 * k + d] = p[d];
    }
    VecRestoreArray(coordinates, &c);
    MatNullSpace space = nullptr;
    petsc_check(MatNullSpaceCreateRigidBody(coordinates, &space), "rigid-body modes");
    petsc_check(MatSetNearNullSpace(matrix, space), "near-null space");
    MatNullSpaceDestroy(&space);
    VecDestroy(&coordinates);
  }

  void make_ksp(const Parameters& parameters) {
    petsc_check(KSPCreate(comm(), &ksp), "solver");
    petsc_check(KSPSetOperators(ksp, matrix, matrix), "solver operators");
    configure(ksp, parameters);
  }

  void fill(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors) {
    if (!distributed()) {
      PetscScalar* a = nullptr;
      petsc_check(MatSeqAIJGetArray(matrix, &a), "matrix values");
      const std::size_t count = static_cast<std::size_t>(9 * rows.block_start.back());
      std::fill(a, a + count, 0.0);
      add_entries(system, factors, a);
      petsc_check(MatSeqAIJRestoreArray(matrix, &a), "matrix values");
      return;
    }
    std::fill(values.begin(), values.end(), 0.0);
    add_entries(system, factors, values.data());
    petsc_check(MatZeroEntries(matrix), "matrix");
    std::vector<PetscInt> columns;
    for (Index i = 0; i < rows.points(); ++i) {
      const PetscInt k = rows.blocks(i);
      // A held point's identity comes once, from its owner; a point of no local block has none.
      if ((rows.held[static_cast<std::size_t>(i)] && !distribution->owns(i)) || (k == 1 && !touched(system, i))) continue;
      columns.resize(static_cast<std::size_t>(k));
      for (PetscInt m = 0; m < k; ++m) {
        columns[static_cast<std::size_t>(m)] = row_of(rows.block_column[static_cast<std::size_t>(rows.block_start[static_cast<std::size_t>(i)] + m)]);
      }
      const PetscInt row = row_of(i);
      petsc_check(MatSetValuesBlocked(matrix, 1, &row, k, columns.data(), values.data() + 9 * rows.block_start[static_cast<std::size_t>(i)],
                                      ADD_VALUES),
                  "matrix entries");
    }
    petsc_check(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY), "matrix assembly");
    petsc_check(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY), "matrix assembly");
  }

  // Whether point i has anything on this rank (a tetrahedron of its force fields or a mass).
  static bool touched(const MechanicalSystem<double>& system, Index i) {
    if (system.mass.size() != 0 && system.mass.vertex_masses()[static_cast<std::size_t>(i)] != 0) return true;
    for (const auto& field : system.force_fields) {
      if (!field->mesh().tetrahedra_around_vertex(i).empty()) return true;
    }
    return false;
  }

  void add_entries(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors, PetscScalar* a) {
    BlockRowSink sink(rows, a);
    if (system.mass.size() != 0) system.mass.add_to_matrix(sink, factors.m);
    for (const auto& field : system.force_fields) field->add_stiffness(sink, factors.k, 0, factors.b);
    for (Index i = 0; i < rows.points(); ++i) {
      if (!rows.held[static_cast<std::size_t>(i)]) continue;
      for (int d = 0; d < 3; ++d) a[rows.offset(i, i, d, d)] = 1.0;
    }
  }

  // Projections or couplings (rare in large scenes): the general assembly, one process.
  void fill_generally(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                      const Parameters& parameters) {
    Eigen::SparseMatrix<double, Eigen::RowMajor> a = system.assemble(factors);
    a.makeCompressed();
    release();
    ++builds;
    solves_since_setup = 0;
    rows.block_start.assign(static_cast<std::size_t>(system.size()) + 1, 0);
    std::vector<PetscInt> row_start(a.outerIndexPtr(), a.outerIndexPtr() + a.rows() + 1);
    std::vector<PetscInt> column(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
    petsc_check(MatCreate(PETSC_COMM_SELF, &matrix), "matrix");
    petsc_check(MatSetSizes(matrix, a.rows(), a.cols(), a.rows(), a.cols()), "matrix size");
    petsc_check(MatSetBlockSize(matrix, 3), "matrix block size");
    petsc_check(MatSetType(matrix, MATSEQAIJ), "matrix type");
    petsc_check(MatSeqAIJSetPreallocationCSR(matrix, row_start.data(), column.data(), a.valuePtr()), "matrix");
    petsc_check(MatCreateVecs(matrix, &solution, &rhs), "vectors");
    if (parameters.near_null_space) set_near_null_space(system);
    make_ksp(parameters);
  }
};

PetscLinearSolver::PetscLinearSolver(Parameters parameters) : parameters_(std::move(parameters)), impl_(std::make_unique<Impl>()) {
  if (!(parameters_.tolerance > 0) || !std::isfinite(parameters_.tolerance)) {
    throw make_error("tolerance ", parameters_.tolerance, ": must be > 0");
  }
  if (parameters_.max_iterations < 1) throw make_error("maxIterations ", parameters_.max_iterations, ": must be >= 1");
  if (parameters_.rebuild_every < 1) throw make_error("rebuildEvery ", parameters_.rebuild_every, ": must be >= 1");
  initialise_petsc();
  // The types and the command line's options are checked now, when the scene is built.
  KSP probe = nullptr;
  petsc_check(KSPCreate(PETSC_COMM_SELF, &probe), "solver");
  try {
    configure(probe, parameters_);
  } catch (const Error&) {
    KSPDestroy(&probe);
    throw;
  }
  KSPDestroy(&probe);
}

PetscLinearSolver::~PetscLinearSolver() = default;

void PetscLinearSolver::distribute(std::shared_ptr<const Distribution> distribution) {
  impl_->release();
  impl_->pattern_key.clear();
  impl_->distribution = std::move(distribution);
}

int PetscLinearSolver::pattern_builds() const { return impl_->builds; }

std::vector<std::int64_t> PetscLinearSolver::carried_state() const { return {impl_->solves_since_setup}; }

void PetscLinearSolver::restore_carried_state(const std::vector<std::int64_t>& state) {
  check_carried_state(state);
  if (state[0] < 0) throw make_error("PETScLinearSolver: a negative solve count, ", state[0]);
  impl_->solves_since_setup = static_cast<long>(state[0]);
}

std::size_t PetscLinearSolver::memory_bytes() const {
  if (!impl_->matrix) return 0;
  // Entries and their column indices, and the row starts (PETSc's own memory count is off unless
  // its memory logging is on).
  MatInfo info;
  MatGetInfo(impl_->matrix, MAT_LOCAL, &info);
  PetscInt rows = 0, columns = 0;
  MatGetLocalSize(impl_->matrix, &rows, &columns);
  return static_cast<std::size_t>(info.nz_allocated) * (sizeof(PetscScalar) + sizeof(PetscInt)) +
         static_cast<std::size_t>(rows + 1) * sizeof(PetscInt);
}

LinearSolveReport PetscLinearSolver::solve(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                                           std::span<const Vec3<double>> rhs, std::span<Vec3<double>> x) {
  Impl& impl = *impl_;
  const bool general = !system.projections.empty() || !system.couplings.empty();
  if (general && impl.distributed()) {
    throw make_error("PETScLinearSolver: partial projective constraints and attachments are not supported in a "
                     "distributed run (run on one process)");
  }
  {
    const PhaseTimer timer(system.timer_slot(&PhaseTimes::solver_vectors));  // assembly and set-up
    if (general) {
      impl.fill_generally(system, factors, parameters_);
    } else {
      std::vector<Index> key = Impl::key_of(system);
      if (!impl.matrix || key != impl.pattern_key) {
        impl.build(system, parameters_);
        impl.pattern_key = std::move(key);
      }
      impl.fill(system, factors);
    }
    PetscScalar* b = nullptr;
    petsc_check(VecGetArray(impl.rhs, &b), "right-hand side");
    for (PetscInt k = 0; k < impl.owned(); ++k) {
      const Vec3<double>& value = rhs[static_cast<std::size_t>(impl.owned_point(k))];
      for (int d = 0; d < 3; ++d) b[3 * k + d] = value[d];
    }
    petsc_check(VecRestoreArray(impl.rhs, &b), "right-hand side");
    petsc_check(KSPSetOperators(impl.ksp, impl.matrix, impl.matrix), "solver operators");
    const bool rebuild = impl.solves_since_setup % parameters_.rebuild_every == 0;
    petsc_check(KSPSetReusePreconditioner(impl.ksp, rebuild ? PETSC_FALSE : PETSC_TRUE), "preconditioner reuse");
    impl.solves_since_setup = rebuild ? 1 : impl.solves_since_setup + 1;
  }
  const int code = KSPSolve(impl.ksp, impl.rhs, impl.solution);
  if (code != 0) petsc_check(code, "solve (ksp " + parameters_.ksp + ", pc " + parameters_.pc + ")");
  KSPConvergedReason reason;
  KSPGetConvergedReason(impl.ksp, &reason);
  PetscInt iterations = 0;
  KSPGetIterationNumber(impl.ksp, &iterations);
  PetscReal residual = 0, rhs_norm = 0;
  KSPGetResidualNorm(impl.ksp, &residual);
  VecNorm(impl.rhs, NORM_2, &rhs_norm);
  const double relative = rhs_norm > 0 ? residual / rhs_norm : 0.0;
  if (reason < 0) {
    KSPType type = nullptr;
    PC pc = nullptr;
    PCType pc_type = nullptr;
    KSPGetType(impl.ksp, &type);
    KSPGetPC(impl.ksp, &pc);
    PCGetType(pc, &pc_type);
    throw make_error("PETScLinearSolver (ksp ", type ? type : "?", ", pc ", pc_type ? pc_type : "?", "): the solve did not converge: ",
                     KSPConvergedReasons[reason], " after ", iterations, " iterations (relative residual ", relative,
                     ", tolerance ", parameters_.tolerance, "); raise maxIterations (-ksp_max_it) or check the scene");
  }
  const PetscScalar* solution = nullptr;
  petsc_check(VecGetArrayRead(impl.solution, &solution), "solution");
  std::fill(x.begin(), x.end(), Vec3<double>::Zero());
  for (PetscInt k = 0; k < impl.owned(); ++k) {
    x[static_cast<std::size_t>(impl.owned_point(k))] = {solution[3 * k], solution[3 * k + 1], solution[3 * k + 2]};
  }
  VecRestoreArrayRead(impl.solution, &solution);
  // Ghost copies get their owners' values (owners' values plus zeros: the same bits).
  if (impl.distributed()) impl.distribution->sum_shared(x);
  return {static_cast<int>(iterations), relative};
}

}  // namespace fastcorot
