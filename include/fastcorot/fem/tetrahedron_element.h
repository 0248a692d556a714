// One corotational linear tetrahedron, as free functions of its four rest points p0..p3 and four
// current points x0..x3, with no mesh or scene: rest data, rotation, forces, energy and the 3×3
// stiffness blocks of SPEC.md. The force field applies these over a mesh; tests and other codes can
// call them on a single element. Forces are in world coordinates; the per-element rotation R maps
// the rest frame to the world.
#pragma once

#include "fastcorot/core/lame.h"
#include "fastcorot/core/types.h"
#include "fastcorot/fem/rotation_method.h"
#include "fastcorot/topology/tet_mesh.h"

#include <array>

namespace fastcorot {

template <class Real>
using TetPoints = std::array<Vec3<Real>, 4>;

// What an element keeps from its rest state (SPEC.md, "Rest state").
template <class Real>
struct TetrahedronRest {
  std::array<Vec3<Real>, 4> shape;  // s_j: gradient of the barycentric coordinate of vertex j
  Real volume;                      // V = -dot(p1-p0, (p2-p0) × (p3-p0)) / 6 (SOFA's sign)
  Real mu;                          // mu |V|
  Real lambda;                      // lambda |V|
  Mat3<Real> rest_rotation;         // R0 for qr and polar2, identity otherwise
};

// Rest data of the element with rest points p. The caller checks that V is not (near) zero.
template <class Real>
TetrahedronRest<Real> tetrahedron_rest(const TetPoints<Real>& p, const LameParameters<Real>& lame,
                                       RotationMethod method);

// D_j = (lambda' + mu') s_j s_j^T + mu' (s_j . s_j) I.
template <class Real>
Mat3<Real> vertex_block(const TetrahedronRest<Real>& rest, int j);

// L_e = lambda' s_l s_k^T + mu' s_k s_l^T + mu' (s_l . s_k) I for local edge e = (k, l).
template <class Real>
Mat3<Real> edge_block(const TetrahedronRest<Real>& rest, int e);

// Rotation R (rest frame → world) of the element at current points x.
template <class Real>
Mat3<Real> tetrahedron_rotation(const TetrahedronRest<Real>& rest, const TetPoints<Real>& x,
                                RotationMethod method);

// Forces on the four vertices (world frame) for rotation R. SPEC.md writes them per edge
// (g_l += L_e u_e, g_k -= L_e^T u_e in the rest frame, f_j = R g_j); summing the edge blocks gives
// the same forces through the rest-frame displacement gradient H = sum_j u_j s_j^T, with
// u_j = R^T (x_j - x0) - (p_j - p0):  g_j = -(lambda' tr(H) I + mu' (H + H^T)) s_j. That form costs
// a third of the edge form; tests keep the edge form as the reference (tests/support/reference_element.h).
template <class Real>
TetPoints<Real> tetrahedron_force(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p,
                                  const TetPoints<Real>& x, const Mat3<Real>& rotation);

// Energy U = -1/2 sum_j u_j . g_j = lambda'/2 tr(H)^2 + mu' |sym H|^2, for rotation R.
template <class Real>
Real tetrahedron_energy(const TetrahedronRest<Real>& rest, const TetPoints<Real>& p,
                        const TetPoints<Real>& x, const Mat3<Real>& rotation);

// R L_e R^T for local edge e = (k, l), from the rotated shape vectors r_j = R s_j:
// lambda' r_l r_k^T + mu' r_k r_l^T + mu' (s_l . s_k) I. With `transposed`, R L_e^T R^T.
// Defined here so that the per-edge stiffness refresh inlines it.
template <class Real>
inline Mat3<Real> rotated_edge_block(const TetrahedronRest<Real>& rest,
                                     const std::array<Vec3<Real>, 4>& rotated_shape, int e, bool transposed) {
  const int k = kTetrahedronEdges[e][0];
  const int l = kTetrahedronEdges[e][1];
  const Vec3<Real>& rk = rotated_shape[transposed ? l : k];
  const Vec3<Real>& rl = rotated_shape[transposed ? k : l];
  Mat3<Real> block = rest.lambda * rl * rk.transpose() + rest.mu * rk * rl.transpose();
  block.diagonal().array() += rest.mu * rest.shape[l].dot(rest.shape[k]);
  return block;
}

}  // namespace fastcorot
