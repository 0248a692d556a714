// The inner loops of CorotationalForceField on plain scalars. Forces and the stiffness refresh work
// on a batch of kLanes tetrahedra at once: every quantity is an array over the batch, and each
// formula is a loop over the lanes that the compiler turns into SIMD instructions (`omp simd`; one
// simple loop per quantity, which GCC vectorises reliably). Where whole vectors of one tetrahedron
// or point go to memory, a Packed register holds three coordinates and a spare lane instead: the
// refresh adds each tetrahedron's edge blocks that way (add_edge_blocks), and add_dforce works on
// points throughout (add_edge_terms). The formulas
// are those of SPEC.md written in the rest frame of the rotation method (corotational_force_field.h
// explains the frame). Internal to src/fem.
#pragma once

#include "fastcorot/core/packed.h"
#include "fastcorot/topology/tet_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

namespace fastcorot::kernels {

// Two AVX2 registers per quantity: enough independent work to hide the latency of sqrt and division.
template <class Real>
inline constexpr int kLanes = 64 / sizeof(Real);

// Edge blocks are 3×3 column-major, nine values per slot; a column is read as four values, so the
// block array ends with kBlockTail spare zeros after its last block.
inline constexpr std::size_t kBlockTail = 3;

template <class Real>
struct ElementBatch {
  static constexpr int W = kLanes<Real>;
  alignas(64) Real d[3][3][W];    // current edge vectors d_j = x_{j+1} - x0
  alignas(64) Real s[4][3][W];    // rest-frame shape vectors s~_0..s~_3 (s~_0 = -(s~_1 + s~_2 + s~_3))
  alignas(64) Real mu[W];
  alignas(64) Real lambda[W];
  alignas(64) Real q[3][3][W];    // rows: world to rest frame
  alignas(64) Real local[3][3][W];  // Q d_j
  alignas(64) Real stress[3][3][W];
  alignas(64) Real f[4][3][W];    // forces on the four vertices
  alignas(64) Real r[4][3][W];    // rotated shape vectors Q^T s~_j
  alignas(64) Real diagonal[6][W];  // per local edge: mu (s~_k . s~_m)
  alignas(64) Real corner[6][W];    // per local edge: its block's entry (2, 2)
};

// s~_0 = -(s~_1 + s~_2 + s~_3).
template <class Real>
inline void first_shape_vector(ElementBatch<Real>& b) {
  constexpr int W = ElementBatch<Real>::W;
  for (int c = 0; c < 3; ++c) {
#pragma omp simd
    for (int l = 0; l < W; ++l) b.s[0][c][l] = -(b.s[1][c][l] + b.s[2][c][l] + b.s[3][c][l]);
  }
}

// q = SOFA's QR frame of (d_1, d_2): rows e1 = a / |a|, e3 = (a × b) / |a × b|, e2 = e3 × e1 (the
// direction of e1 × b is that of a × b; computing it from a lets both square roots run at once).
// A zero vector stays zero, as with Eigen's normalized().
template <class Real>
inline void qr_frames(ElementBatch<Real>& b) {
  constexpr int W = ElementBatch<Real>::W;
  const auto& a = b.d[0];
  const auto& c = b.d[1];
  auto& q = b.q;
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    const Real na = a[0][l] * a[0][l] + a[1][l] * a[1][l] + a[2][l] * a[2][l];
    const Real z0 = a[1][l] * c[2][l] - a[2][l] * c[1][l];
    const Real z1 = a[2][l] * c[0][l] - a[0][l] * c[2][l];
    const Real z2 = a[0][l] * c[1][l] - a[1][l] * c[0][l];
    const Real nz = z0 * z0 + z1 * z1 + z2 * z2;
    const Real ia = Real(1) / std::sqrt(na > 0 ? na : Real(1));
    const Real iz = Real(1) / std::sqrt(nz > 0 ? nz : Real(1));
    q[0][0][l] = a[0][l] * ia;
    q[0][1][l] = a[1][l] * ia;
    q[0][2][l] = a[2][l] * ia;
    q[2][0][l] = z0 * iz;
    q[2][1][l] = z1 * iz;
    q[2][2][l] = z2 * iz;
    q[1][0][l] = q[2][1][l] * q[0][2][l] - q[2][2][l] * q[0][1][l];
    q[1][1][l] = q[2][2][l] * q[0][0][l] - q[2][0][l] * q[0][2][l];
    q[1][2][l] = q[2][0][l] * q[0][1][l] - q[2][1][l] * q[0][0][l];
  }
}

// Forces. H = sum_j (Q d_j) s~_j^T - I, stress = mu (H + H^T) + lambda tr(H) I, M = Q^T stress;
// vertex j gets -M s~_j (j = 0..3).
template <class Real>
inline void element_forces(ElementBatch<Real>& b) {
  constexpr int W = ElementBatch<Real>::W;
  const auto& q = b.q;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        b.local[j][i][l] = q[i][0][l] * b.d[j][0][l] + q[i][1][l] * b.d[j][1][l] + q[i][2][l] * b.d[j][2][l];
      }
    }
  }
  // H[i][m] = sum_j local[j][i] s~_{j+1}[m] - delta; the stress is symmetric.
  const auto h = [&](int i, int m, int l) {
    return b.local[0][i][l] * b.s[1][m][l] + b.local[1][i][l] * b.s[2][m][l] + b.local[2][i][l] * b.s[3][m][l];
  };
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    const Real h00 = h(0, 0, l) - 1, h11 = h(1, 1, l) - 1, h22 = h(2, 2, l) - 1;
    const Real volumetric = b.lambda[l] * (h00 + h11 + h22);
    const Real mu2 = 2 * b.mu[l];
    b.stress[0][0][l] = mu2 * h00 + volumetric;
    b.stress[1][1][l] = mu2 * h11 + volumetric;
    b.stress[2][2][l] = mu2 * h22 + volumetric;
    b.stress[0][1][l] = b.stress[1][0][l] = b.mu[l] * (h(0, 1, l) + h(1, 0, l));
    b.stress[0][2][l] = b.stress[2][0][l] = b.mu[l] * (h(0, 2, l) + h(2, 0, l));
    b.stress[1][2][l] = b.stress[2][1][l] = b.mu[l] * (h(1, 2, l) + h(2, 1, l));
  }
  // M = Q^T stress, kept in `local` (no longer needed).
  auto& m = b.local;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        m[i][k][l] = q[0][i][l] * b.stress[0][k][l] + q[1][i][l] * b.stress[1][k][l] + q[2][i][l] * b.stress[2][k][l];
      }
    }
  }
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 3; ++i) {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        b.f[j][i][l] = -(m[i][0][l] * b.s[j][0][l] + m[i][1][l] * b.s[j][1][l] + m[i][2][l] * b.s[j][2][l]);
      }
    }
  }
}

// r_j = Q^T s~_j for the four vertices.
template <class Real>
inline void rotated_shapes(ElementBatch<Real>& b) {
  constexpr int W = ElementBatch<Real>::W;
  const auto& q = b.q;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 3; ++i) {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        b.r[j][i][l] = q[0][i][l] * b.s[j][0][l] + q[1][i][l] * b.s[j][1][l] + q[2][i][l] * b.s[j][2][l];
      }
    }
  }
}

// Per local edge e = (k, m) of kTetrahedronEdges: the diagonal term mu (s~_k . s~_m) of its block
// and the block's last entry, (lambda + mu) r_k[2] r_m[2] plus that term (the same for either
// orientation).
template <class Real>
inline void edge_diagonals(ElementBatch<Real>& b) {
  constexpr int W = ElementBatch<Real>::W;
  for (int e = 0; e < 6; ++e) {
    const int k = kTetrahedronEdges[static_cast<std::size_t>(e)][0];
    const int m = kTetrahedronEdges[static_cast<std::size_t>(e)][1];
    const auto& sk = b.s[k];
    const auto& sm = b.s[m];
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const Real diagonal = b.mu[l] * (sk[0][l] * sm[0][l] + sk[1][l] * sm[1][l] + sk[2][l] * sm[2][l]);
      b.diagonal[e][l] = diagonal;
      b.corner[e][l] = b.lambda[l] * b.r[m][2][l] * b.r[k][2][l] + b.mu[l] * b.r[k][2][l] * b.r[m][2][l] + diagonal;
    }
  }
}

// Adds lane l's six edge blocks into the block array: the block of local edge e, oriented from its
// lower vertex u to its higher one v (from k to m unless swap[e]), at entry[e] (nine values,
// column-major): lambda r_v r_u^T + mu r_u r_v^T + mu (s~_k . s~_m) I. Entries 0..7 are one sum of
// eight-value products of permuted rotated shape vectors (in double one AVX-512 register, or two
// AVX2 halves on CPUs without it; in float one AVX register), entry 8 is the batch's corner.
template <class Real>
inline void add_edge_blocks(const ElementBatch<Real>& b, int l, Real* const (&entry)[6], const bool (&swap)[6]) {
  typedef Real Eight __attribute__((vector_size(8 * sizeof(Real))));
  // With r = (x, y, z), entry i + 3 j (i, j < 3) is lambda v_i u_j + mu u_i v_j: the eight first
  // are lambda (v_x, v_y, v_z, v_x, v_y, v_z, v_x, v_y) * (u_x, u_x, u_x, u_y, u_y, u_y, u_z, u_z)
  // + mu (u_x, u_y, ...) * (v_x, v_x, ...).
  Eight lambda_rows[4], mu_rows[4], columns[4];
  for (int j = 0; j < 4; ++j) {
    const Real x = b.r[j][0][l], y = b.r[j][1][l], z = b.r[j][2][l];
    const Eight rows = {x, y, z, x, y, z, x, y};
    lambda_rows[j] = b.lambda[l] * rows;
    mu_rows[j] = b.mu[l] * rows;
    columns[j] = Eight{x, x, x, y, y, y, z, z};
  }
  for (int e = 0; e < 6; ++e) {
    const int k = kTetrahedronEdges[static_cast<std::size_t>(e)][0];
    const int m = kTetrahedronEdges[static_cast<std::size_t>(e)][1];
    const int u = swap[e] ? m : k, v = swap[e] ? k : m;
    const Real d = b.diagonal[e][l];
    const Eight diagonal = {d, 0, 0, 0, d, 0, 0, 0};
    Real* to = entry[e];
    Eight sum;
    std::memcpy(&sum, to, sizeof sum);
    // (Grouped so that both products fuse into multiply-adds.)
    sum += lambda_rows[v] * columns[u] + (mu_rows[u] * columns[v] + diagonal);
    std::memcpy(to, &sum, sizeof sum);
    to[8] += b.corner[e][l];
  }
}

// For the points [begin, end) of an array `from` of `count` points of three values: to[i] =
// (scale x, scale y, scale z, 0) and zeroed[i] = 0, four values each. One four-value load per point,
// but for the array's last point, which nothing follows.
template <class Real>
inline void pad_points(const Real* from, Real scale, std::size_t count, Real* to, Real* zeroed, std::size_t begin,
                       std::size_t end) {
  using P = Packed<Real>;
  const std::size_t whole = std::min(end, count - 1);
  std::size_t i = begin;
  for (; i < whole; ++i) {
    store_packed(to + 4 * i, __builtin_shufflevector(load_packed(from + 3 * i) * scale, P{}, 0, 1, 2, 4));
    store_packed(zeroed + 4 * i, P{});
  }
  for (; i < end; ++i) {
    store_packed(to + 4 * i, P{scale * from[3 * i], scale * from[3 * i + 1], scale * from[3 * i + 2], Real(0)});
    store_packed(zeroed + 4 * i, P{});
  }
}

// The reverse of pad_points: to[i] += the first three of the four values padded[i], for the points
// [begin, end).
template <class Real>
inline void add_padded_points(const Real* padded, Real* to, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    for (std::size_t c = 0; c < 3; ++c) to[3 * i + c] += padded[4 * i + c];
  }
}

// pad_points and add_padded_points for a force field with its own point order: point i of `from`
// and `to` is padded point internal[i].
template <class Real>
inline void pad_points_renumbered(const Real* from, Real scale, const Index* internal, Real* to, Real* zeroed,
                                  std::size_t begin, std::size_t end) {
  using P = Packed<Real>;
  for (std::size_t i = begin; i < end; ++i) {
    const auto j = static_cast<std::size_t>(internal[i]);
    store_packed(to + 4 * j, P{scale * from[3 * i], scale * from[3 * i + 1], scale * from[3 * i + 2], Real(0)});
    store_packed(zeroed + 4 * j, P{});
  }
}

template <class Real>
inline void add_padded_points_renumbered(const Real* padded, const Index* internal, Real* to, std::size_t begin,
                                         std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    const Real* from = padded + 4 * static_cast<std::size_t>(internal[i]);
    for (std::size_t c = 0; c < 3; ++c) to[3 * i + c] += from[c];
  }
}

// One edge (u, v) in slot `slot` of add_dforce's loops: out[v] += K w with w = in[v] - x_u, and the
// lane-wise products of K's columns with w added to u's running sums t0..t2.
template <class Real>
[[gnu::always_inline]] inline void add_edge_term(const Real* __restrict in, Real* __restrict out,
                                                 const Real* __restrict blocks, std::size_t v, std::size_t slot,
                                                 const Packed<Real>& x_u, Packed<Real>& t0, Packed<Real>& t1,
                                                 Packed<Real>& t2) {
  using P = Packed<Real>;
  const P w = load_packed(in + 4 * v) - x_u;
  const Real* block = blocks + 9 * slot;
  const P c0 = load_packed(block), c1 = load_packed(block + 3), c2 = load_packed(block + 6);
  store_packed(out + 4 * v,
               load_packed(out + 4 * v) + (c0 * broadcast(w[0]) + c1 * broadcast(w[1]) + c2 * broadcast(w[2])));
  t0 += c0 * w;
  t1 += c1 * w;
  t2 += c2 * w;
}

// add_dforce over the edge slots [begin, end) (sorted by lower vertex u), on points padded to four
// values: `in` holds k dx, `out` receives the sums. For the edge (u, v) with block K and
// w = in[v] - in[u]: out[v] += K w at once, and u's share -K^T w summed along u's run, K^T w being
// (c_0.w, c_1.w, c_2.w) for the columns c_j of K: lane-wise products summed over the run, then over
// the lanes. Never inlined and with restrict pointers: inlined into the schedule's lambda, GCC kept
// w on the stack between iterations (a store and a reload on the critical path of every edge).
template <class Real, class Pair>
[[gnu::noinline]] void add_edge_terms(const Real* __restrict in, Real* __restrict out, const Real* __restrict blocks,
                                      const Pair* __restrict vertices, std::size_t begin, std::size_t end) {
  using P = Packed<Real>;
  for (std::size_t slot = begin; slot < end;) {
    const auto u = static_cast<std::size_t>(vertices[slot][0]);
    const P x_u = load_packed(in + 4 * u);
    P t0{}, t1{}, t2{};
    do {
      add_edge_term(in, out, blocks, static_cast<std::size_t>(vertices[slot][1]), slot, x_u, t0, t1, t2);
      ++slot;
    } while (slot < end && static_cast<std::size_t>(vertices[slot][0]) == u);
    const P share = {t0[0] + t0[1] + t0[2], t1[0] + t1[1] + t1[2], t2[0] + t2[1] + t2[2], Real(0)};
    const P total = load_packed(out + 4 * u) - share;
    store_packed(out + 4 * u, total);
  }
}

// Whether add_dforce takes the edges two at a time (add_edge_terms_in_pairs): in builds with
// AVX-512, where it measured 15 % faster per edge (a Zen 5 VM, 2026-12-02); on the earlier VMs
// without AVX-512, a standalone version of it measured slower than one edge at a time.
#if defined(__AVX512F__)
inline constexpr bool kEdgesInPairs = true;
#else
inline constexpr bool kEdgesInPairs = false;
#endif

// add_edge_terms two edges of a run at a time in one eight-value register (each edge's four values
// in one half): the same K w for every edge, added to out[v] in the same order; u's share summed
// over the run's odd and even edges apart, then together.
template <class Real, class Pair>
[[gnu::noinline]] void add_edge_terms_in_pairs(const Real* __restrict in, Real* __restrict out,
                                               const Real* __restrict blocks, const Pair* __restrict vertices,
                                               std::size_t begin, std::size_t end) {
  using P = Packed<Real>;
  typedef Real Two __attribute__((vector_size(8 * sizeof(Real))));
  const auto join = [](const P& a, const P& b) { return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7); };
  for (std::size_t slot = begin; slot < end;) {
    const auto u = static_cast<std::size_t>(vertices[slot][0]);
    const P x_u = load_packed(in + 4 * u);
    const Two x_uu = join(x_u, x_u);
    Two t0{}, t1{}, t2{};
    // (After topological changes a lower vertex may have runs apart: both edges are checked.)
    for (; slot + 1 < end && static_cast<std::size_t>(vertices[slot][0]) == u &&
           static_cast<std::size_t>(vertices[slot + 1][0]) == u;
         slot += 2) {
      const auto v1 = static_cast<std::size_t>(vertices[slot][1]);
      const auto v2 = static_cast<std::size_t>(vertices[slot + 1][1]);
      const Two w = join(load_packed(in + 4 * v1), load_packed(in + 4 * v2)) - x_uu;
      const Real* block = blocks + 9 * slot;
      const Two c0 = join(load_packed(block), load_packed(block + 9));
      const Two c1 = join(load_packed(block + 3), load_packed(block + 12));
      const Two c2 = join(load_packed(block + 6), load_packed(block + 15));
      const Two wx = __builtin_shufflevector(w, w, 0, 0, 0, 0, 4, 4, 4, 4);
      const Two wy = __builtin_shufflevector(w, w, 1, 1, 1, 1, 5, 5, 5, 5);
      const Two wz = __builtin_shufflevector(w, w, 2, 2, 2, 2, 6, 6, 6, 6);
      const Two kw = c0 * wx + c1 * wy + c2 * wz;
      store_packed(out + 4 * v1, load_packed(out + 4 * v1) + __builtin_shufflevector(kw, kw, 0, 1, 2, 3));
      store_packed(out + 4 * v2, load_packed(out + 4 * v2) + __builtin_shufflevector(kw, kw, 4, 5, 6, 7));
      t0 += c0 * w;
      t1 += c1 * w;
      t2 += c2 * w;
    }
    P s0 = __builtin_shufflevector(t0, t0, 0, 1, 2, 3) + __builtin_shufflevector(t0, t0, 4, 5, 6, 7);
    P s1 = __builtin_shufflevector(t1, t1, 0, 1, 2, 3) + __builtin_shufflevector(t1, t1, 4, 5, 6, 7);
    P s2 = __builtin_shufflevector(t2, t2, 0, 1, 2, 3) + __builtin_shufflevector(t2, t2, 4, 5, 6, 7);
    if (slot < end && static_cast<std::size_t>(vertices[slot][0]) == u) {  // a run's last, odd edge
      add_edge_term(in, out, blocks, static_cast<std::size_t>(vertices[slot][1]), slot, x_u, s0, s1, s2);
      ++slot;
    }
    const P share = {s0[0] + s0[1] + s0[2], s1[0] + s1[1] + s1[2], s2[0] + s2[1] + s2[2], Real(0)};
    store_packed(out + 4 * u, load_packed(out + 4 * u) - share);
  }
}

}  // namespace fastcorot::kernels
