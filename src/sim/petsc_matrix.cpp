#include "petsc_matrix.h"

#include "block_pattern.h"
#include "fastcorot/sim/distribution.h"
#include "petsc_check.h"

#include <algorithm>

namespace fastcorot {

// The local matrix in compressed rows of 3x3 blocks: block row i holds the blocks of columns
// block_column[block_start[i] .. block_start[i + 1]), sorted; its values are three scalar rows of
// 3k entries each (k blocks), row after row, as PETSc's AIJ format stores them.
struct PetscMatrix::BlockRows {
  std::vector<PetscInt> block_start, block_column;

  Index points() const { return static_cast<Index>(block_start.size()) - 1; }
  PetscInt first(Index i) const { return block_start[static_cast<std::size_t>(i)]; }
  PetscInt blocks(Index i) const { return first(i + 1) - first(i); }
  // Offset of entry (r, s) of block (i, j) in the values.
  std::size_t offset(Index i, Index j, int r, int s) const {
    const auto begin = block_column.begin() + first(i);
    const auto end = block_column.begin() + first(i + 1);
    const auto m = std::lower_bound(begin, end, static_cast<PetscInt>(j)) - begin;
    return static_cast<std::size_t>(9 * first(i) + r * 3 * (end - begin) + 3 * m + s);
  }
};

namespace {

// Adds blocks into compressed block rows (held rows and columns are left out, as in assemble()).
template <class Rows>
class BlockRowSink final : public MatrixSink<double> {
 public:
  BlockRowSink(const Rows& rows, const std::vector<bool>& held, PetscScalar* values)
      : rows_(rows), held_(held), values_(values) {}
  void add_block(Index row, Index col, const Mat3<double>& block) override {
    const Index i = row / 3, j = col / 3;
    if (held_[static_cast<std::size_t>(i)] || held_[static_cast<std::size_t>(j)]) return;
    const std::size_t at = rows_.offset(i, j, 0, 0);
    const std::size_t stride = static_cast<std::size_t>(3 * rows_.blocks(i));
    for (int r = 0; r < 3; ++r) {
      for (int s = 0; s < 3; ++s) values_[at + static_cast<std::size_t>(r) * stride + static_cast<std::size_t>(s)] += block(r, s);
    }
  }

 private:
  const Rows& rows_;
  const std::vector<bool>& held_;
  PetscScalar* values_;
};

// Whether point i has anything on this rank (a tetrahedron of its force fields or a mass).
bool touched(const MechanicalSystem<double>& system, Index i) {
  if (system.mass.size() != 0 && system.mass.vertex_masses()[static_cast<std::size_t>(i)] != 0) return true;
  for (const auto& field : system.force_fields) {
    if (!field->mesh().tetrahedra_around_vertex(i).empty()) return true;
  }
  return false;
}

}  // namespace

PetscMatrix::PetscMatrix(std::shared_ptr<const Distribution> distribution)
    : distribution_(std::move(distribution)), rows_(std::make_unique<BlockRows>()) {}

PetscMatrix::~PetscMatrix() { release(); }

void PetscMatrix::release() {
  if (matrix_) MatDestroy(&matrix_);
}

bool PetscMatrix::distributed() const { return distribution_ && distribution_->ranks() > 1; }

MPI_Comm PetscMatrix::comm() const { return distributed() ? PETSC_COMM_WORLD : PETSC_COMM_SELF; }

PetscInt PetscMatrix::owned() const {
  return distribution_ ? static_cast<PetscInt>(distribution_->owned_points().size()) : rows_->points();
}

Index PetscMatrix::owned_point(PetscInt k) const {
  return distribution_ ? distribution_->owned_points()[static_cast<std::size_t>(k)] : static_cast<Index>(k);
}

PetscInt PetscMatrix::row_of(Index point) const {
  return distribution_ ? static_cast<PetscInt>(distribution_->rows()[static_cast<std::size_t>(point)]) : point;
}

void PetscMatrix::build(const MechanicalSystem<double>& system, bool near_null_space) {
  release();
  held_ = sim_detail::held_points(system);
  BlockRows& rows = *rows_;
  {
    const std::vector<std::vector<Index>> pattern = sim_detail::block_pattern(system, held_);
    rows.block_start.assign(1, 0);
    rows.block_column.clear();
    for (const auto& columns : pattern) {
      rows.block_start.push_back(rows.block_start.back() + static_cast<PetscInt>(columns.size()));
      rows.block_column.insert(rows.block_column.end(), columns.begin(), columns.end());
    }
    rows.block_column.shrink_to_fit();
  }
  const PetscInt n = owned();
  petsc_check(MatCreate(comm(), &matrix_), "matrix");
  petsc_check(MatSetSizes(matrix_, 3 * n, 3 * n, PETSC_DETERMINE, PETSC_DETERMINE), "matrix size");
  petsc_check(MatSetBlockSize(matrix_, 3), "matrix block size");
  if (distributed()) {
    petsc_check(MatSetType(matrix_, MATMPIAIJ), "matrix type");
    std::vector<PetscInt> diagonal(distribution_->diagonal_blocks().begin(), distribution_->diagonal_blocks().end());
    std::vector<PetscInt> off(distribution_->off_diagonal_blocks().begin(), distribution_->off_diagonal_blocks().end());
    petsc_check(MatXAIJSetPreallocation(matrix_, 3, diagonal.data(), off.data(), nullptr, nullptr), "preallocation");
    values_.assign(static_cast<std::size_t>(9 * rows.block_start.back()), 0.0);
  } else {
    // PETSc's compressed rows are the pattern itself: values are written in place each fill.
    // The pattern goes in block row by block row (zeros), without a second copy of the indices.
    petsc_check(MatSetType(matrix_, MATSEQAIJ), "matrix type");
    std::vector<PetscInt> per_row;
    per_row.reserve(3 * static_cast<std::size_t>(rows.points()));
    for (Index i = 0; i < rows.points(); ++i) {
      for (int r = 0; r < 3; ++r) per_row.push_back(3 * rows.blocks(i));
    }
    petsc_check(MatSeqAIJSetPreallocation(matrix_, 0, per_row.data()), "preallocation");
    std::vector<PetscScalar> zeros;
    for (Index i = 0; i < rows.points(); ++i) {
      const PetscInt k = rows.blocks(i);
      zeros.assign(static_cast<std::size_t>(9 * k), 0.0);
      const PetscInt row = i;
      petsc_check(MatSetValuesBlocked(matrix_, 1, &row, k, rows.block_column.data() + rows.first(i), zeros.data(),
                                      INSERT_VALUES),
                  "matrix pattern");
    }
    petsc_check(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY), "matrix pattern");
    petsc_check(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY), "matrix pattern");
  }
  petsc_check(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "matrix option");
  if (near_null_space) set_near_null_space(system);
}

void PetscMatrix::add_entries(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                              PetscScalar* values) const {
  const BlockRows& rows = *rows_;
  BlockRowSink<BlockRows> sink(rows, held_, values);
  if (system.mass.size() != 0) system.mass.add_to_matrix(sink, factors.m);
  for (const auto& field : system.force_fields) field->add_stiffness(sink, factors.k, 0, factors.b);
  for (Index i = 0; i < rows.points(); ++i) {
    if (!held_[static_cast<std::size_t>(i)]) continue;
    for (int d = 0; d < 3; ++d) values[rows.offset(i, i, d, d)] = 1.0;
  }
}

void PetscMatrix::fill(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors) {
  const BlockRows& rows = *rows_;
  if (!distributed()) {
    PetscScalar* a = nullptr;
    petsc_check(MatSeqAIJGetArray(matrix_, &a), "matrix values");
    std::fill(a, a + 9 * rows.block_start.back(), 0.0);
    add_entries(system, factors, a);
    petsc_check(MatSeqAIJRestoreArray(matrix_, &a), "matrix values");
    return;
  }
  std::fill(values_.begin(), values_.end(), 0.0);
  add_entries(system, factors, values_.data());
  petsc_check(MatZeroEntries(matrix_), "matrix");
  std::vector<PetscInt> columns;
  for (Index i = 0; i < rows.points(); ++i) {
    const PetscInt k = rows.blocks(i);
    // A held point's identity comes once, from its owner; a point of no local block has none.
    if ((held_[static_cast<std::size_t>(i)] && !distribution_->owns(i)) || (k == 1 && !touched(system, i))) continue;
    columns.resize(static_cast<std::size_t>(k));
    for (PetscInt m = 0; m < k; ++m) columns[static_cast<std::size_t>(m)] = row_of(rows.block_column[static_cast<std::size_t>(rows.first(i) + m)]);
    const PetscInt row = row_of(i);
    petsc_check(MatSetValuesBlocked(matrix_, 1, &row, k, columns.data(), values_.data() + 9 * rows.first(i), ADD_VALUES),
                "matrix entries");
  }
  petsc_check(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY), "matrix assembly");
  petsc_check(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY), "matrix assembly");
}

void PetscMatrix::build_general(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                                bool near_null_space) {
  Eigen::SparseMatrix<double, Eigen::RowMajor> a = system.assemble(factors);
  a.makeCompressed();
  release();
  held_ = sim_detail::held_points(system);
  rows_->block_start.assign(static_cast<std::size_t>(system.size()) + 1, 0);
  std::vector<PetscInt> row_start(a.outerIndexPtr(), a.outerIndexPtr() + a.rows() + 1);
  std::vector<PetscInt> column(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  petsc_check(MatCreate(PETSC_COMM_SELF, &matrix_), "matrix");
  petsc_check(MatSetSizes(matrix_, a.rows(), a.cols(), a.rows(), a.cols()), "matrix size");
  petsc_check(MatSetBlockSize(matrix_, 3), "matrix block size");
  petsc_check(MatSetType(matrix_, MATSEQAIJ), "matrix type");
  petsc_check(MatSeqAIJSetPreallocationCSR(matrix_, row_start.data(), column.data(), a.valuePtr()), "matrix");
  if (near_null_space) set_near_null_space(system);
}

// The rigid-body modes at the rest positions (three translations, three rotations).
void PetscMatrix::set_near_null_space(const MechanicalSystem<double>& system) {
  Vec coordinates = nullptr;
  petsc_check(MatCreateVecs(matrix_, &coordinates, nullptr), "coordinates");
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
  petsc_check(MatSetNearNullSpace(matrix_, space), "near-null space");
  MatNullSpaceDestroy(&space);
  VecDestroy(&coordinates);
}

std::size_t PetscMatrix::memory_bytes() const {
  if (!matrix_) return 0;
  // Entries and their column indices, and the row starts (PETSc's own memory count is off unless
  // its memory logging is on).
  MatInfo info;
  MatGetInfo(matrix_, MAT_LOCAL, &info);
  PetscInt rows = 0, columns = 0;
  MatGetLocalSize(matrix_, &rows, &columns);
  return static_cast<std::size_t>(info.nz_allocated) * (sizeof(PetscScalar) + sizeof(PetscInt)) +
         static_cast<std::size_t>(rows + 1) * sizeof(PetscInt);
}

}  // namespace fastcorot
