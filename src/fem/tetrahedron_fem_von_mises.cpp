// TetrahedronFEMForceField's von Mises stress (SOFA's computeVonMisesStress, which SOFA runs at the
// end of each step when computeVonMisesStress is 1 or 2).
#include "fastcorot/core/error.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include <Eigen/LU>

#include <cmath>

namespace fastcorot {

template <class Real>
bool TetrahedronFEMForceField<Real>::computes_von_mises_stress() const {
  // SOFA marks the component invalid for 1 with small (a warning) and computes nothing.
  return parameters_.von_mises == 2 ||
         (parameters_.von_mises == 1 && parameters_.method != TetrahedronFEMMethod::small);
}

template <class Real>
void TetrahedronFEMForceField<Real>::update_von_mises_stress(std::span<const Vec3<Real>> x) {
  if (!computes_von_mises_stress()) return;
  check_size(x, "x");
  using Mat4 = Eigen::Matrix<Real, 4, 4>;
  const Index num_tetrahedra = mesh_->num_tetrahedra();
  if (shape_derivatives_.size() != static_cast<std::size_t>(num_tetrahedra)) {
    // SOFA's elemShapeFun (made at init): the inverse of the rows (1, X0_m) of the rest vertices,
    // whose rows 1..3 hold the derivatives of the four shape functions along x, y, z.
    shape_derivatives_.resize(static_cast<std::size_t>(num_tetrahedra));
    for (Index t = 0; t < num_tetrahedra; ++t) {
      const TetPoints<Real> rest = tetrahedron_points<Real>(mesh_->tetrahedron(t), rest_positions_);
      Mat4 vertices;
      for (int m = 0; m < 4; ++m) {
        vertices(m, 0) = 1;
        for (int l = 0; l < 3; ++l) vertices(m, l + 1) = rest[static_cast<std::size_t>(m)][l];
      }
      shape_derivatives_[static_cast<std::size_t>(t)] = vertices.inverse().template bottomRows<3>();
    }
  }
  von_mises_element_.assign(static_cast<std::size_t>(num_tetrahedra), Real(0));
  for (Index t = 0; t < num_tetrahedra; ++t) {
    const Tetrahedron& tet = mesh_->tetrahedron(t);
    const TetPoints<Real> rest = tetrahedron_points<Real>(tet, rest_positions_);
    const TetPoints<Real> p = tetrahedron_points<Real>(tet, x);
    const auto& shape = shape_derivatives_[static_cast<std::size_t>(t)];
    // The displacement: the world one (Green strain) or the element's D (corotational; SOFA uses
    // the frame's D with the world rest shape functions, and so do we).
    std::array<Vec3<Real>, 4> u;
    if (parameters_.von_mises == 2) {
      for (std::size_t m = 0; m < 4; ++m) u[m] = p[m] - rest[m];
    } else {
      // SOFA takes the plain polar factor for svd here, not the stable one.
      const TetrahedronFEMMethod method =
          parameters_.method == TetrahedronFEMMethod::svd ? TetrahedronFEMMethod::polar : parameters_.method;
      Mat3<Real> frame;
      u = displacement(elements_[static_cast<std::size_t>(t)], p, method, frame);
    }
    Mat3<Real> grad = Mat3<Real>::Zero();
    for (int k = 0; k < 3; ++k) {
      for (int l = 0; l < 3; ++l) {
        for (int m = 0; m < 4; ++m) grad(k, l) += shape(l, m) * u[static_cast<std::size_t>(m)][k];
      }
    }
    const Mat3<Real> strain = parameters_.von_mises == 2
                                  ? Mat3<Real>(Real(0.5) * (grad + grad.transpose() + grad.transpose() * grad))
                                  : Mat3<Real>(Real(0.5) * (grad + grad.transpose()));
    const Real e[6] = {strain(0, 0), strain(1, 1), strain(2, 2), strain(1, 2), strain(0, 2), strain(0, 1)};
    // SOFA's elemLambda and elemMu: K(0,1) and K(3,3) before the division by the volume.
    const Real young = young_modulus_of(t), nu = poisson_ratio_of(t);
    const Real scale = (young * (1 - nu)) / ((1 + nu) * (1 - 2 * nu));
    const Real lambda = (nu / (1 - nu)) * scale, mu = ((1 - 2 * nu) / (2 * (1 - nu))) * scale;
    Real s[6];
    Real trace = 0;
    for (int k = 0; k < 3; ++k) {
      trace += e[k];
      s[k] = e[k] * 2 * mu;
    }
    for (int k = 3; k < 6; ++k) s[k] = e[k] * 2 * mu;
    for (int k = 0; k < 3; ++k) s[k] += lambda * trace;
    Real value = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - s[0] * s[1] - s[1] * s[2] - s[2] * s[0] +
                           3 * s[3] * s[3] + 3 * s[4] * s[4] + 3 * s[5] * s[5]);
    if (value < Real(1e-10)) value = 0;
    von_mises_element_[static_cast<std::size_t>(t)] = value;
  }
  von_mises_node_.assign(static_cast<std::size_t>(mesh_->num_points()), Real(0));
  for (Index v = 0; v < mesh_->num_points(); ++v) {
    const auto around = mesh_->tetrahedra_around_vertex(v);
    Real sum = 0;
    for (Index t : around) sum += von_mises_element_[static_cast<std::size_t>(t)];
    if (!around.empty()) sum /= static_cast<Real>(around.size());
    von_mises_node_[static_cast<std::size_t>(v)] = sum;
  }
}

template bool TetrahedronFEMForceField<float>::computes_von_mises_stress() const;
template bool TetrahedronFEMForceField<double>::computes_von_mises_stress() const;
template void TetrahedronFEMForceField<float>::update_von_mises_stress(std::span<const Vec3<float>>);
template void TetrahedronFEMForceField<double>::update_von_mises_stress(std::span<const Vec3<double>>);

}  // namespace fastcorot
