// Mass of a deformable object: lumped (one mass per vertex: SOFA's DiagonalMass, UniformMass and
// MeshMatrixMass with lumping), consistent (a symmetric #V×#V scalar matrix applied to each axis:
// MeshMatrixMass without lumping) or block-diagonal (one symmetric 3×3 block per vertex: rigid
// bodies, whose angular block is m·inertia: state/rigid_mass.h), with optional couplings between
// two blocks (a rigid carrying masses: sim/rigid_mapped_mass.h). Gravity acts through the mass:
// f_i += (sum_j M_ij) g, or the gravity masses when set, or a block mass's gravity blocks.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/topology/tet_mesh.h"
#include "fastcorot/topology/topology_change.h"

#include <Eigen/SparseCore>

#include <memory>
#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
class Mass {
 public:
  Mass() = default;

  // One mass per vertex; throws fastcorot::Error for a negative or non-finite entry.
  static Mass lumped(std::vector<Real> vertex_masses);
  // A consistent #V×#V scalar matrix (symmetric); vertex_masses() then returns its row sums.
  // Throws fastcorot::Error for a non-square matrix or a non-finite entry.
  static Mass consistent(Eigen::SparseMatrix<Real> matrix);

  // One symmetric 3×3 block per vertex (rigid bodies: m I₃ and m·inertia); vertex_masses() are
  // then the blocks' traces / 3, and gravity acts on the gravity masses, which the caller sets.
  // Throws fastcorot::Error for a non-finite or non-symmetric block.
  static Mass block_diagonal(std::vector<Mat3<Real>> blocks);

  // An off-diagonal block pair of a block mass: M_{first,second} = block, M_{second,first} = blockᵀ.
  struct Coupling {
    Index first = 0;
    Index second = 0;
    Mat3<Real> block = Mat3<Real>::Zero();
  };
  // Sets the couplings of a block-diagonal mass (replacing any before). Throws fastcorot::Error for
  // another kind of mass, an index out of range, first == second or a non-finite block.
  void set_couplings(std::vector<Coupling> couplings);
  std::span<const Coupling> couplings() const { return couplings_; }
  // Gravity on a block mass as 3×3 blocks, f_i += G_i g (a rigid carrying masses m_j at offsets
  // r_j: G = Σ m_j I on its linear block, [Σ m_j r_j]× on its angular one). Throws fastcorot::Error
  // for another kind of mass, a wrong size or a non-finite block.
  void set_gravity_blocks(std::vector<Mat3<Real>> blocks);

  bool is_lumped() const { return matrix_.size() == 0 && blocks_.empty(); }
  bool is_block_diagonal() const { return !blocks_.empty(); }
  std::span<const Mat3<Real>> blocks() const { return blocks_; }
  // The consistent matrix (empty when lumped).
  const Eigen::SparseMatrix<Real, Eigen::RowMajor>& matrix() const { return matrix_; }
  Index size() const { return static_cast<Index>(vertex_masses_.size()); }
  // Lumped masses, or the row sums of the consistent matrix.
  std::span<const Real> vertex_masses() const { return vertex_masses_; }
  Real total_mass() const;

  // out += factor · M dx
  void add_mdx(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor) const;
  // out = factor · M dx (every point written; the rows on up to `threads` threads, the same bits for
  // any count).
  void multiply(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor, int threads) const;
  // f += m_i g for each vertex i, m_i its gravity mass (below), or f_i += G_i g (gravity blocks).
  void add_gravity(const Vec3<Real>& gravity, std::span<Vec3<Real>> f) const;
  // The potential of gravity at x: -Σ (weight of i) · x_i.
  Real gravity_energy(const Vec3<Real>& gravity, std::span<const Vec3<Real>> x) const;
  // The masses gravity acts on: vertex_masses() unless set otherwise. SOFA's
  // HexahedronFEMForceFieldAndMass weighs its points (density x volume / 8 from each hexahedron)
  // otherwise than its mass matrix's row sums. Throws fastcorot::Error for a wrong size or a
  // negative or non-finite entry.
  void set_gravity_masses(std::vector<Real> masses);
  std::span<const Real> gravity_masses() const { return gravity_masses_.empty() ? vertex_masses() : gravity_masses_; }
  bool has_own_gravity_masses() const { return !gravity_masses_.empty(); }
  // factor · M as 3×3 blocks (diagonal blocks m I, or M_ij I) at the given scalar offset.
  void add_to_matrix(MatrixSink<Real>& sink, Real factor, Index offset = 0) const;
  // blocks[i] += factor · M_ii · I (the lumped mass, or the consistent matrix's diagonal entry): the
  // diagonal blocks of factor · M. Throws fastcorot::Error for a wrong size.
  void add_diagonal_blocks(std::span<Mat3<Real>> blocks, Real factor) const;
  // 1/2 v^T M v
  Real kinetic_energy(std::span<const Vec3<Real>> v) const;

  // Masses computed from the tetrahedra of `mesh` (DiagonalMass, MeshMatrixMass) follow its
  // topological changes as SOFA's do: each removed tetrahedron takes back density |V| / 4 from each
  // vertex (lumped) or its element matrix (consistent), each added one gives them, at the rest
  // positions. A point left without tetrahedra gets exactly zero mass.
  void follow_tetrahedra(std::shared_ptr<const TetMesh> mesh, Real density);
  bool follows(const TetMesh& mesh) const { return topology_.get() == &mesh; }
  // Follows a change just made to the followed mesh (does nothing for masses that do not follow).
  void apply(const TopologyChange& change, std::span<const Vec3<Real>> rest);

 private:
  void add_tetrahedron(const Tetrahedron& tet, std::span<const Vec3<Real>> rest, Real sign);
  // out += factor · (the couplings' blocks) dx.
  void add_couplings(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor) const;

  std::shared_ptr<const TetMesh> topology_;
  Real density_ = 0;
  std::vector<Real> vertex_masses_;
  Eigen::SparseMatrix<Real, Eigen::RowMajor> matrix_;  // empty when lumped
  std::vector<Real> gravity_masses_;                  // empty: vertex_masses_
  std::vector<Mat3<Real>> blocks_;                    // block-diagonal masses only
  std::vector<Coupling> couplings_;                   // block masses only
  std::vector<Mat3<Real>> gravity_blocks_;            // block masses only; empty: gravity masses
};

// SOFA's DiagonalMass on tetrahedra: each tetrahedron gives density · |V| / 4 to each of its vertices.
template <class Real>
std::vector<Real> tetrahedral_lumped_masses(const TetMesh& mesh, std::span<const Vec3<Real>> rest,
                                            Real density);

// SOFA's MeshMatrixMass on tetrahedra: the consistent linear-tetrahedron mass matrix,
// M_ii += density |V| / 10, M_ij += density |V| / 20 for i != j in each tetrahedron.
template <class Real>
Eigen::SparseMatrix<Real> tetrahedral_mass_matrix(const TetMesh& mesh, std::span<const Vec3<Real>> rest,
                                                  Real density);

// Total rest volume sum |V_t|.
template <class Real>
Real total_volume(const TetMesh& mesh, std::span<const Vec3<Real>> rest);

}  // namespace fastcorot
