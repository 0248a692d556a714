// SOFA's generic finite elements (its Sofa.FEM library, FiniteElement[Tetrahedron] and
// FiniteElement[Hexahedron]) as free functions of an element's N corner points: the reference
// element (shape functions, their gradients, quadrature), the linear elastic element stiffness
// K = sum_q w_q |det J_q| B_q^T C B_q and the consistent scalar mass matrix
// M = sum_q w_q rho(q) |det J_q| N(q) N(q)^T, integrated exactly as SOFA integrates them.
//   - LinearTetrahedron (N = 4): reference corners (0,0,0), (1,0,0), (0,1,0), (0,0,1), shape
//     functions 1-u-v-w, u, v, w; ONE quadrature point (the centroid, weight 1/6). K is then the
//     textbook V B^T C B, and the mass matrix is rho V / 16 in every entry (not the exactly
//     integrated rho V (1 + delta_ij) / 20: SOFA's FEMMass uses this one-point rule).
//   - TrilinearHexahedron (N = 8): corners (+-1,+-1,+-1) in SOFA's order (bottom face
//     counter-clockwise from (-1,-1,-1), then the top face), 2x2x2 Gauss points at the corners times
//     1/1.73205080757 (SOFA's truncated sqrt(3)), weights 1.
// B is SOFA's 6 x 3N strain-displacement matrix in Voigt order (xx, yy, zz, yz, xz, xy) with
// engineering shear strains, and C the isotropic elasticity tensor of (E, nu) in the same order
// (lambda + 2 mu on the normal diagonal, lambda off it, mu on the shear diagonal).
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/Core>

#include <array>

namespace fastcorot {

template <class Real, int N>
using ElementPoints = std::array<Vec3<Real>, N>;

// The shape functions' gradients in the reference element (N × 3) and the shape functions (N) at a
// quadrature point, with its weight.
template <class Real, int N>
struct QuadraturePoint {
  Eigen::Matrix<Real, N, 3> reference_gradients;
  Eigen::Matrix<Real, N, 1> shape_functions;
  Real weight;
};

// The quadrature points SOFA uses for the element of N corners (N = 4: tetrahedron, 8: hexahedron).
template <class Real, int N>
std::array<QuadraturePoint<Real, N>, N == 4 ? 1 : 8> quadrature_points();

// The 3N × 3N linear elastic stiffness (SOFA's `integrate`, BaseElementLinearFEMForceField's
// elementStiffness) of the element with rest corners `nodes`, from Lamé's mu and lambda. Throws
// fastcorot::Error when det J is zero or not finite at a quadrature point (a flat element).
template <class Real, int N>
Eigen::Matrix<Real, 3 * N, 3 * N> element_stiffness(const ElementPoints<Real, N>& nodes, Real mu, Real lambda);

// The N × N consistent mass matrix (SOFA's FEMMass::calculateElementMassMatrix) of the element with
// rest corners `nodes` and a density per corner (interpolated by the shape functions).
template <class Real, int N>
Eigen::Matrix<Real, N, N> element_mass_matrix(const ElementPoints<Real, N>& nodes,
                                              const std::array<Real, N>& densities);

}  // namespace fastcorot
