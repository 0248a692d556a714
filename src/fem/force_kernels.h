// The inner loops of CorotationalForceField on plain scalars, for a batch of kLanes tetrahedra at
// once: every quantity is an array over the batch, and each formula is a loop over the lanes that
// the compiler turns into SIMD instructions (`omp simd`; one simple loop per quantity, which GCC
// vectorises reliably). The formulas are those of SPEC.md written in the rest frame of the rotation
// method (corotational_force_field.h explains the frame). Internal to src/fem.
#pragma once

#include <cmath>
#include <cstddef>

namespace fastcorot::kernels {

// Two AVX2 registers per quantity: enough independent work to hide the latency of sqrt and division.
template <class Real>
inline constexpr int kLanes = 64 / sizeof(Real);

// Edge blocks are stored in groups of kEdgeLanes edges (one AVX2 register), entry i of the edge in
// lane l of a group at group[i * kEdgeLanes + l]: add_dforce loads each entry of a whole group at once.
template <class Real>
inline constexpr int kEdgeLanes = 32 / sizeof(Real);

template <class Real>
inline std::size_t edge_block_offset(std::size_t slot, int i) {
  constexpr auto L = static_cast<std::size_t>(kEdgeLanes<Real>);
  return (slot / L) * 9 * L + static_cast<std::size_t>(i) * L + slot % L;
}

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
  alignas(64) Real block[9][W];   // one edge block, column-major
  bool swap[W];                   // the edge's lower vertex is local vertex l, not k
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

// The block of local edge (k, l) oriented from its lower vertex u to its higher one v (u = k unless
// swap): lambda r_v r_u^T + mu r_u r_v^T + mu (s~_k . s~_l) I.
template <class Real>
inline void edge_block(ElementBatch<Real>& b, int k, int l_vertex) {
  constexpr int W = ElementBatch<Real>::W;
  const auto& sk = b.s[k];
  const auto& sl = b.s[l_vertex];
  alignas(64) Real ru[3][W], rv[3][W];
  for (int c = 0; c < 3; ++c) {
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      ru[c][l] = b.swap[l] ? b.r[l_vertex][c][l] : b.r[k][c][l];
      rv[c][l] = b.swap[l] ? b.r[k][c][l] : b.r[l_vertex][c][l];
    }
  }
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        b.block[3 * col + row][l] = b.lambda[l] * rv[row][l] * ru[col][l] + b.mu[l] * ru[row][l] * rv[col][l];
      }
    }
  }
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    const Real diagonal = b.mu[l] * (sk[0][l] * sl[0][l] + sk[1][l] * sl[1][l] + sk[2][l] * sl[2][l]);
    b.block[0][l] += diagonal;
    b.block[4][l] += diagonal;
    b.block[8][l] += diagonal;
  }
}

// For one group of kEdgeLanes edges with blocks K (grouped layout) and w = dx_v - dx_u per lane:
// kw = K (k w) and ktw = K^T (k w).
template <class Real>
inline void edge_products(const Real* group, Real k, const Real (&w)[3][kEdgeLanes<Real>],
                          Real (&kw)[3][kEdgeLanes<Real>], Real (&ktw)[3][kEdgeLanes<Real>]) {
  constexpr int L = kEdgeLanes<Real>;
  const auto m = [&](int i, int l) { return group[i * L + l]; };
#pragma omp simd
  for (int l = 0; l < L; ++l) {
    const Real w0 = k * w[0][l], w1 = k * w[1][l], w2 = k * w[2][l];
    kw[0][l] = m(0, l) * w0 + m(3, l) * w1 + m(6, l) * w2;
    kw[1][l] = m(1, l) * w0 + m(4, l) * w1 + m(7, l) * w2;
    kw[2][l] = m(2, l) * w0 + m(5, l) * w1 + m(8, l) * w2;
    ktw[0][l] = m(0, l) * w0 + m(1, l) * w1 + m(2, l) * w2;
    ktw[1][l] = m(3, l) * w0 + m(4, l) * w1 + m(5, l) * w2;
    ktw[2][l] = m(6, l) * w0 + m(7, l) * w1 + m(8, l) * w2;
  }
}

}  // namespace fastcorot::kernels
