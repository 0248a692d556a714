#include "fastcorot/fem/tetrahedron_element.h"

#include "fastcorot/topology/tet_mesh.h"
#include "support/deformations.h"
#include "support/finite_difference.h"
#include "support/reference_element.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fastcorot {
namespace {

using testing::flatten;
using testing::unflatten;

// SPEC.md example: points (0,0,0) (1,0,0) (0,1,0) (0,0,1), tetrahedron (2,3,1,0).
TetPoints<double> spec_example_points() {
  return {Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1), Vec3<double>(1, 0, 0), Vec3<double>(0, 0, 0)};
}

TetPoints<double> irregular_points() {
  return {Vec3<double>(0.1, -0.2, 0.05), Vec3<double>(1.3, 0.1, -0.1), Vec3<double>(0.2, 0.9, 0.15),
          Vec3<double>(0.3, 0.2, 1.4)};
}

TEST(TetrahedronRest, SpecExampleValues) {
  // Reference values: SPEC.md "Rest state" example (E = 1000, nu = 0.3), which reproduces SOFA.
  const auto rest = tetrahedron_rest(spec_example_points(), lame_parameters(1000.0, 0.3), RotationMethod::qr);
  EXPECT_NEAR(rest.volume, 1.0 / 6.0, 1e-15);
  const Vec3<double> expected_shape[4] = {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {-1, -1, -1}};
  for (int j = 0; j < 4; ++j) EXPECT_LT((rest.shape[j] - expected_shape[j]).norm(), 1e-14) << j;

  const double mu = 1000.0 / 2.6 / 6.0, lambda = 300.0 / (1.3 * 0.4) / 6.0;  // scaled by |V| = 1/6
  EXPECT_NEAR(mu, 64.1026, 1e-4);
  EXPECT_NEAR(lambda, 96.1538, 1e-4);
  const Mat3<double> d0 = vertex_block(rest, 0);
  EXPECT_LT((d0 - Vec3<double>(mu, lambda + 2 * mu, mu).asDiagonal().toDenseMatrix()).norm(), 1e-12);
  EXPECT_NEAR(vertex_block(rest, 0)(1, 1), 224.359, 1e-3);
  const Mat3<double> d3 = vertex_block(rest, 3);
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(d3(i, k), i == k ? 352.5641 : 160.25641, 1e-4);
  }
  Mat3<double> l0;
  l0 << 0, 0, 0, 0, 0, 64.1026, 0, 96.1538, 0;
  EXPECT_LT((edge_block(rest, 0) - l0).cwiseAbs().maxCoeff(), 1e-4);

  // The QR rest frame, worked by hand in core/rotation_test.cpp.
  const double r2 = std::sqrt(2.0), r3 = std::sqrt(3.0), r6 = std::sqrt(6.0);
  Mat3<double> r0;
  r0 << 0, -1 / r2, 1 / r2, 2 / r6, -1 / r6, -1 / r6, 1 / r3, 1 / r3, 1 / r3;
  EXPECT_LT((rest.rest_rotation - r0).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(TetrahedronRest, ShapeVectorsAreBarycentricGradients) {
  // sum_j s_j = 0 and sum_j p_j s_j^T = I, for both orientations of the element.
  for (bool flip : {false, true}) {
    auto p = irregular_points();
    if (flip) std::swap(p[1], p[2]);
    const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), RotationMethod::polar);
    Vec3<double> sum = Vec3<double>::Zero();
    Mat3<double> identity = Mat3<double>::Zero();
    for (int j = 0; j < 4; ++j) {
      sum += rest.shape[j];
      identity += p[j] * rest.shape[j].transpose();
    }
    EXPECT_LT(sum.norm(), 1e-13);
    EXPECT_LT((identity - Mat3<double>::Identity()).norm(), 1e-13);
    EXPECT_GT(rest.mu, 0);
  }
}

// Independent reference: the 12×12 linear elasticity stiffness |V| B^T C B in Voigt notation
// (xx, yy, zz, xy, yz, zx with engineering shears), C = lambda 1 1^T + mu diag(2,2,2,1,1,1).
Eigen::Matrix<double, 12, 12> voigt_stiffness(const TetrahedronRest<double>& rest) {
  Eigen::Matrix<double, 6, 12> b = Eigen::Matrix<double, 6, 12>::Zero();
  for (int j = 0; j < 4; ++j) {
    const Vec3<double>& s = rest.shape[j];
    b(0, 3 * j) = s.x();
    b(1, 3 * j + 1) = s.y();
    b(2, 3 * j + 2) = s.z();
    b(3, 3 * j) = s.y();
    b(3, 3 * j + 1) = s.x();
    b(4, 3 * j + 1) = s.z();
    b(4, 3 * j + 2) = s.y();
    b(5, 3 * j) = s.z();
    b(5, 3 * j + 2) = s.x();
  }
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  c.topLeftCorner<3, 3>().setConstant(rest.lambda);  // lambda and mu already carry |V|
  c.diagonal() += Eigen::Matrix<double, 6, 1>(2, 2, 2, 1, 1, 1) * rest.mu;
  return b.transpose() * c * b;
}

TEST(TetrahedronBlocks, MatchLinearElasticityStiffness) {
  for (const auto& p : {spec_example_points(), irregular_points()}) {
    const auto rest = tetrahedron_rest(p, lame_parameters(1234.0, 0.37), RotationMethod::qr);
    const auto k = voigt_stiffness(rest);
    for (int j = 0; j < 4; ++j) {
      EXPECT_LT((vertex_block(rest, j) - k.block<3, 3>(3 * j, 3 * j)).norm(), 1e-9 * k.norm()) << j;
    }
    for (int e = 0; e < 6; ++e) {
      const int kk = kTetrahedronEdges[e][0], l = kTetrahedronEdges[e][1];
      // L_e is the block coupling vertex l's force to vertex k's displacement.
      EXPECT_LT((edge_block(rest, e) - k.block<3, 3>(3 * l, 3 * kk)).norm(), 1e-9 * k.norm()) << e;
    }
  }
}

class TetrahedronMethod : public ::testing::TestWithParam<RotationMethod> {};

TetPoints<double> deformed(const TetPoints<double>& p, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  TetPoints<double> x = p;
  for (auto& v : x) v += Vec3<double>(u(rng), u(rng), u(rng));
  return x;
}

TetPoints<double> force_at(const TetrahedronRest<double>& rest, const TetPoints<double>& p,
                           const TetPoints<double>& x, RotationMethod method) {
  return tetrahedron_force(rest, p, x, tetrahedron_rotation(rest, x, method));
}

double energy_at(const TetrahedronRest<double>& rest, const TetPoints<double>& p,
                 const TetPoints<double>& x, RotationMethod method) {
  return tetrahedron_energy(rest, p, x, tetrahedron_rotation(rest, x, method));
}

Eigen::VectorXd flat(const TetPoints<double>& x) { return flatten({x.begin(), x.end()}); }

TetPoints<double> tet(const Eigen::VectorXd& v) {
  const auto points = unflatten(v);
  return {points[0], points[1], points[2], points[3]};
}

TEST_P(TetrahedronMethod, ZeroForceAndEnergyAtRestAndUnderRigidMotion) {
  const RotationMethod method = GetParam();
  const auto p = irregular_points();
  const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), method);
  for (const auto& f : force_at(rest, p, p, method)) EXPECT_LT(f.norm(), 1e-12);
  EXPECT_NEAR(energy_at(rest, p, p, method), 0.0, 1e-14);
  // A rigid motion: translation for every method, rotation too for the corotational ones.
  std::mt19937 rng(3);
  const Mat3<double> q = method == RotationMethod::none ? Mat3<double>::Identity() : testing::random_rotation(rng);
  TetPoints<double> x;
  for (int j = 0; j < 4; ++j) x[j] = q * p[j] + Vec3<double>(0.4, -1.0, 2.0);
  for (const auto& f : force_at(rest, p, x, method)) EXPECT_LT(f.norm(), 1e-10);
  EXPECT_NEAR(energy_at(rest, p, x, method), 0.0, 1e-12);
  if (method != RotationMethod::none) {
    EXPECT_LT((tetrahedron_rotation(rest, x, method) - q).norm(), 1e-12);
  }
}

TEST_P(TetrahedronMethod, TranslationInvariantAndForcesSumToZero) {
  const RotationMethod method = GetParam();
  const auto p = irregular_points();
  const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), method);
  const auto x = deformed(p, 0.2, 5);
  const auto f = force_at(rest, p, x, method);
  TetPoints<double> shifted = x;
  for (auto& v : shifted) v += Vec3<double>(3.0, -2.0, 7.5);
  const auto g = force_at(rest, p, shifted, method);
  Vec3<double> sum = Vec3<double>::Zero();
  double scale = 0;
  for (int j = 0; j < 4; ++j) {
    EXPECT_LT((f[j] - g[j]).norm(), 1e-11 * f[j].norm() + 1e-12);
    sum += f[j];
    scale = std::max(scale, f[j].norm());
  }
  EXPECT_GT(scale, 1.0);  // the deformation is not trivial
  EXPECT_LT(sum.norm(), 1e-12 * scale);
}

// Linear elasticity (`none`) is not rotation invariant; the corotational methods are.
class CorotationalTetrahedronMethod : public ::testing::TestWithParam<RotationMethod> {};

TEST_P(CorotationalTetrahedronMethod, RotationInvariance) {
  const RotationMethod method = GetParam();
  const auto p = irregular_points();
  const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), method);
  const auto x = deformed(p, 0.2, 9);
  std::mt19937 rng(13);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3<double> q = testing::random_rotation(rng);
    TetPoints<double> qx;
    for (int j = 0; j < 4; ++j) qx[j] = q * x[j];
    const auto f = force_at(rest, p, x, method);
    const auto g = force_at(rest, p, qx, method);
    for (int j = 0; j < 4; ++j) EXPECT_LT((g[j] - q * f[j]).norm(), 1e-11 * (1 + f[j].norm()));
    EXPECT_NEAR(energy_at(rest, p, qx, method), energy_at(rest, p, x, method), 1e-11);
  }
}

TEST_P(TetrahedronMethod, EnergyGradientIsMinusForce) {
  // For `none` the force is exactly -dU/dx; for `polar` too (R^T F is symmetric, so the rotation's
  // derivative does no work); for qr and polar2 the dropped rotation derivative is a relative error
  // of the order of the strain, so we test them at small strain.
  const RotationMethod method = GetParam();
  const bool exact = method == RotationMethod::none || method == RotationMethod::polar;
  const double amplitude = exact ? 0.15 : 1e-4;
  const double tolerance = exact ? 1e-6 : 2e-3;
  const auto p = irregular_points();
  const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), method);
  const auto x = deformed(p, amplitude, 21);
  const Eigen::VectorXd gradient = testing::fd_gradient(
      [&](const Eigen::VectorXd& v) { return energy_at(rest, p, tet(v), method); }, flat(x), amplitude * 1e-3);
  const Eigen::VectorXd force = flat(force_at(rest, p, x, method));
  EXPECT_LT(testing::relative_error(-gradient, force), tolerance);
}

TEST_P(TetrahedronMethod, StiffnessIsTheForceDerivativeAtRest) {
  // At rest (rigidly moved) the rotation's derivative multiplies a zero stress, so SPEC's tangent
  // R K0 R^T is the exact derivative for every method; for `none` it is exact everywhere.
  const RotationMethod method = GetParam();
  const auto p = irregular_points();
  const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), method);
  std::mt19937 rng(17);
  const Mat3<double> q = method == RotationMethod::none ? Mat3<double>::Identity() : testing::random_rotation(rng);
  TetPoints<double> x;
  for (int j = 0; j < 4; ++j) x[j] = q * p[j] + Vec3<double>(1, 2, 3);
  if (method == RotationMethod::none) x = deformed(p, 0.3, 4);
  const Eigen::MatrixXd jacobian = testing::fd_jacobian(
      [&](const Eigen::VectorXd& v) { return flat(force_at(rest, p, tet(v), method)); }, flat(x), 1e-6);
  const Mat3<double> r = tetrahedron_rotation(rest, x, method);
  Eigen::Matrix<double, 12, 12> k;
  for (int j = 0; j < 4; ++j) k.block<3, 3>(3 * j, 3 * j) = -r * vertex_block(rest, j) * r.transpose();
  for (int e = 0; e < 6; ++e) {
    const int kk = kTetrahedronEdges[e][0], l = kTetrahedronEdges[e][1];
    k.block<3, 3>(3 * l, 3 * kk) = -r * edge_block(rest, e) * r.transpose();
    k.block<3, 3>(3 * kk, 3 * l) = -r * edge_block(rest, e).transpose() * r.transpose();
  }
  EXPECT_LT(testing::relative_error(jacobian, k), 1e-7);
}

TEST_P(TetrahedronMethod, KernelsMatchSpecsPerEdgeReference) {
  // The stress form of the force and energy and the rotated edge blocks equal SPEC's literal
  // per-edge formulas (tests/support/reference_element.h) to round-off, for both orientations.
  const RotationMethod method = GetParam();
  for (bool flip : {false, true}) {
    auto p = irregular_points();
    if (flip) std::swap(p[0], p[3]);
    const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), method);
    for (unsigned seed = 40; seed < 45; ++seed) {
      const auto x = deformed(p, 0.3, seed);
      const Mat3<double> r = tetrahedron_rotation(rest, x, method);
      const auto f = tetrahedron_force(rest, p, x, r);
      const auto ref = testing::reference_force(rest, p, x, r);
      EXPECT_LT(testing::relative_error(flat(f), flat(ref)), 1e-13);
      const double u = tetrahedron_energy(rest, p, x, r);
      EXPECT_NEAR(u, testing::reference_energy(rest, p, x, r), 1e-13 * std::abs(u));
      const std::array<Vec3<double>, 4> rotated = {r * rest.shape[0], r * rest.shape[1], r * rest.shape[2], r * rest.shape[3]};
      for (int e = 0; e < 6; ++e) {
        const Mat3<double> block = edge_block(rest, e);
        EXPECT_LT((rotated_edge_block(rest, rotated, e, false) - r * block * r.transpose()).norm(), 1e-12 * block.norm());
        EXPECT_LT((rotated_edge_block(rest, rotated, e, true) - r * block.transpose() * r.transpose()).norm(),
                  1e-12 * block.norm());
      }
    }
  }
}

TEST_P(TetrahedronMethod, FloatAgreesWithDouble) {
  const RotationMethod method = GetParam();
  const auto p = irregular_points();
  const auto x = deformed(p, 0.2, 33);
  const auto rest = tetrahedron_rest(p, lame_parameters(1000.0, 0.3), method);
  const auto f = force_at(rest, p, x, method);
  TetPoints<float> pf, xf;
  for (int j = 0; j < 4; ++j) {
    pf[j] = p[j].cast<float>();
    xf[j] = x[j].cast<float>();
  }
  const auto rest_f = tetrahedron_rest(pf, lame_parameters(1000.0f, 0.3f), method);
  const auto ff = tetrahedron_force(rest_f, pf, xf, tetrahedron_rotation(rest_f, xf, method));
  double scale = 0;
  for (int j = 0; j < 4; ++j) scale = std::max(scale, f[j].norm());
  for (int j = 0; j < 4; ++j) EXPECT_LT((ff[j].cast<double>() - f[j]).norm(), 1e-4 * scale);
}

INSTANTIATE_TEST_SUITE_P(CorotationalMethods, CorotationalTetrahedronMethod,
                         ::testing::Values(RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2),
                         [](const auto& info) { return to_string(info.param); });
INSTANTIATE_TEST_SUITE_P(AllMethods, TetrahedronMethod,
                         ::testing::Values(RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2,
                                           RotationMethod::none),
                         [](const auto& info) { return to_string(info.param); });

}  // namespace
}  // namespace fastcorot
