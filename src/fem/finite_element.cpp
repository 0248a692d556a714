#include "fastcorot/fem/finite_element.h"

#include "fastcorot/core/error.h"

#include <Eigen/LU>

#include <cmath>
#include <limits>

namespace fastcorot {

namespace {

// SOFA's hexahedron corners in the reference element [-1, 1]^3.
constexpr int kHexahedronCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                         {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

// Voigt index -> tensor indices (i, j), SOFA's order.
constexpr int kVoigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

template <class Real>
Eigen::Matrix<Real, 6, 6> isotropic_elasticity(Real mu, Real lambda) {
  Eigen::Matrix<Real, 6, 6> C;
  const auto delta = [](int a, int b) { return a == b ? Real(1) : Real(0); };
  for (int a = 0; a < 6; ++a) {
    for (int b = 0; b < 6; ++b) {
      const int i = kVoigt[a][0], j = kVoigt[a][1], k = kVoigt[b][0], l = kVoigt[b][1];
      C(a, b) = mu * (delta(i, k) * delta(j, l) + delta(i, l) * delta(j, k)) + lambda * delta(i, j) * delta(k, l);
    }
  }
  return C;
}

// J = sum_i x_i g_i^T (the reference-to-physical Jacobian at a quadrature point).
template <class Real, int N>
Mat3<Real> jacobian(const ElementPoints<Real, N>& nodes, const Eigen::Matrix<Real, N, 3>& gradients) {
  Mat3<Real> J = Mat3<Real>::Zero();
  for (int i = 0; i < N; ++i) J += nodes[static_cast<std::size_t>(i)] * gradients.row(i);
  return J;
}

template <class Real, int N>
Real checked_determinant(const Mat3<Real>& J) {
  const Real det = std::abs(J.determinant());
  // Flat when det J is round-off of the element's size cubed (the corners span no volume).
  const Real size = J.colwise().norm().maxCoeff();
  const Real scale = size * size * size;
  if (!(det > Real(64) * std::numeric_limits<Real>::epsilon() * scale) || !std::isfinite(det)) {
    throw make_error("flat element: det J = ", det, " at a quadrature point");
  }
  return det;
}

}  // namespace

template <class Real, int N>
std::array<QuadraturePoint<Real, N>, N == 4 ? 1 : 8> quadrature_points() {
  static_assert(N == 4 || N == 8, "tetrahedra (4 corners) and hexahedra (8 corners) only");
  std::array<QuadraturePoint<Real, N>, N == 4 ? 1 : 8> points;
  if constexpr (N == 4) {
    const Real q = Real(1. / 4.);
    auto& p = points[0];
    p.reference_gradients << -1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1;
    p.shape_functions << Real(1) - q - q - q, q, q, q;
    p.weight = Real(1. / 6.);
  } else {
    // SOFA writes sqrt(3) as 1.73205080757 (to 1e-12): kept, so that K agrees with SOFA's to round-off.
    const Real inverse_sqrt3 = Real(1) / Real(1.73205080757);
    for (int g = 0; g < 8; ++g) {
      const Real x = kHexahedronCorner[g][0] * inverse_sqrt3, y = kHexahedronCorner[g][1] * inverse_sqrt3,
                 z = kHexahedronCorner[g][2] * inverse_sqrt3;
      auto& p = points[static_cast<std::size_t>(g)];
      for (int i = 0; i < 8; ++i) {
        const Real xr = kHexahedronCorner[i][0], yr = kHexahedronCorner[i][1], zr = kHexahedronCorner[i][2];
        p.reference_gradients(i, 0) = Real(1. / 8.) * (xr * (1 + y * yr) * (1 + z * zr));
        p.reference_gradients(i, 1) = Real(1. / 8.) * (yr * (1 + x * xr) * (1 + z * zr));
        p.reference_gradients(i, 2) = Real(1. / 8.) * (zr * (1 + x * xr) * (1 + y * yr));
        p.shape_functions(i) = Real(0.125) * (1 + x * xr) * (1 + y * yr) * (1 + z * zr);
      }
      p.weight = 1;
    }
  }
  return points;
}

template <class Real, int N>
Eigen::Matrix<Real, 3 * N, 3 * N> element_stiffness(const ElementPoints<Real, N>& nodes, Real mu, Real lambda) {
  const Eigen::Matrix<Real, 6, 6> C = isotropic_elasticity(mu, lambda);
  Eigen::Matrix<Real, 3 * N, 3 * N> K = Eigen::Matrix<Real, 3 * N, 3 * N>::Zero();
  for (const auto& q : quadrature_points<Real, N>()) {
    const Mat3<Real> J = jacobian<Real, N>(nodes, q.reference_gradients);
    const Real det = checked_determinant<Real, N>(J);
    const Mat3<Real> J_inverse = J.inverse();
    // Gradients in the physical element: row i is (J^-T g_i)^T.
    const Eigen::Matrix<Real, N, 3> gradients = q.reference_gradients * J_inverse;
    Eigen::Matrix<Real, 6, 3 * N> B = Eigen::Matrix<Real, 6, 3 * N>::Zero();
    for (int a = 0; a < 6; ++a) {
      const int i = kVoigt[a][0], j = kVoigt[a][1];
      for (int n = 0; n < N; ++n) {
        B(a, 3 * n + i) = gradients(n, j);
        if (i != j) B(a, 3 * n + j) = gradients(n, i);  // engineering shear strain
      }
    }
    K += (q.weight * det) * (B.transpose() * (C * B));
  }
  return K;
}

template <class Real, int N>
Eigen::Matrix<Real, N, N> element_mass_matrix(const ElementPoints<Real, N>& nodes, const std::array<Real, N>& densities) {
  Eigen::Matrix<Real, N, N> M = Eigen::Matrix<Real, N, N>::Zero();
  for (const auto& q : quadrature_points<Real, N>()) {
    const Real det = checked_determinant<Real, N>(jacobian<Real, N>(nodes, q.reference_gradients));
    Real density = 0;
    for (int i = 0; i < N; ++i) density += densities[static_cast<std::size_t>(i)] * q.shape_functions(i);
    M += (q.weight * density * det) * (q.shape_functions * q.shape_functions.transpose());
  }
  return M;
}

#define FASTCOROT_INSTANTIATE(Real, N)                                                                          \
  template std::array<QuadraturePoint<Real, N>, N == 4 ? 1 : 8> quadrature_points<Real, N>();                \
  template Eigen::Matrix<Real, 3 * N, 3 * N> element_stiffness<Real, N>(const ElementPoints<Real, N>&, Real, \
                                                                        Real);                              \
  template Eigen::Matrix<Real, N, N> element_mass_matrix<Real, N>(const ElementPoints<Real, N>&,            \
                                                                  const std::array<Real, N>&);
FASTCOROT_INSTANTIATE(float, 4)
FASTCOROT_INSTANTIATE(float, 8)
FASTCOROT_INSTANTIATE(double, 4)
FASTCOROT_INSTANTIATE(double, 8)
#undef FASTCOROT_INSTANTIATE

}  // namespace fastcorot
