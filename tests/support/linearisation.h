// A force field's linearisation checked against its forces: add_dforce against central differences
// of add_force, the assembled stiffness and its diagonal blocks against add_dforce (for fields whose
// stiffness is not that of a mesh's elements: the contact force fields).
#pragma once

#include "fastcorot/fem/force_field.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <vector>

namespace fastcorot::testing {

// `field` linearised at x (its add_force or set-up called there); `probe` takes the differences'
// add_force calls (the field itself, or one made like it where add_force changes what it keeps).
// df = K dx must match the central difference (step 1e-6) within `tolerance`; 2 K dx, the rows of
// stiffness_matrix(2) and the diagonal blocks agree within 1e-12.
inline void expect_linearisation_is_the_forces_derivative(const ForceField<double>& field, ForceField<double>& probe,
                                                           const std::vector<Vec3<double>>& x,
                                                           const std::vector<Vec3<double>>& dx, double tolerance = 1e-8) {
  const std::size_t n = x.size();
  std::vector<Vec3<double>> df(n, Vec3<double>::Zero());
  field.add_dforce(dx, df, 1.0);
  const double h = 1e-6;
  std::vector<Vec3<double>> xp(x), xm(x), fp(n, Vec3<double>::Zero()), fm(n, Vec3<double>::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    xp[i] += h * dx[i];
    xm[i] -= h * dx[i];
  }
  probe.add_force(xp, fp);
  probe.add_force(xm, fm);
  for (std::size_t i = 0; i < n; ++i) EXPECT_LT((df[i] - (fp[i] - fm[i]) / (2 * h)).norm(), tolerance) << "point " << i;
  const Eigen::MatrixXd k(field.stiffness_matrix(2.0));
  Eigen::VectorXd flat(static_cast<Eigen::Index>(3 * n));
  for (std::size_t i = 0; i < n; ++i) flat.segment<3>(static_cast<Eigen::Index>(3 * i)) = dx[i];
  const Eigen::VectorXd kdx = k * flat;
  std::vector<Mat3<double>> diagonal(n, Mat3<double>::Zero());
  field.add_diagonal_blocks(diagonal, 2.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto b = static_cast<Eigen::Index>(3 * i);
    EXPECT_LT((kdx.segment<3>(b) - 2.0 * df[i]).norm(), 1e-12) << "point " << i;
    EXPECT_LT((Mat3<double>(k.block(b, b, 3, 3)) - diagonal[i]).norm(), 1e-12) << "point " << i;
  }
}

}  // namespace fastcorot::testing
