#include "fastcorot/sim/mass.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/packed.h"
#include "fastcorot/core/parallel.h"

#include <cmath>

namespace fastcorot {

template <class Real>
Mass<Real> Mass<Real>::lumped(std::vector<Real> vertex_masses) {
  for (std::size_t i = 0; i < vertex_masses.size(); ++i) {
    if (!(vertex_masses[i] >= 0) || !std::isfinite(vertex_masses[i])) {
      throw make_error("mass of vertex ", i, " = ", vertex_masses[i], ": must be finite and >= 0");
    }
  }
  Mass mass;
  mass.vertex_masses_ = std::move(vertex_masses);
  return mass;
}

template <class Real>
Mass<Real> Mass<Real>::consistent(Eigen::SparseMatrix<Real> matrix) {
  if (matrix.rows() != matrix.cols()) throw make_error("mass matrix is not square");
  Mass mass;
  mass.matrix_ = matrix;
  mass.vertex_masses_.assign(static_cast<std::size_t>(matrix.rows()), Real(0));
  for (Eigen::Index row = 0; row < mass.matrix_.outerSize(); ++row) {
    for (typename Eigen::SparseMatrix<Real, Eigen::RowMajor>::InnerIterator it(mass.matrix_, row); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw make_error("mass matrix entry (", row, ", ", it.col(), ") = ", it.value(), ": must be finite");
      }
      mass.vertex_masses_[static_cast<std::size_t>(row)] += it.value();
    }
  }
  return mass;
}

template <class Real>
Mass<Real> Mass<Real>::block_diagonal(std::vector<Mat3<Real>> blocks) {
  Mass mass;
  mass.vertex_masses_.reserve(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!blocks[i].allFinite() || !blocks[i].isApprox(blocks[i].transpose(), Real(0))) {
      throw make_error("mass block of vertex ", i, ": must be finite and symmetric");
    }
    mass.vertex_masses_.push_back(blocks[i].trace() / 3);
  }
  mass.blocks_ = std::move(blocks);
  return mass;
}

template <class Real>
void Mass<Real>::set_couplings(std::vector<Coupling> couplings) {
  if (!is_block_diagonal()) throw make_error("mass couplings: only a block mass has them");
  const auto n = static_cast<Index>(blocks_.size());
  for (const Coupling& c : couplings) {
    if (c.first < 0 || c.first >= n || c.second < 0 || c.second >= n || c.first == c.second) {
      throw make_error("mass coupling (", c.first, ", ", c.second, "): needs two different blocks of ", n);
    }
    if (!c.block.allFinite()) throw make_error("mass coupling (", c.first, ", ", c.second, "): must be finite");
  }
  couplings_ = std::move(couplings);
}

template <class Real>
void Mass<Real>::set_gravity_blocks(std::vector<Mat3<Real>> blocks) {
  if (!is_block_diagonal()) throw make_error("gravity blocks: only a block mass has them");
  if (blocks.size() != blocks_.size()) {
    throw make_error("gravity blocks: ", blocks.size(), " blocks for ", blocks_.size(), " points");
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!blocks[i].allFinite()) throw make_error("gravity block of vertex ", i, ": must be finite");
  }
  gravity_blocks_ = std::move(blocks);
}

template <class Real>
Real Mass<Real>::total_mass() const {
  Real total = 0;
  for (Real m : vertex_masses_) total += m;
  return total;
}

namespace {

// sum_j M_ij dx_j over the stored entries of row i.
template <class Real>
Vec3<Real> row_product(const Eigen::SparseMatrix<Real, Eigen::RowMajor>& matrix, std::size_t row,
                       std::span<const Vec3<Real>> dx) {
  Vec3<Real> sum = Vec3<Real>::Zero();
  for (typename Eigen::SparseMatrix<Real, Eigen::RowMajor>::InnerIterator it(matrix, static_cast<Eigen::Index>(row)); it; ++it) {
    sum += it.value() * dx[static_cast<std::size_t>(it.col())];
  }
  return sum;
}

}  // namespace

template <class Real>
void Mass<Real>::add_mdx(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor) const {
  if (is_block_diagonal()) {
    // As SOFA's UniformMass<Rigid3>::addMDx: the mass scaled by the factor first.
    for (std::size_t i = 0; i < blocks_.size(); ++i) out[i] += (factor * blocks_[i]) * dx[i];
    add_couplings(dx, out, factor);
    return;
  }
  if (is_lumped()) {
    for (std::size_t i = 0; i < vertex_masses_.size(); ++i) out[i] += (factor * vertex_masses_[i]) * dx[i];
    return;
  }
  for (std::size_t row = 0; row < static_cast<std::size_t>(matrix_.outerSize()); ++row) {
    out[row] += factor * row_product(matrix_, row, dx);
  }
}

template <class Real>
void Mass<Real>::multiply(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor, int threads) const {
  if (is_block_diagonal()) {
    for (std::size_t i = 0; i < blocks_.size(); ++i) out[i] = (factor * blocks_[i]) * dx[i];
    add_couplings(dx, out, factor);
    return;
  }
  if (is_lumped()) {
    // Plain pointers, so that the loop keeps them in registers (through the captured spans GCC
    // reloaded them for every point).
    const Real* masses = vertex_masses_.data();
    const auto* in = reinterpret_cast<const Real*>(dx.data());
    auto* to = reinterpret_cast<Real*>(out.data());
    parallel_ranges(threads, vertex_masses_.size(), [masses, in, to, factor](std::size_t begin, std::size_t end) {
      // Four points (twelve values) at a time as three packs, each value times its point's
      // factor · mass: the same products as one point at a time.
      using P = Packed<Real>;
      std::size_t i = begin;
      for (; i + 4 <= end; i += 4) {
        const P m = broadcast(factor) * load_packed(masses + i);
        const Real* from = in + 3 * i;
        Real* into = to + 3 * i;
        store_packed(into, permute<0, 0, 0, 1>(m) * load_packed(from));
        store_packed(into + 4, permute<1, 1, 2, 2>(m) * load_packed(from + 4));
        store_packed(into + 8, permute<2, 3, 3, 3>(m) * load_packed(from + 8));
      }
      for (; i < end; ++i) {
        const Real m = factor * masses[i];
        for (std::size_t c = 0; c < 3; ++c) to[3 * i + c] = m * in[3 * i + c];
      }
    });
    return;
  }
  parallel_ranges(threads, vertex_masses_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t row = begin; row < end; ++row) out[row] = factor * row_product(matrix_, row, dx);
  });
}

template <class Real>
void Mass<Real>::add_couplings(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> out, Real factor) const {
  for (const Coupling& c : couplings_) {
    const auto a = static_cast<std::size_t>(c.first), b = static_cast<std::size_t>(c.second);
    const Mat3<Real> scaled = factor * c.block;
    out[a] += scaled * dx[b];
    out[b] += scaled.transpose() * dx[a];
  }
}

template <class Real>
void Mass<Real>::add_gravity(const Vec3<Real>& gravity, std::span<Vec3<Real>> f) const {
  if (!gravity_blocks_.empty()) {
    for (std::size_t i = 0; i < gravity_blocks_.size(); ++i) f[i] += gravity_blocks_[i] * gravity;
    return;
  }
  const std::span<const Real> masses = gravity_masses();
  for (std::size_t i = 0; i < masses.size(); ++i) f[i] += masses[i] * gravity;
}

template <class Real>
Real Mass<Real>::gravity_energy(const Vec3<Real>& gravity, std::span<const Vec3<Real>> x) const {
  std::vector<Vec3<Real>> weight(static_cast<std::size_t>(size()), Vec3<Real>::Zero());
  add_gravity(gravity, weight);
  Real energy = 0;
  for (std::size_t i = 0; i < weight.size(); ++i) energy -= weight[i].dot(x[i]);
  return energy;
}

template <class Real>
void Mass<Real>::set_gravity_masses(std::vector<Real> masses) {
  if (masses.size() != vertex_masses_.size()) {
    throw make_error("gravity masses: ", masses.size(), " values for ", vertex_masses_.size(), " points");
  }
  for (std::size_t i = 0; i < masses.size(); ++i) {
    if (!(masses[i] >= 0) || !std::isfinite(masses[i])) {
      throw make_error("gravity mass of vertex ", i, " = ", masses[i], ": must be finite and >= 0");
    }
  }
  gravity_masses_ = std::move(masses);
}

template <class Real>
void Mass<Real>::add_to_matrix(MatrixSink<Real>& sink, Real factor, Index offset) const {
  if (is_block_diagonal()) {
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      const Index row = offset + 3 * static_cast<Index>(i);
      sink.add_block(row, row, factor * blocks_[i]);
    }
    for (const Coupling& c : couplings_) {
      const Index a = offset + 3 * c.first, b = offset + 3 * c.second;
      sink.add_block(a, b, factor * c.block);
      sink.add_block(b, a, factor * c.block.transpose());
    }
    return;
  }
  if (is_lumped()) {
    for (std::size_t i = 0; i < vertex_masses_.size(); ++i) {
      const Index row = offset + 3 * static_cast<Index>(i);
      sink.add_block(row, row, (factor * vertex_masses_[i]) * Mat3<Real>::Identity());
    }
    return;
  }
  for (Eigen::Index row = 0; row < matrix_.outerSize(); ++row) {
    for (typename Eigen::SparseMatrix<Real, Eigen::RowMajor>::InnerIterator it(matrix_, row); it; ++it) {
      sink.add_block(offset + 3 * static_cast<Index>(row), offset + 3 * static_cast<Index>(it.col()),
                     (factor * it.value()) * Mat3<Real>::Identity());
    }
  }
}

template <class Real>
void Mass<Real>::add_diagonal_blocks(std::span<Mat3<Real>> blocks, Real factor) const {
  if (blocks.size() != vertex_masses_.size()) {
    throw make_error("mass diagonal: ", blocks.size(), " blocks for ", vertex_masses_.size(), " points");
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (is_block_diagonal()) {
      blocks[i] += factor * blocks_[i];
      continue;
    }
    const auto row = static_cast<Eigen::Index>(i);
    const Real m = is_lumped() ? vertex_masses_[i] : matrix_.coeff(row, row);
    blocks[i].diagonal().array() += factor * m;
  }
}

template <class Real>
Real Mass<Real>::kinetic_energy(std::span<const Vec3<Real>> v) const {
  std::vector<Vec3<Real>> mv(v.size(), Vec3<Real>::Zero());
  add_mdx(v, mv, Real(1));
  Real energy = 0;
  for (std::size_t i = 0; i < v.size(); ++i) energy += v[i].dot(mv[i]);
  return energy / 2;
}

template <class Real>
void Mass<Real>::follow_tetrahedra(std::shared_ptr<const TetMesh> mesh, Real density) {
  topology_ = std::move(mesh);
  density_ = density;
}

template <class Real>
void Mass<Real>::add_tetrahedron(const Tetrahedron& tet, std::span<const Vec3<Real>> rest, Real sign) {
  const Real mass = sign * density_ * std::abs(signed_volume(tetrahedron_points(tet, rest)));
  if (is_lumped()) {
    for (Index v : tet) vertex_masses_[static_cast<std::size_t>(v)] += mass / 4;
    return;
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Real entry = mass / (i == j ? 10 : 20);
      matrix_.coeffRef(tet[i], tet[j]) += entry;
      vertex_masses_[static_cast<std::size_t>(tet[i])] += entry;
    }
  }
}

template <class Real>
void Mass<Real>::apply(const TopologyChange& change, std::span<const Vec3<Real>> rest) {
  if (!topology_) return;
  for (const Tetrahedron& tet : change.removed_tetrahedron_vertices) add_tetrahedron(tet, rest, Real(-1));
  const Index first = change.first_added_tetrahedron;
  for (Index t = first; t < first + change.num_added_tetrahedra; ++t) {
    add_tetrahedron(topology_->tetrahedron(t), rest, Real(1));
  }
  // Round-off must not leave a point without tetrahedra with a trace of mass.
  for (Index v : change.isolated_points) {
    vertex_masses_[static_cast<std::size_t>(v)] = 0;
    if (is_lumped()) continue;
    for (typename Eigen::SparseMatrix<Real, Eigen::RowMajor>::InnerIterator it(matrix_, v); it; ++it) {
      matrix_.coeffRef(it.col(), v) = 0;
      it.valueRef() = 0;
    }
  }
  if (!is_lumped()) matrix_.makeCompressed();
}

template <class Real>
std::vector<Real> tetrahedral_lumped_masses(const TetMesh& mesh, std::span<const Vec3<Real>> rest,
                                            Real density) {
  std::vector<Real> masses(static_cast<std::size_t>(mesh.num_points()), Real(0));
  for (const Tetrahedron& t : mesh.tetrahedra()) {
    const Real share = density * std::abs(signed_volume(tetrahedron_points(t, rest))) / 4;
    for (Index v : t) masses[static_cast<std::size_t>(v)] += share;
  }
  return masses;
}

template <class Real>
Eigen::SparseMatrix<Real> tetrahedral_mass_matrix(const TetMesh& mesh, std::span<const Vec3<Real>> rest,
                                                  Real density) {
  std::vector<Eigen::Triplet<Real>> triplets;
  triplets.reserve(16 * static_cast<std::size_t>(mesh.num_tetrahedra()));
  for (const Tetrahedron& t : mesh.tetrahedra()) {
    const Real volume = std::abs(signed_volume(tetrahedron_points(t, rest)));
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) triplets.emplace_back(t[i], t[j], density * volume / (i == j ? 10 : 20));
    }
  }
  Eigen::SparseMatrix<Real> matrix(mesh.num_points(), mesh.num_points());
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  return matrix;
}

template <class Real>
Real total_volume(const TetMesh& mesh, std::span<const Vec3<Real>> rest) {
  Real volume = 0;
  for (const Tetrahedron& t : mesh.tetrahedra()) volume += std::abs(signed_volume(tetrahedron_points(t, rest)));
  return volume;
}

template class Mass<float>;
template class Mass<double>;
template std::vector<float> tetrahedral_lumped_masses(const TetMesh&, std::span<const Vec3<float>>, float);
template std::vector<double> tetrahedral_lumped_masses(const TetMesh&, std::span<const Vec3<double>>, double);
template Eigen::SparseMatrix<float> tetrahedral_mass_matrix(const TetMesh&, std::span<const Vec3<float>>, float);
template Eigen::SparseMatrix<double> tetrahedral_mass_matrix(const TetMesh&, std::span<const Vec3<double>>, double);
template float total_volume(const TetMesh&, std::span<const Vec3<float>>);
template double total_volume(const TetMesh&, std::span<const Vec3<double>>);

}  // namespace fastcorot
