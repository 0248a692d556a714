#include "fastcorot/fem/corotational_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/parallel.h"
#include "fastcorot/core/rotation.h"
#include "fastcorot/topology/point_order.h"
#include "force_kernels.h"
#include "material_checks.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace fastcorot {

namespace {

// SPEC.md: element t uses entry t if present, else entry 0.
template <class Real>
Real entry_for(const std::vector<Real>& values, std::size_t t) {
  return t < values.size() ? values[t] : values.front();
}

template <class Real>
LameParameters<Real> element_lame(const std::vector<Real>& young, const std::vector<Real>& poisson,
                                  std::size_t t) {
  try {
    return lame_parameters(entry_for(young, t), entry_for(poisson, t));
  } catch (const Error& error) {
    if (young.size() == 1 && poisson.size() == 1) throw;
    throw make_error(error.what(), " (tetrahedron ", t, ")");
  }
}

// Q (rows): world to the method's rest frame at the current edge vectors d_j = x_{j+1} - x0, given
// the rest-frame shape vectors s~_1..s~_3. The element rotation (rest to world) is R = Q^T R0.
template <class Real>
void world_to_rest_frame(RotationMethod method, const Real d[3][3], const Real s[3][3], Real q[3][3]) {
  Mat3<Real> frame = Mat3<Real>::Identity();
  const Vec3<Real> d0(d[0][0], d[0][1], d[0][2]), d1(d[1][0], d[1][1], d[1][2]), d2(d[2][0], d[2][1], d[2][2]);
  switch (method) {
    case RotationMethod::qr:
      frame = qr_frame<Real>(d0, d1);
      break;
    case RotationMethod::polar2:
      frame = polar_frame<Real>(d0, d1, d2);
      break;
    case RotationMethod::polar: {
      // R0 = I, so s~ = s and the deformation gradient is sum_j d_j s_j^T.
      const Vec3<Real> s0(s[0][0], s[0][1], s[0][2]), s1(s[1][0], s[1][1], s[1][2]), s2(s[2][0], s[2][1], s[2][2]);
      frame = polar_factor<Real>(d0 * s0.transpose() + d1 * s1.transpose() + d2 * s2.transpose()).transpose();
      break;
    }
    case RotationMethod::none:
      break;
  }
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) q[i][c] = frame(i, c);
  }
}

}  // namespace

template <class Real>
CorotationalForceField<Real>::CorotationalForceField(std::shared_ptr<TetMesh> mesh,
                                                     std::span<const Vec3<Real>> rest_positions,
                                                     Parameters parameters)
    : mesh_(std::move(mesh)),
      rest_positions_(rest_positions.begin(), rest_positions.end()),
      parameters_(std::move(parameters)) {
  if (!mesh_ || mesh_->num_tetrahedra() == 0) {
    throw make_error("FastTetrahedralCorotationalForceField: the topology has no tetrahedra");
  }
  const Index n = mesh_->num_tetrahedra();
  detail::check_material_lists(parameters_.young_modulus, parameters_.poisson_ratio, parameters_.rayleigh_stiffness, n);
  check_rest_volumes<Real>(*mesh_, rest_positions_);
  young_per_tetrahedron_ = n > 1 && parameters_.young_modulus.size() > 1;
  poisson_per_tetrahedron_ = n > 1 && parameters_.poisson_ratio.size() > 1;
  added_young_ = parameters_.young_modulus.front();
  added_poisson_ = parameters_.poisson_ratio.front();
  choose_point_order();
  rebuild();
}

// The mesh's numbering is kept unless it is scattered: SOFA's grids and the Gmsh example measure
// 2.3-4 times the mean edge span of a reverse Cuthill-McKee order, a shuffled mesh about 37 times.
// Renumbering a grid measured slower (76x16x16 on 2 threads), a shuffled mesh much faster
// (docs/performance.md, "Point order"), hence the factor of 8.
template <class Real>
void CorotationalForceField<Real>::choose_point_order() {
  const auto edges = mesh_->edges();
  std::vector<Index> order = reverse_cuthill_mckee(mesh_->num_points(), edges);
  if (mean_edge_span(edges) <= 8 * mean_edge_span(edges, order)) return;
  mesh_point_.assign(order.size(), 0);
  for (std::size_t p = 0; p < order.size(); ++p) mesh_point_[static_cast<std::size_t>(order[p])] = static_cast<Index>(p);
  internal_point_ = std::move(order);
}

template <class Real>
TetrahedronRest<Real> CorotationalForceField<Real>::element_rest(Index t) const {
  const auto p = tetrahedron_points<Real>(mesh_->tetrahedron(t), rest_positions_);
  const auto e = static_cast<std::size_t>(t);
  return tetrahedron_rest(p, element_lame(parameters_.young_modulus, parameters_.poisson_ratio, e),
                          parameters_.method);
}

template <class Real>
std::size_t CorotationalForceField<Real>::rest_index(std::size_t position, std::size_t value) const {
  constexpr auto W = static_cast<std::size_t>(kernels::kLanes<Real>);
  return (position / W * kRestValues + value) * W + position % W;
}

template <class Real>
void CorotationalForceField<Real>::move_rest_data(std::size_t from, std::size_t to) {
  for (std::size_t v = 0; v < kRestValues; ++v) rest_[rest_index(to, v)] = rest_[rest_index(from, v)];
}

// Writes tetrahedron t's rest data at its position, making room for the position if needed.
template <class Real>
void CorotationalForceField<Real>::set_rest_data(Index t) {
  const TetrahedronRest<Real> rest = element_rest(t);
  const auto position = static_cast<std::size_t>(position_[static_cast<std::size_t>(t)]);
  constexpr auto W = static_cast<std::size_t>(kernels::kLanes<Real>);
  const std::size_t blocks = tetrahedron_schedule_.order.size() / W + 1;
  if (rest_.size() < blocks * kRestValues * W) rest_.resize(blocks * kRestValues * W, Real(0));
  for (std::size_t j = 1; j < 4; ++j) {
    const Vec3<Real> s = rest.rest_rotation * rest.shape[j];
    for (std::size_t c = 0; c < 3; ++c) rest_[rest_index(position, 3 * (j - 1) + c)] = s[static_cast<Index>(c)];
  }
  rest_[rest_index(position, 9)] = rest.mu;
  rest_[rest_index(position, 10)] = rest.lambda;
}

template <class Real>
void CorotationalForceField<Real>::rebuild() {
  const auto n = static_cast<std::size_t>(mesh_->num_tetrahedra());
  std::vector<Tetrahedron> renumbered;
  if (renumbers_points()) {
    renumbered.reserve(n);
    for (const Tetrahedron& tet : mesh_->tetrahedra()) renumbered.push_back(internal(tet));
  }
  tetrahedron_schedule_ = make_scatter_schedule<4>(
      mesh_->num_points(), renumbers_points() ? std::span<const Tetrahedron>(renumbered) : mesh_->tetrahedra(),
      kDefaultMinPart, kernels::kLanes<Real>);
  const auto& visiting = tetrahedron_schedule_.order;
  position_.assign(n, 0);
  for (std::size_t position = 0; position < visiting.size(); ++position) {
    if (visiting[position] >= 0) position_[static_cast<std::size_t>(visiting[position])] = static_cast<Index>(position);
  }
  rest_.clear();
  for (std::size_t t = 0; t < n; ++t) set_rest_data(static_cast<Index>(t));

  // Edges sorted by (lower, higher) vertex, then scheduled (which keeps that order within groups);
  // slot i of the internal arrays holds the edge at position i of the schedule.
  const auto edges = mesh_->edges();
  std::vector<Index> by_vertex(edges.size());
  std::iota(by_vertex.begin(), by_vertex.end(), Index(0));
  const auto ordered = [&](Index e) { return slot_edge(edges[static_cast<std::size_t>(e)]); };
  std::sort(by_vertex.begin(), by_vertex.end(), [&](Index a, Index b) { return ordered(a) < ordered(b); });
  std::vector<Edge> sorted(edges.size());
  for (std::size_t i = 0; i < sorted.size(); ++i) sorted[i] = ordered(by_vertex[i]);
  const ScatterSchedule schedule = make_scatter_schedule<2>(mesh_->num_points(), std::span<const Edge>(sorted));
  edge_schedule_ = schedule;
  edge_slot_.assign(edges.size(), 0);
  edge_vertices_.clear();
  edge_vertices_.reserve(edges.size());
  free_slots_.assign(static_cast<std::size_t>(schedule.num_groups()), {});
  num_free_slots_ = 0;
  for (Index g = 0; g < schedule.num_groups(); ++g) {
    const auto gi = static_cast<std::size_t>(g);
    edge_schedule_.group_begin[gi] = static_cast<Index>(edge_vertices_.size());
    for (Index i = schedule.group_begin[gi]; i < schedule.group_begin[gi + 1]; ++i) {
      const Index e = by_vertex[static_cast<std::size_t>(schedule.order[static_cast<std::size_t>(i)])];
      edge_slot_[static_cast<std::size_t>(e)] = static_cast<Index>(edge_vertices_.size());
      edge_vertices_.push_back(ordered(e));
    }
  }
  edge_schedule_.group_begin.back() = static_cast<Index>(edge_vertices_.size());
  edge_schedule_.group_end.assign(edge_schedule_.group_begin.begin() + 1, edge_schedule_.group_begin.end());
  edge_schedule_.order.clear();  // positions are slots

  blocks_.assign(9 * edge_vertices_.size() + kernels::kBlockTail, Real(0));
  stale_ = true;
}

template <class Real>
void CorotationalForceField<Real>::ensure_linearisation() const {
  if (!stale_) return;
  const std::vector<Vec3<Real>>& x = last_positions_.empty() ? rest_positions_ : last_positions_;
  std::vector<Vec3<Real>> scratch(x.size(), Vec3<Real>::Zero());
  accumulate_force<true>(x, scratch);
  stale_ = false;
}

template <class Real>
void CorotationalForceField<Real>::set_method(RotationMethod method) {
  parameters_.method = method;
  rebuild();
  last_positions_.clear();
}

template <class Real>
void CorotationalForceField<Real>::check_size(std::span<const Vec3<Real>> v, const char* what) const {
  if (v.size() != static_cast<std::size_t>(mesh_->num_points())) {
    throw make_error("FastTetrahedralCorotationalForceField: ", what, " holds ", v.size(),
                     " points; the topology has ", mesh_->num_points());
  }
}

// Points padded to four values (scaled by `scale`; `zeroed` cleared), and the reverse (added), in
// the force field's own point order when it has one.
template <class Real>
void CorotationalForceField<Real>::pad(const Real* from, Real scale, Real* to, Real* zeroed) const {
  const std::size_t n = static_cast<std::size_t>(mesh_->num_points());
  const Index* order = internal_point_.data();
  parallel_ranges(threads_, n, [=](std::size_t begin, std::size_t end) {
    if (order) {
      kernels::pad_points_renumbered(from, scale, order, to, zeroed, begin, end);
    } else {
      kernels::pad_points(from, scale, n, to, zeroed, begin, end);
    }
  });
}

template <class Real>
void CorotationalForceField<Real>::unpad(const Real* padded, Real* to) const {
  const std::size_t n = static_cast<std::size_t>(mesh_->num_points());
  const Index* order = internal_point_.data();
  parallel_ranges(threads_, n, [=](std::size_t begin, std::size_t end) {
    if (order) {
      kernels::add_padded_points_renumbered(padded, order, to, begin, end);
    } else {
      kernels::add_padded_points(padded, to, begin, end);
    }
  });
}

template <class Real>
void CorotationalForceField<Real>::add_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  check_size(x, "x");
  check_size(f, "f");
  const PhaseTimer timer(times_ ? &times_->add_force : nullptr);
  accumulate_force<true>(x, f);
  last_positions_.assign(x.begin(), x.end());
  stale_ = false;
}

template <class Real>
void CorotationalForceField<Real>::add_force_only(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) {
  check_size(x, "x");
  check_size(f, "f");
  accumulate_force<false>(x, f);
}

template <class Real>
template <bool kRefresh>
void CorotationalForceField<Real>::accumulate_force(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> f) const {
  if constexpr (kRefresh) {
    parallel_ranges(threads_, blocks_.size(), [&](std::size_t begin, std::size_t end) {
      std::fill(blocks_.begin() + static_cast<std::ptrdiff_t>(begin), blocks_.begin() + static_cast<std::ptrdiff_t>(end), Real(0));
    });
  }
  const Tetrahedron* tetrahedra = mesh_->tetrahedra().data();
  // Points padded to four values (add_dforce's scratch arrays): the positions in, the forces out,
  // so that a point is one SIMD load or load-add-store.
  using P = Packed<Real>;
  const std::size_t n = x.size();
  packed_in_.resize(n);
  packed_out_.resize(n);
  Real* padded_x = reinterpret_cast<Real*>(packed_in_.data());
  Real* padded_f = reinterpret_cast<Real*>(packed_out_.data());
  const Real* xs = x.data()->data();
  Real* fs = f.data()->data();
  pad(xs, Real(1), padded_x, padded_f);
  Real* blocks = blocks_.data();
  // (A field emptied by topological changes has no tetrahedron 0.)
  const std::array<Index, 6>* edges_of_tetrahedra =
      mesh_->num_tetrahedra() > 0 ? &mesh_->edges_of_tetrahedron(0) : nullptr;
  const Index* slots = edge_slot_.data();
  const RotationMethod method = parameters_.method;
  constexpr int W = kernels::kLanes<Real>;
  run_schedule(tetrahedron_schedule_, threads_, [&](Index begin, Index end) {
    kernels::ElementBatch<Real> batch;
    Index lane_tetrahedron[W];
    // For the refresh: where each lane's six blocks start and whether the local edge runs from the
    // higher to the lower vertex, for this batch and the next; the next batch's blocks are fetched
    // while this one computes (those of a large mesh live beyond the core's caches).
    struct BlockTargets {
      Real* entry[W][6];
      bool swap[W][6];
    };
    BlockTargets targets[2];
    const auto locate_blocks = [&](Index from, BlockTargets& to) {
      const Index last = std::min<Index>(end, from + W);
      for (Index i = from; i < last; ++i) {
        const auto l = static_cast<std::size_t>(i - from);
        const Index t = tetrahedron_schedule_.order[static_cast<std::size_t>(i)];
        const Tetrahedron tet = internal(tetrahedra[t]);
        const std::array<Index, 6> edges = edges_of_tetrahedra[t];
        for (std::size_t e = 0; e < 6; ++e) {
          Real* entry = blocks + 9 * static_cast<std::size_t>(slots[edges[e]]);
          __builtin_prefetch(entry, 1);
          __builtin_prefetch(entry + 8, 1);
          to.entry[l][e] = entry;
          to.swap[l][e] = tet[static_cast<std::size_t>(kTetrahedronEdges[e][0])] > tet[static_cast<std::size_t>(kTetrahedronEdges[e][1])];
        }
      }
    };
    for (Index first = begin; first < end; first += W) {
      const int count = static_cast<int>(std::min<Index>(W, end - first));
      // Gather: the rest data is the batch's block (groups start at multiples of W); lanes past the
      // end take the first element's points, their rest data is whatever the block holds there,
      // and they are not scattered.
      for (int l = 0; l < W; ++l) {
        lane_tetrahedron[l] = tetrahedron_schedule_.order[static_cast<std::size_t>(first + (l < count ? l : 0))];
      }
      const Real* rest = rest_.data() + rest_index(static_cast<std::size_t>(first), 0);
      if (first + W < end) {
        // The next batch's rest block (kRestValues rows of 64 bytes, contiguous): within a step the
        // products stream the edge blocks through the caches in between, so it is rarely there.
        const char* next = reinterpret_cast<const char*>(rest + kRestValues * W);
        for (std::size_t byte = 0; byte <= kRestValues * W * sizeof(Real); byte += 64) __builtin_prefetch(next + byte);
      }
      for (int j = 0; j < 3; ++j) {
        for (int c = 0; c < 3; ++c) std::copy_n(rest + (3 * j + c) * W, W, batch.s[j + 1][c]);
      }
      std::copy_n(rest + 9 * W, W, batch.mu);
      std::copy_n(rest + 10 * W, W, batch.lambda);
      // Edge vectors d_j = x_{j+1} - x_0, four lanes at a time: each point one load, the differences
      // transposed into the batch's rows.
      for (int g = 0; g < W; g += 4) {
        P points[4][4];  // [vertex][lane - g]
        for (int i = 0; i < 4; ++i) {
          const Tetrahedron tet = internal(tetrahedra[lane_tetrahedron[g + i]]);
          for (int j = 0; j < 4; ++j) points[j][i] = load_packed(padded_x + 4 * tet[static_cast<std::size_t>(j)]);
        }
        for (int j = 0; j < 3; ++j) {
          P dx, dy, dz;
          points_to_lanes(points[j + 1][0] - points[0][0], points[j + 1][1] - points[0][1],
                          points[j + 1][2] - points[0][2], points[j + 1][3] - points[0][3], dx, dy, dz);
          store_packed(&batch.d[j][0][g], dx);
          store_packed(&batch.d[j][1][g], dy);
          store_packed(&batch.d[j][2][g], dz);
        }
      }
      if constexpr (kRefresh) {
        if (first == begin) locate_blocks(first, targets[0]);
        locate_blocks(first + W, targets[(first - begin) / W % 2 == 0 ? 1 : 0]);
        // The mesh data that locating the batch after next will read.
        for (Index i = first + 2 * W; i < std::min<Index>(end, first + 3 * W); ++i) {
          const Index t = tetrahedron_schedule_.order[static_cast<std::size_t>(i)];
          __builtin_prefetch(&tetrahedra[t]);
          __builtin_prefetch(&edges_of_tetrahedra[t]);
        }
      }
      kernels::first_shape_vector(batch);
      if (method == RotationMethod::qr) {
        kernels::qr_frames(batch);
      } else {
        for (int l = 0; l < W; ++l) {
          Real d[3][3], sl[3][3], q[3][3];
          for (int j = 0; j < 3; ++j) {
            for (int c = 0; c < 3; ++c) {
              d[j][c] = batch.d[j][c][l];
              sl[j][c] = batch.s[j + 1][c][l];
            }
          }
          world_to_rest_frame(method, d, sl, q);
          for (int i = 0; i < 3; ++i) {
            for (int c = 0; c < 3; ++c) batch.q[i][c][l] = q[i][c];
          }
        }
      }
      kernels::element_forces(batch);
      // Forces, four lanes at a time: transposed into points, then one load-add-store per vertex
      // (lanes in order, vertices in order within a lane).
      for (int g = 0; g < count; g += 4) {
        P forces[4][4];  // [vertex][lane - g]
        for (int j = 0; j < 4; ++j) {
          lanes_to_points(load_packed(&batch.f[j][0][g]), load_packed(&batch.f[j][1][g]), load_packed(&batch.f[j][2][g]),
                          forces[j]);
        }
        for (int i = 0; i < std::min(4, count - g); ++i) {
          const Tetrahedron tet = internal(tetrahedra[lane_tetrahedron[g + i]]);
          for (int j = 0; j < 4; ++j) {
            Real* to = padded_f + 4 * tet[static_cast<std::size_t>(j)];
            store_packed(to, load_packed(to) + forces[j][i]);
          }
        }
      }
      if constexpr (kRefresh) {
        // Each local edge block goes to its mesh edge's slot.
        kernels::rotated_shapes(batch);
        const BlockTargets& here = targets[(first - begin) / W % 2];
        kernels::edge_diagonals(batch);
        for (int l = 0; l < count; ++l) kernels::add_edge_blocks(batch, l, here.entry[l], here.swap[l]);
      }
    }
  });
  unpad(padded_f, fs);
}

template <class Real>
void CorotationalForceField<Real>::add_dforce(std::span<const Vec3<Real>> dx, std::span<Vec3<Real>> df,
                                              Real k_factor, Real b_factor) const {
  check_size(dx, "dx");
  check_size(df, "df");
  ensure_linearisation();
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  const std::size_t n = dx.size();
  // Points padded to four values: k dx in, the sum of the edge terms out.
  packed_in_.resize(n);
  packed_out_.resize(n);
  Real* in = reinterpret_cast<Real*>(packed_in_.data());
  Real* out = reinterpret_cast<Real*>(packed_out_.data());
  const Real* dx_values = dx.data()->data();
  Real* df_values = df.data()->data();
  const auto edge_terms = [&](Index begin, Index end) {
    if constexpr (kernels::kEdgesInPairs) {
      kernels::add_edge_terms_in_pairs(in, out, blocks_.data(), edge_vertices_.data(), static_cast<std::size_t>(begin),
                                       static_cast<std::size_t>(end));
    } else {
      kernels::add_edge_terms(in, out, blocks_.data(), edge_vertices_.data(), static_cast<std::size_t>(begin),
                              static_cast<std::size_t>(end));
    }
  };
  const ScatterSchedule& s = edge_schedule_;
  if (renumbers_points() || !s.has_first_and_last_points()) {
    pad(dx_values, k, in, out);
    run_schedule(s, threads_, edge_terms);
    unpad(out, df_values);
    return;
  }
  // The point passes inside the schedule's groups, each group padding the points it is the first
  // to touch and adding to df those it is the last to touch: two parallel loops fewer per product,
  // and points padded just before their edges. The passes are elementwise, so the bits are those
  // of the separate passes.
  run_schedule_groups(s, threads_, [&](Index g) {
    const auto [first_begin, first_end] = s.first_points(g);
    kernels::pad_points(dx_values, k, n, in, out, static_cast<std::size_t>(first_begin),
                        static_cast<std::size_t>(first_end));
    edge_terms(s.group_begin[static_cast<std::size_t>(g)], s.group_end[static_cast<std::size_t>(g)]);
    const auto [last_begin, last_end] = s.last_points(g);
    kernels::add_padded_points(out, df_values, static_cast<std::size_t>(last_begin), static_cast<std::size_t>(last_end));
  });
}

template <class Real>
Mat3<Real> CorotationalForceField<Real>::block(Index slot) const {
  Mat3<Real> m;
  for (int i = 0; i < 9; ++i) {
    m.data()[i] = blocks_[9 * static_cast<std::size_t>(slot) + static_cast<std::size_t>(i)];
  }
  return m;
}

template <class Real>
void CorotationalForceField<Real>::add_diagonal_blocks(std::span<Mat3<Real>> diagonal, Real k_factor,
                                                       Real b_factor) const {
  // Row sums of each element's stiffness vanish, so a vertex's diagonal block is minus the sum of
  // its off-diagonal blocks: with block(lo, hi) = -k K^T and block(hi, lo) = -k K for the edge
  // block K oriented from lo to hi, diagonal(lo) += k K^T and diagonal(hi) += k K.
  if (diagonal.size() != static_cast<std::size_t>(mesh_->num_points())) {
    throw make_error("diagonal blocks: ", diagonal.size(), " blocks for a mesh of ", mesh_->num_points(), " points");
  }
  ensure_linearisation();
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  // In add_dforce's schedule (slots of removed edges hold zero blocks and add nothing): a point
  // receives its blocks in the same order on any thread count.
  run_schedule(edge_schedule_, threads_, [&](Index begin, Index end) {
    for (Index slot = begin; slot < end; ++slot) {
      const Edge& edge = edge_vertices_[static_cast<std::size_t>(slot)];
      const Mat3<Real> block = k * this->block(slot);
      diagonal[static_cast<std::size_t>(mesh_point(edge[0]))] += block.transpose();
      diagonal[static_cast<std::size_t>(mesh_point(edge[1]))] += block;
    }
  });
}

template <class Real>
void CorotationalForceField<Real>::add_stiffness(MatrixSink<Real>& sink, Real k_factor, Index offset,
                                                 Real b_factor) const {
  std::vector<Mat3<Real>> diagonal(static_cast<std::size_t>(mesh_->num_points()), Mat3<Real>::Zero());
  add_diagonal_blocks(diagonal, k_factor, b_factor);
  const Real k = k_factor + b_factor * parameters_.rayleigh_stiffness;
  std::vector<bool> used(diagonal.size(), false);
  for (const Index slot : edge_slot_) {
    const Index a = mesh_point(edge_vertices_[static_cast<std::size_t>(slot)][0]);
    const Index b = mesh_point(edge_vertices_[static_cast<std::size_t>(slot)][1]);
    const Mat3<Real> block = k * this->block(slot);
    used[static_cast<std::size_t>(a)] = used[static_cast<std::size_t>(b)] = true;
    sink.add_block(offset + 3 * a, offset + 3 * b, -block.transpose());
    sink.add_block(offset + 3 * b, offset + 3 * a, -block);
  }
  for (std::size_t v = 0; v < diagonal.size(); ++v) {
    if (used[v]) sink.add_block(offset + 3 * static_cast<Index>(v), offset + 3 * static_cast<Index>(v), diagonal[v]);
  }
}

template <class Real>
std::vector<double> CorotationalForceField<Real>::model_values() const {
  std::vector<double> values(parameters_.young_modulus.begin(), parameters_.young_modulus.end());
  values.insert(values.end(), parameters_.poisson_ratio.begin(), parameters_.poisson_ratio.end());
  values.push_back(static_cast<double>(parameters_.method));
  values.push_back(static_cast<double>(parameters_.rayleigh_stiffness));
  return values;
}

template <class Real>
Real CorotationalForceField<Real>::potential_energy(std::span<const Vec3<Real>> x) const {
  check_size(x, "x");
  Real energy = 0;
  const auto tetrahedra = mesh_->tetrahedra();
  for (std::size_t t = 0; t < tetrahedra.size(); ++t) {
    const TetrahedronRest<Real> rest = element_rest(static_cast<Index>(t));
    const auto p = tetrahedron_points<Real>(tetrahedra[t], rest_positions_);
    const auto xt = tetrahedron_points(tetrahedra[t], x);
    const Mat3<Real> r = tetrahedron_rotation(rest, xt, parameters_.method);
    energy += tetrahedron_energy(rest, p, xt, r);
  }
  return energy;
}

template <class Real>
std::vector<Mat3<Real>> CorotationalForceField<Real>::rotations() const {
  std::vector<Mat3<Real>> result(static_cast<std::size_t>(mesh_->num_tetrahedra()), Mat3<Real>::Identity());
  if (last_positions_.empty()) return result;
  for (std::size_t t = 0; t < result.size(); ++t) {
    const auto xt = tetrahedron_points<Real>(mesh_->tetrahedron(static_cast<Index>(t)), last_positions_);
    result[t] = tetrahedron_rotation(element_rest(static_cast<Index>(t)), xt, parameters_.method);
  }
  return result;
}

template <class Real>
std::vector<Real> CorotationalForceField<Real>::rest_volumes() const {
  std::vector<Real> volumes;
  volumes.reserve(static_cast<std::size_t>(mesh_->num_tetrahedra()));
  for (const Tetrahedron& tet : mesh_->tetrahedra()) {
    volumes.push_back(signed_volume(tetrahedron_points<Real>(tet, rest_positions_)));
  }
  return volumes;
}

template <class Real>
std::vector<Mat3<Real>> CorotationalForceField<Real>::edge_stiffness() const {
  ensure_linearisation();
  const auto edges = mesh_->edges();
  std::vector<Mat3<Real>> result(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Mat3<Real> block = this->block(edge_slot_[e]);
    result[e] = internal(edges[e][0]) < internal(edges[e][1]) ? block : Mat3<Real>(block.transpose());
  }
  return result;
}

template <class Real>
std::size_t CorotationalForceField<Real>::memory_bytes() const {
  const auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  const auto schedule_bytes = [&](const ScatterSchedule& s) {
    return bytes(s.order) + bytes(s.group_begin) + bytes(s.group_end) + bytes(s.part_begin);
  };
  std::size_t free_bytes = bytes(free_slots_);
  for (const auto& slots : free_slots_) free_bytes += bytes(slots);
  return bytes(rest_positions_) + bytes(rest_) + bytes(blocks_) +
         bytes(edge_slot_) + bytes(edge_vertices_) + bytes(position_) + free_bytes +
         bytes(packed_in_) + bytes(packed_out_) +
         schedule_bytes(tetrahedron_schedule_) + schedule_bytes(edge_schedule_) + bytes(last_positions_) +
         bytes(internal_point_) + bytes(mesh_point_) +
         sizeof(*this);
}

template <class Real>
void CorotationalForceField<Real>::update_topology_information() {
  mesh_->update_topology_information();
  rebuild();
}

template class CorotationalForceField<float>;
template class CorotationalForceField<double>;

}  // namespace fastcorot
