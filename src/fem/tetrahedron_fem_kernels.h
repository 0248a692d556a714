// TetrahedronFEMForceField's element arithmetic (the `large`, `polar` and `svd` methods without
// plasticity or updateStiffnessMatrix) on a batch of kLanes tetrahedra at once, in the manner of
// force_kernels.h: every quantity an array over the batch, each formula a loop over the lanes that
// the compiler turns into SIMD instructions. Each lane does the same operations in the same order,
// so a tetrahedron's results do not depend on the batch it falls in (nor on the thread count).
// The formulas are TetrahedronFEMForceField's (tetrahedron_fem_force_field.h): D the rest positions
// minus the current ones in the element's frame, the force R J K J^T D, and the gradients in the
// world w = R g that the stiffness blocks are made of. Internal to src/fem.
#pragma once

namespace fastcorot::tetrahedron_fem_kernels {

template <class Real>
inline constexpr int kLanes = 64 / sizeof(Real);

template <class Real>
struct Batch {
  static constexpr int W = kLanes<Real>;
  alignas(64) Real p[4][3][W];      // current positions
  alignas(64) Real frame[3][3][W];  // world to the element's frame, by rows (R^T)
  alignas(64) Real rest[4][3][W];   // rest positions in the element's rest frame
  alignas(64) Real g[4][3][W];      // J's three values per vertex
  alignas(64) Real k[3][W];         // K's three values
  alignas(64) Real d[4][3][W];      // displacements in the frame
  alignas(64) Real force[4][3][W];  // out: forces in the world
  alignas(64) Real w[4][3][W];      // out: R g per vertex
};

// v in the frame: row r of `frame` times v, ((f_r0 v0 + f_r1 v1) + f_r2 v2), in lane l.
template <class Real, int W>
inline Real frame_times(const Real (&frame)[3][3][W], const Real (&v)[3][W], int r, int l) {
  return frame[r][0][l] * v[0][l] + frame[r][1][l] * v[1][l] + frame[r][2][l] * v[2][l];
}

// v back in the world: column r of `frame` (row r of R) times v, in lane l.
template <class Real, int W>
inline Real frame_transpose_times(const Real (&frame)[3][3][W], const Real (&v)[3][W], int r, int l) {
  return frame[0][r][l] * v[0][l] + frame[1][r][l] * v[1][l] + frame[2][r][l] * v[2][l];
}

// `large`: SOFA's frame puts vertex 1 on the x axis and vertex 2 in the xy plane, whose other
// coordinates it takes as exactly zero, relative to vertex 0 (whose displacement is zero).
template <class Real>
inline void displacements(Batch<Real>& b, bool large) {
  constexpr int W = Batch<Real>::W;
  Real deformed[4][3][W];
  for (int i = 0; i < 4; ++i) {
    for (int r = 0; r < 3; ++r) {
#pragma omp simd
      for (int l = 0; l < W; ++l) deformed[i][r][l] = frame_times(b.frame, b.p[i], r, l);
    }
  }
  if (!large) {
    for (int i = 0; i < 4; ++i) {
      for (int r = 0; r < 3; ++r) {
#pragma omp simd
        for (int l = 0; l < W; ++l) b.d[i][r][l] = b.rest[i][r][l] - deformed[i][r][l];
      }
    }
    return;
  }
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    b.d[0][0][l] = b.d[0][1][l] = b.d[0][2][l] = 0;
    b.d[1][0][l] = b.rest[1][0][l] - (deformed[1][0][l] - deformed[0][0][l]);
    b.d[1][1][l] = b.d[1][2][l] = 0;
    b.d[2][0][l] = b.rest[2][0][l] - (deformed[2][0][l] - deformed[0][0][l]);
    b.d[2][1][l] = b.rest[2][1][l] - (deformed[2][1][l] - deformed[0][1][l]);
    b.d[2][2][l] = 0;
    for (int r = 0; r < 3; ++r) b.d[3][r][l] = b.rest[3][r][l] - (deformed[3][r][l] - deformed[0][r][l]);
  }
}

// The forces J K J^T D in the frame (element_force's order of operations), rotated to the world,
// and R g.
template <class Real>
inline void forces(Batch<Real>& b, bool large) {
  constexpr int W = Batch<Real>::W;
  displacements(b, large);
  Real s[6][W];
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    Real e[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 4; ++i) {
      const Real gx = b.g[i][0][l], gy = b.g[i][1][l], gz = b.g[i][2][l];
      const Real dx = b.d[i][0][l], dy = b.d[i][1][l], dz = b.d[i][2][l];
      e[0] += gx * dx;
      e[1] += gy * dy;
      e[2] += gz * dz;
      e[3] += gy * dx + gx * dy;
      e[4] += gz * dy + gy * dz;
      e[5] += gz * dx + gx * dz;
    }
    const Real k0 = b.k[0][l], k1 = b.k[1][l], k2 = b.k[2][l];
    s[0][l] = k0 * e[0] + k1 * e[1] + k1 * e[2];
    s[1][l] = k1 * e[0] + k0 * e[1] + k1 * e[2];
    s[2][l] = k1 * e[0] + k1 * e[1] + k0 * e[2];
    s[3][l] = k2 * e[3];
    s[4][l] = k2 * e[4];
    s[5][l] = k2 * e[5];
  }
  for (int i = 0; i < 4; ++i) {
    Real local[3][W];
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const Real gx = b.g[i][0][l], gy = b.g[i][1][l], gz = b.g[i][2][l];
      local[0][l] = gx * s[0][l] + gy * s[3][l] + gz * s[5][l];
      local[1][l] = gy * s[1][l] + gx * s[3][l] + gz * s[4][l];
      local[2][l] = gz * s[2][l] + gy * s[4][l] + gx * s[5][l];
    }
    for (int r = 0; r < 3; ++r) {
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        b.force[i][r][l] = frame_transpose_times(b.frame, local, r, l);
        b.w[i][r][l] = frame_transpose_times(b.frame, b.g[i], r, l);
      }
    }
  }
}

}  // namespace fastcorot::tetrahedron_fem_kernels
