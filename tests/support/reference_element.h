// The straightforward per-edge element of SPEC.md, written literally, as the reference that the
// library's optimised kernels are checked against: for each local edge e = (k, l),
// u_e = R^T (x_l - x_k) - (p_l - p_k), g_l += L_e u_e, g_k -= L_e^T u_e, then f_j = R g_j and
// U = -1/2 sum_j u_j . g_j with u_j = R^T (x_j - x0) - (p_j - p0).
#pragma once

#include "fastcorot/fem/tetrahedron_element.h"
#include "fastcorot/topology/tet_mesh.h"

namespace fastcorot::testing {

template <class Real>
TetPoints<Real> reference_rest_frame_force(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p,
                                           const TetPoints<Real>& x, const Mat3<Real>& rotation) {
  TetPoints<Real> g;
  for (auto& v : g) v.setZero();
  for (int e = 0; e < 6; ++e) {
    const int k = kTetrahedronEdges[e][0];
    const int l = kTetrahedronEdges[e][1];
    const Vec3<Real> u = rotation.transpose() * (x[l] - x[k]) - (p[l] - p[k]);
    const Mat3<Real> block = edge_block(rest, e);
    g[l] += block * u;
    g[k] -= block.transpose() * u;
  }
  return g;
}

template <class Real>
TetPoints<Real> reference_force(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p,
                                const TetPoints<Real>& x, const Mat3<Real>& rotation) {
  TetPoints<Real> f = reference_rest_frame_force(rest, p, x, rotation);
  for (auto& v : f) v = rotation * v;
  return f;
}

template <class Real>
Real reference_energy(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p, const TetPoints<Real>& x,
                      const Mat3<Real>& rotation) {
  const TetPoints<Real> g = reference_rest_frame_force(rest, p, x, rotation);
  Real energy = 0;
  for (int j = 1; j < 4; ++j) energy -= (rotation.transpose() * (x[j] - x[0]) - (p[j] - p[0])).dot(g[j]);
  return energy / 2;
}

}  // namespace fastcorot::testing
