// TetrahedronFEMForceField's assembled stiffness: the rows of 3×3 blocks (one row per point, one
// block per neighbouring point, both blocks of each mesh edge), made from each element's w = R g and
// K's values at the last linearisation, and what the solvers read of them: the product
// (add_dforce), the blocks (add_stiffness) and the diagonal. The element arithmetic, the forces and
// the rest of the force field are in tetrahedron_fem_force_field.cpp.
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/packed.h"
#include "fastcorot/core/parallel.h"
#include "fastcorot/fem/tetrahedron_element.h"

namespace fastcorot {

template <class Real>
void TetrahedronFEMForceField<Real>::lay_out_blocks() {
  point_blocks_.assign(static_cast<std::size_t>(mesh_->num_points()), PaddedBlock{});
  const Index n = mesh_->num_points();
  row_begin_.assign(static_cast<std::size_t>(n) + 1, 0);
  row_neighbour_.clear();
  // Entry of each edge in the rows of its first and its second point.
  std::vector<std::array<Index, 2>>& entry_of_edge = edge_entries_;
  entry_of_edge.assign(static_cast<std::size_t>(mesh_->num_edges()), {0, 0});
  for (Index v = 0; v < n; ++v) {
    for (Index e : mesh_->edges_around_vertex(v)) {
      const Edge& edge = mesh_->edges()[static_cast<std::size_t>(e)];
      const bool first = edge[0] == v;
      entry_of_edge[static_cast<std::size_t>(e)][first ? 0 : 1] = static_cast<Index>(row_neighbour_.size());
      row_neighbour_.push_back(first ? edge[1] : edge[0]);
    }
    row_begin_[static_cast<std::size_t>(v) + 1] = static_cast<Index>(row_neighbour_.size());
  }
  row_blocks_.assign(row_neighbour_.size(), PaddedBlock{});
  // Each mesh edge's elements in schedule order, the order in which their blocks are summed.
  const auto edge_count = static_cast<std::size_t>(mesh_->num_edges());
  edge_incidence_begin_.assign(edge_count + 1, 0);
  for (const Index t : schedule_.order) {
    for (const Index e : mesh_->edges_of_tetrahedron(t)) ++edge_incidence_begin_[static_cast<std::size_t>(e) + 1];
  }
  for (std::size_t e = 0; e < edge_count; ++e) edge_incidence_begin_[e + 1] += edge_incidence_begin_[e];
  edge_incidences_.resize(static_cast<std::size_t>(edge_incidence_begin_[edge_count]));
  std::vector<Index> filled(edge_incidence_begin_.begin(), edge_incidence_begin_.end() - 1);
  for (const Index t : schedule_.order) {
    const auto& edges = mesh_->edges_of_tetrahedron(t);
    for (std::size_t e = 0; e < 6; ++e) {
      edge_incidences_[static_cast<std::size_t>(filled[static_cast<std::size_t>(edges[e])]++)] = {
          t, static_cast<signed char>(e), static_cast<signed char>(mesh_->edge_follows_mesh_edge(t, static_cast<int>(e)) ? 1 : -1)};
    }
  }
  element_stiffness_.resize(static_cast<std::size_t>(mesh_->num_tetrahedra()));
}

template <class Real>
void TetrahedronFEMForceField<Real>::store_element_stiffness(Index t) {
  // w = R g (the gradients in the world) from the element's rotation, as the kernels make it.
  const Element& element = elements_[static_cast<std::size_t>(t)];
  ElementStiffness& stiffness = element_stiffness_[static_cast<std::size_t>(t)];
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec3<Real>& g = element.gradient[i];
    const Mat3<Real>& r = element.rotation;
    for (int c = 0; c < 3; ++c) stiffness.w[i][c] = r(c, 0) * g[0] + r(c, 1) * g[1] + r(c, 2) * g[2];
  }
  stiffness.k1 = element.material[1];
  stiffness.k2 = element.material[2];
}

template <class Real>
Mat3<Real> TetrahedronFEMForceField<Real>::PaddedBlock::matrix() const {
  Mat3<Real> m;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) m(r, c) = value[4 * c + r];
  }
  return m;
}

template <class Real>
void TetrahedronFEMForceField<Real>::assemble_blocks() {
  // Block (k, l) of an element, R J K J^T R^T's, is k1 w_k w_l^T + k2 w_l w_k^T + k2 (w_k . w_l) I
  // (J K J^T's blocks in the element's frame, rotated; their diagonal also carries
  // (k0 - k1 - 2 k2) w_k∘w_l in the frame, zero for isotropic K up to rounding, left out). Each mesh
  // edge (u, v) sums its elements' blocks in schedule order, in registers: column c of block (u, v)
  // is k1 w_k w_l[c] + k2 w_l w_k[c] plus the diagonal term in lane c for a local edge (k, l) along
  // (u, v); for one against it, column c of the transpose, k1 w_l w_k[c] + k2 w_k w_l[c] with each
  // product's factors swapped (the same bits as the transpose entry by entry). Then block (v, u) is
  // its transpose, and each point's block (v, v) minus the sum of row v's other blocks: an
  // element's gradients sum to zero, so that each of its block rows does (Σ_l K_kl = 0).
  //
  // With one Poisson ratio for all the elements, k1 = ρ k2 with the same ρ = 2ν / (1 - 2ν) for all,
  // so block (u, v) is A + ρ Aᵀ + s I with A = Σ k2 w_v w_uᵀ and s = Σ k2 (w_u · w_v) over the
  // edge's elements: a third of the arithmetic per element, and ρ Aᵀ and s I once per edge (the
  // same blocks up to rounding).
  using P = Packed<Real>;
  // The diagonal term is added to lane c of column c as a packet that is zero in the other lanes.
  const P unit[3] = {P{1, 0, 0, 0}, P{0, 1, 0, 0}, P{0, 0, 1, 0}};
  const bool factored = !poisson_per_tetrahedron_;
  const Real nu = parameters_.poisson_ratio.front();
  const Real ratio = (nu / (1 - nu)) / ((1 - 2 * nu) / (2 * (1 - nu)));  // k1 / k2, as initialise_element's factors
  parallel_ranges(threads_, edge_entries_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t edge = begin; edge < end; ++edge) {
      P sum[3] = {P{}, P{}, P{}};
      Real diagonal_sum = 0;
      const auto last = static_cast<std::size_t>(edge_incidence_begin_[edge + 1]);
      for (auto i = static_cast<std::size_t>(edge_incidence_begin_[edge]); i < last; ++i) {
        const EdgeIncidence& incidence = edge_incidences_[i];
        const ElementStiffness& element = element_stiffness_[static_cast<std::size_t>(incidence.element)];
        const auto& local = kTetrahedronEdges[static_cast<std::size_t>(incidence.local_edge)];
        const Vec3<Real>& a = element.w[static_cast<std::size_t>(local[0])];
        const Vec3<Real>& b = element.w[static_cast<std::size_t>(local[1])];
        const Real k1 = element.k1, k2 = element.k2;
        if (factored) {
          // A's column c: k2 w_v w_u[c], (u, v) the mesh edge's orientation
          const Vec3<Real>& u = incidence.along > 0 ? a : b;
          const Vec3<Real>& v = incidence.along > 0 ? b : a;
          const P k2v = packed_point(k2 * v);
          for (int c = 0; c < 3; ++c) sum[c] = sum[c] + k2v * u[c];
          diagonal_sum = diagonal_sum + k2 * a.dot(b);
          continue;
        }
        const P diagonal = broadcast(k2 * a.dot(b));
        if (incidence.along > 0) {
          const P k1a = packed_point(k1 * a), k2b = packed_point(k2 * b);
          for (int c = 0; c < 3; ++c) sum[c] = sum[c] + ((k1a * b[c] + k2b * a[c]) + diagonal * unit[c]);
        } else {
          const P pa = packed_point(a), pb = packed_point(b);
          for (int c = 0; c < 3; ++c) sum[c] = sum[c] + ((pb * (k1 * a[c]) + pa * (k2 * b[c])) + diagonal * unit[c]);
        }
      }
      P rows[4];
      lanes_to_points(sum[0], sum[1], sum[2], rows);
      if (factored) {
        const P diagonal = broadcast(diagonal_sum);
        for (int c = 0; c < 3; ++c) sum[c] = (sum[c] + ratio * rows[c]) + diagonal * unit[c];
        lanes_to_points(sum[0], sum[1], sum[2], rows);
      }
      const auto& entries = edge_entries_[edge];
      Real* block = row_blocks_[static_cast<std::size_t>(entries[0])].value;
      for (int c = 0; c < 3; ++c) store_packed(block + 4 * c, sum[c]);
      Real* mirror = row_blocks_[static_cast<std::size_t>(entries[1])].value;
      for (int c = 0; c < 3; ++c) store_packed(mirror + 4 * c, rows[c]);
    }
  });
  parallel_ranges(threads_, point_blocks_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      P sum[3] = {P{}, P{}, P{}};
      for (auto entry = static_cast<std::size_t>(row_begin_[v]); entry < static_cast<std::size_t>(row_begin_[v + 1]); ++entry) {
        for (int c = 0; c < 3; ++c) sum[c] -= load_packed(row_blocks_[entry].value + 4 * c);
      }
      for (int c = 0; c < 3; ++c) store_packed(point_blocks_[v].value + 4 * c, sum[c]);
    }
  });
}

template <class Real>
void TetrahedronFEMForceField<Real>::refresh_blocks() {
  run_schedule(schedule_, threads_, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) store_element_stiffness(schedule_.order[static_cast<std::size_t>(i)]);
  });
  assemble_blocks();
  stale_ = false;
}

template <class Real>
void TetrahedronFEMForceField<Real>::ensure_linearisation() const {
  if (!stale_) return;
  // After a topological change: the blocks of the last linearisation, with the new elements.
  auto* self = const_cast<TetrahedronFEMForceField*>(this);
  std::vector<Vec3<Real>> scratch(last_positions_.size(), Vec3<Real>::Zero());
  const std::vector<Vec3<Real>> at = last_positions_;
  self->add_force(at, scratch);
}

template <class Real>
void TetrahedronFEMForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df,
                                                Real k_factor, Real b_factor) const {
  check_size(dx, "dx");
  check_size(df, "df");
  ensure_linearisation();
  // SOFA's applyStiffness: df -= k R J K J^T R^T dx, here one row of blocks per point (no races,
  // each point's sum in the order of its edges). A block times a point is c0 x + c1 y + c2 z over its
  // columns, three lanes of a Packed register (the spare lane unused), on dx padded to four values.
  using P = Packed<Real>;
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  padded_dx_.resize(dx.size());
  for (std::size_t v = 0; v < dx.size(); ++v) padded_dx_[v] = PaddedPoint{{dx[v][0], dx[v][1], dx[v][2], Real(0)}};
  const auto times = [](const PaddedBlock& block, const P& x) {
    const Real* m = block.value;
    return load_packed(m) * permute<0, 0, 0, 0>(x) + load_packed(m + 4) * permute<1, 1, 1, 1>(x) +
           load_packed(m + 8) * permute<2, 2, 2, 2>(x);
  };
  parallel_ranges(threads_, point_blocks_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      P sum = times(point_blocks_[v], load_packed(padded_dx_[v].value));
      const auto last = static_cast<std::size_t>(row_begin_[v + 1]);
      for (auto entry = static_cast<std::size_t>(row_begin_[v]); entry < last; ++entry) {
        sum += times(row_blocks_[entry], load_packed(padded_dx_[static_cast<std::size_t>(row_neighbour_[entry])].value));
      }
      df[v] -= k * Vec3<Real>(sum[0], sum[1], sum[2]);
    }
  });
}

template <class Real>
void TetrahedronFEMForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset,
                                                   Real b_factor) const {
  ensure_linearisation();
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  for (std::size_t v = 0; v < point_blocks_.size(); ++v) {
    const Index row = offset + 3 * static_cast<Index>(v);
    sink.add_block(row, row, -k * point_blocks_[v].matrix());
  }
  for (std::size_t v = 0; v < point_blocks_.size(); ++v) {
    const Index row = offset + 3 * static_cast<Index>(v);
    for (auto entry = static_cast<std::size_t>(row_begin_[v]); entry < static_cast<std::size_t>(row_begin_[v + 1]);
         ++entry) {
      sink.add_block(row, offset + 3 * row_neighbour_[entry], -k * row_blocks_[entry].matrix());
    }
  }
}

template <class Real>
void TetrahedronFEMForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor,
                                                         Real b_factor) const {
  if (diagonal.size() != point_blocks_.size()) {
    throw make_error("TetrahedronFEMForceField: ", diagonal.size(), " diagonal blocks for ", point_blocks_.size(),
                     " points");
  }
  ensure_linearisation();
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  for (std::size_t v = 0; v < diagonal.size(); ++v) diagonal[v] -= k * point_blocks_[v].matrix();
}

#define FASTCOROT_TETRAHEDRON_FEM_STIFFNESS_ROWS(Real)                                                                   \
  template void TetrahedronFEMForceField<Real>::lay_out_blocks();                                                    \
  template void TetrahedronFEMForceField<Real>::store_element_stiffness(Index);                                      \
  template Mat3<Real> TetrahedronFEMForceField<Real>::PaddedBlock::matrix() const;                                   \
  template void TetrahedronFEMForceField<Real>::assemble_blocks();                                                   \
  template void TetrahedronFEMForceField<Real>::refresh_blocks();                                                    \
  template void TetrahedronFEMForceField<Real>::ensure_linearisation() const;                                        \
  template void TetrahedronFEMForceField<Real>::add_dforce(std::span<const Vec3<Real>>, std::span<Vec3<Real>>, Real, \
                                                           Real) const;                                              \
  template void TetrahedronFEMForceField<Real>::add_stiffness(MatrixSink<Real>&, Real, Index, Real) const;           \
  template void TetrahedronFEMForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>>, Real, Real) const;
FASTCOROT_TETRAHEDRON_FEM_STIFFNESS_ROWS(float)
FASTCOROT_TETRAHEDRON_FEM_STIFFNESS_ROWS(double)
#undef FASTCOROT_TETRAHEDRON_FEM_STIFFNESS_ROWS

}  // namespace fastcorot
