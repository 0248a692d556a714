// Small mechanical systems for the linear-solver tests: a 4 × 3 × 3 grid of points (72
// tetrahedra), fixed at the face x = 0, lumped masses, and its matrix as a dense Eigen matrix (column
// by column from the matrix-free product, with the fixed points' rows and columns cleared and their
// diagonal blocks the identity, as an assembled SOFA matrix has them).
#pragma once

#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"
#include "fastcorot/sim/mechanical_system.h"
#include "support/deformations.h"

#include <Eigen/Dense>

#include <memory>
#include <random>
#include <vector>

namespace fastcorot::testing {

// Implicit Euler's factors for h = 0.05, rm = 0.1, rs = 0.1 (docs/sofa-solvers.md §1.2).
constexpr MatrixFactors<double> kEulerFactors{1.005, -0.05, -0.05 * 0.15};

// Positions: the rest grid perturbed by `noise` (seeded), then turned by `turn`; the field is
// TetrahedronFEMForceField (large) when `tetrahedron_fem`, else FastTetrahedralCorotationalForceField
// with its own Rayleigh damping `rayleigh_stiffness`.
inline MechanicalSystem<double> grid_system(unsigned seed, double noise = 0.15, const Mat3<double>& turn = Mat3<double>::Identity(),
                                            bool tetrahedron_fem = false, double rayleigh_stiffness = 0) {
  std::vector<Vec3<double>> rest;
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 4; ++i) rest.emplace_back(i, j, k);
    }
  }
  const auto at = [](int i, int j, int k) { return static_cast<Index>(i + 4 * (j + 3 * k)); };
  std::vector<Tetrahedron> tets;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 3; ++i) {
        const Index c[8] = {at(i, j, k), at(i + 1, j, k), at(i + 1, j + 1, k), at(i, j + 1, k),
                            at(i, j, k + 1), at(i + 1, j, k + 1), at(i + 1, j + 1, k + 1), at(i, j + 1, k + 1)};
        const int split[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
        for (const auto& s : split) tets.push_back({c[s[0]], c[s[1]], c[s[2]], c[s[3]]});
      }
    }
  }
  auto mesh = std::make_shared<TetMesh>(static_cast<Index>(rest.size()), tets);
  std::shared_ptr<ForceField<double>> field;
  if (tetrahedron_fem) {
    TetrahedronFEMForceField<double>::Parameters q;
    q.young_modulus = {2000.0};
    q.poisson_ratio = {0.3};
    field = std::make_shared<TetrahedronFEMForceField<double>>(mesh, rest, q);
  } else {
    CorotationalForceField<double>::Parameters p;
    p.young_modulus = {2000.0};
    p.poisson_ratio = {0.3};
    p.rayleigh_stiffness = rayleigh_stiffness;
    field = std::make_shared<CorotationalForceField<double>>(mesh, rest, p);
  }
  std::mt19937 rng(seed);
  std::vector<Vec3<double>> x = noise > 0 ? perturbed(rest, noise, rng) : rest;
  for (auto& point : x) point = (turn * point).eval();
  std::vector<Vec3<double>> f(rest.size(), Vec3<double>::Zero());
  field->add_force(x, f);
  MechanicalSystem<double> system;
  system.state.position = x;
  system.state.rest_position = rest;
  system.force_fields.push_back(field);
  std::vector<double> masses(rest.size());
  for (std::size_t i = 0; i < masses.size(); ++i) masses[i] = 0.5 + 0.01 * static_cast<double>(i);
  system.mass = Mass<double>::lumped(masses);
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) system.fixed.push_back(at(0, j, k));
  }
  system.finalize();
  return system;
}

inline Eigen::VectorXd flat_vector(const std::vector<Vec3<double>>& v) {
  Eigen::VectorXd out(3 * static_cast<Eigen::Index>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out.segment<3>(3 * static_cast<Eigen::Index>(i)) = v[i];
  return out;
}

inline std::vector<Vec3<double>> points_of(const Eigen::VectorXd& v) {
  std::vector<Vec3<double>> out(static_cast<std::size_t>(v.size() / 3));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = v.segment<3>(3 * static_cast<Eigen::Index>(i));
  return out;
}

// The system matrix, column by column from the matrix-free product; fixed diagonal blocks identity.
inline Eigen::MatrixXd dense_system_matrix(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors) {
  const auto n = static_cast<std::size_t>(system.size());
  Eigen::MatrixXd a(3 * n, 3 * n);
  std::vector<Vec3<double>> e(n, Vec3<double>::Zero()), column(n);
  for (std::size_t j = 0; j < 3 * n; ++j) {
    e[j / 3][static_cast<Eigen::Index>(j % 3)] = 1;
    system.multiply(factors, e, column);
    a.col(static_cast<Eigen::Index>(j)) = flat_vector(column);
    e[j / 3].setZero();
  }
  // The product projects its result (fixed rows zero), not its input: clear the fixed columns too,
  // as the projective constraints do to an assembled matrix.
  for (Index i : system.fixed) {
    a.middleCols<3>(3 * i).setZero();
    a.block<3, 3>(3 * i, 3 * i).setIdentity();
  }
  return a;
}

}  // namespace fastcorot::testing
