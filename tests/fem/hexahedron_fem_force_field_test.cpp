// HexahedronFEMForceField against SOFA's own test (a unit cube stretched 10 % along z: 0.25 on each
// corner), against a reference element stiffness written here the textbook way (B of 6×24 at each
// of the 8 Gauss points, B^T C B det J, on the corners as given), and for what a corotational
// element must do: no force under rigid motions (large, polar), the assembled tangent equal to the
// product, and bad input named.
#include "fastcorot/fem/hexahedron_fem_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/matrix_sink.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <vector>

namespace fastcorot {
namespace {

using Field = HexahedronFEMForceField<double>;
using Points = std::vector<Vec3<double>>;
using Matrix24 = Eigen::Matrix<double, 24, 24>;

const Hexahedron kCube = {0, 1, 2, 3, 4, 5, 6, 7};

Points unit_cube() { return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}; }

Field::Parameters material(double young, double nu, HexahedronFEMMethod method) {
  Field::Parameters p;
  p.young_modulus = {young};
  p.poisson_ratio = {nu};
  p.method = method;
  return p;
}

// The trilinear hexahedron's stiffness, written independently: shape functions N_i = (1 + s_i x1)(1 +
// t_i x2)(1 + u_i x3) / 8, J = sum_i x_i dN_i/dxi^T, B rows (xx, yy, zz, xy, yz, zx) with engineering
// shear strains, C isotropic (lambda + 2 mu, lambda, mu), 2×2×2 Gauss points of weight 1.
Matrix24 reference_stiffness(const Points& x, double young, double nu) {
  const double s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  const double lambda = young * nu / ((1 + nu) * (1 - 2 * nu)), mu = young / (2 * (1 + nu));
  Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
  C.topLeftCorner<3, 3>().setConstant(lambda);
  C.topLeftCorner<3, 3>().diagonal().array() += 2 * mu;
  C.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  Matrix24 K = Matrix24::Zero();
  const double g = 1 / std::sqrt(3.0);
  for (double a : {-g, g}) {
    for (double b : {-g, g}) {
      for (double c : {-g, g}) {
        Eigen::Matrix<double, 8, 3> dn;  // dN_i / d(x1, x2, x3)
        for (int i = 0; i < 8; ++i) {
          dn(i, 0) = s[i][0] * (1 + s[i][1] * b) * (1 + s[i][2] * c) / 8;
          dn(i, 1) = (1 + s[i][0] * a) * s[i][1] * (1 + s[i][2] * c) / 8;
          dn(i, 2) = (1 + s[i][0] * a) * (1 + s[i][1] * b) * s[i][2] / 8;
        }
        Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
        for (int i = 0; i < 8; ++i) J += x[static_cast<std::size_t>(i)] * dn.row(i);
        const Eigen::Matrix<double, 8, 3> grad = dn * J.inverse();  // dN_i / dX
        Eigen::Matrix<double, 6, 24> B = Eigen::Matrix<double, 6, 24>::Zero();
        for (int i = 0; i < 8; ++i) {
          B(0, 3 * i) = grad(i, 0);
          B(1, 3 * i + 1) = grad(i, 1);
          B(2, 3 * i + 2) = grad(i, 2);
          B(3, 3 * i) = grad(i, 1), B(3, 3 * i + 1) = grad(i, 0);
          B(4, 3 * i + 1) = grad(i, 2), B(4, 3 * i + 2) = grad(i, 1);
          B(5, 3 * i) = grad(i, 2), B(5, 3 * i + 2) = grad(i, 0);
        }
        K += B.transpose() * C * B * J.determinant();
      }
    }
  }
  return K;
}

Points forces(Field& field, const Points& x) {
  Points f(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  return f;
}

TEST(HexahedronFEMForceField, SofasStretchedCubeTest) {
  // SOFA's HexahedronFEMForceField_test: E = 10, nu = 0, small; the top face moved 0.1 up.
  Field field(8, {kCube}, unit_cube(), material(10, 0, HexahedronFEMMethod::small));
  Points x = unit_cube();
  for (std::size_t i = 4; i < 8; ++i) x[i].z() = 1.1;
  const Points f = forces(field, x);
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_NEAR(f[i].x(), 0, 1e-12);
    EXPECT_NEAR(f[i].y(), 0, 1e-12);
    EXPECT_NEAR(f[i].z(), i < 4 ? 0.25 : -0.25, 1e-12) << i;
  }
}

TEST(HexahedronFEMForceField, ElementStiffnessIsTheTrilinearElementsOnBoxesAndDistortedHexahedra) {
  const Points box = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {0, 0, 0.5}, {2, 0, 0.5}, {2, 1, 0.5}, {0, 1, 0.5}};
  Points distorted = box;
  distorted[6] += Vec3<double>(0.3, -0.2, 0.25);
  distorted[1] += Vec3<double>(0.1, 0.15, -0.05);
  for (const Points& shape : {box, distorted}) {
    const double young = 700, nu = 0.3;
    const double scale = young * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
    std::array<Vec3<double>, 8> corners;
    for (std::size_t i = 0; i < 8; ++i) corners[i] = shape[i];
    const Matrix24 K = hexahedron_element_stiffness<double>(corners, scale, nu / (1 - nu) * scale,
                                                            (1 - 2 * nu) / (2 * (1 - nu)) * scale);
    const Matrix24 expected = reference_stiffness(shape, young, nu);
    EXPECT_LT((K - expected).norm(), 1e-12 * expected.norm());
    // Rigid translations are in its kernel.
    Eigen::Matrix<double, 24, 1> t;
    for (int i = 0; i < 8; ++i) t.segment<3>(3 * i) = Eigen::Vector3d(1, -2, 0.5);
    EXPECT_LT((K * t).norm(), 1e-10 * K.norm());
  }
}

TEST(HexahedronFEMForceField, CorotationalMethodsGiveNoForceUnderRigidMotionsAndRotateTheirForces) {
  Points rest = unit_cube();
  rest[6] += Vec3<double>(0.1, 0.05, 0.2);  // not a box
  const Mat3<double> Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  const Vec3<double> shift(3, -1, 2);
  Points stretched = rest;
  for (std::size_t i = 4; i < 8; ++i) stretched[i].z() += 0.1;
  for (auto method : {HexahedronFEMMethod::large, HexahedronFEMMethod::polar}) {
    Field field(8, {kCube}, rest, material(100, 0.3, method));
    Points moved(8), moved_stretched(8);
    for (std::size_t i = 0; i < 8; ++i) {
      moved[i] = Q * rest[i] + shift;
      moved_stretched[i] = Q * stretched[i] + shift;
    }
    for (const auto& f : forces(field, moved)) EXPECT_LT(f.norm(), 1e-11);
    const Points f0 = forces(field, stretched), f1 = forces(field, moved_stretched);
    for (std::size_t i = 0; i < 8; ++i) EXPECT_LT((f1[i] - Q * f0[i]).norm(), 1e-11 * (1 + f0[i].norm())) << i;
  }
}

TEST(HexahedronFEMForceField, AssembledTangentIsTheProductAndSmallIsExactlyLinear) {
  // Two hexahedra sharing a face, deformed.
  Points rest = unit_cube();
  for (std::size_t i = 4; i < 8; ++i) rest.push_back(rest[i] + Vec3<double>(0, 0, 1));
  const std::vector<Hexahedron> hexahedra = {kCube, {4, 5, 6, 7, 8, 9, 10, 11}};
  Points x = rest;
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += 0.05 * Vec3<double>(std::sin(1.0 + i), std::cos(2.0 * i), std::sin(3.0 * i));
  Points dx(x.size());
  for (std::size_t i = 0; i < dx.size(); ++i) dx[i] = Vec3<double>(std::cos(0.5 * i), 0.3, std::sin(1.5 + i));
  for (auto method : {HexahedronFEMMethod::small, HexahedronFEMMethod::large, HexahedronFEMMethod::polar}) {
    Field::Parameters p = material(50, 0.35, method);
    p.rayleigh_stiffness = 0.2;
    Field field(12, hexahedra, rest, p);
    forces(field, x);
    Points df(x.size(), Vec3<double>::Zero());
    field.add_dforce(dx, df, 1.5, 2.0);
    TripletSink<double> sink;
    field.add_stiffness(sink, 1.5, 0, 2.0);
    const Eigen::SparseMatrix<double> K = sink.to_sparse(36);
    const Eigen::Map<const Eigen::VectorXd> dxv(dx[0].data(), 36);
    const Eigen::VectorXd product = K * dxv;
    const Eigen::Map<const Eigen::VectorXd> dfv(df[0].data(), 36);
    EXPECT_LT((product - dfv).norm(), 1e-12 * product.norm());
    EXPECT_LT((Eigen::MatrixXd(K) - Eigen::MatrixXd(K).transpose()).norm(), 1e-12 * K.norm());
    std::vector<Mat3<double>> diagonal(12, Mat3<double>::Zero());
    field.add_diagonal_blocks(diagonal, 1.5, 2.0);
    for (Index i = 0; i < 12; ++i) {
      EXPECT_LT((diagonal[static_cast<std::size_t>(i)] - Eigen::MatrixXd(K).block<3, 3>(3 * i, 3 * i)).norm(), 1e-12 * K.norm());
    }
    if (method == HexahedronFEMMethod::small) {
      // small is linear: the forces' difference quotient is the tangent (k_factor 1, no damping part).
      Points shifted = x;
      for (std::size_t i = 0; i < x.size(); ++i) shifted[i] += 1e-3 * dx[i];
      const Points f0 = forces(field, x), f1 = forces(field, shifted);
      Points k_dx(x.size(), Vec3<double>::Zero());
      field.add_dforce(dx, k_dx, 1.0);
      for (std::size_t i = 0; i < x.size(); ++i) EXPECT_LT(((f1[i] - f0[i]) / 1e-3 - k_dx[i]).norm(), 1e-9 * (1 + k_dx[i].norm()));
      // Energy: D . K D / 2 with D = x - rest for small.
      EXPECT_NEAR(field.potential_energy(rest), 0, 1e-14);
    }
  }
}

TEST(HexahedronFEMForceField, VolumeAndDrawnTetrahedra) {
  const Points box = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0}, {0, 0, 4}, {2, 0, 4}, {2, 3, 4}, {0, 3, 4}};
  EXPECT_NEAR(hexahedron_volume<double>(box, kCube), 24, 1e-12);
  const auto tetrahedra = hexahedra_tetrahedra(std::vector<Hexahedron>{kCube});
  ASSERT_EQ(tetrahedra.size(), 6u);
  double sum = 0;
  for (const auto& t : tetrahedra) {
    sum += std::abs((box[static_cast<std::size_t>(t[1])] - box[static_cast<std::size_t>(t[0])])
                        .cross(box[static_cast<std::size_t>(t[2])] - box[static_cast<std::size_t>(t[0])])
                        .dot(box[static_cast<std::size_t>(t[3])] - box[static_cast<std::size_t>(t[0])])) / 6;
  }
  EXPECT_NEAR(sum, 24, 1e-12);
  Field field(8, {kCube}, box, material(1, 0.2, HexahedronFEMMethod::large));
  EXPECT_EQ(field.mesh().num_tetrahedra(), 6);
  EXPECT_EQ(field.rotations().size(), 6u);
}

TEST(HexahedronFEMForceField, BadInputIsNamed) {
  const Points rest = unit_cube();
  const auto message = [&](std::vector<Hexahedron> hexahedra, Field::Parameters p, Index points = 8) {
    try {
      Field(points, std::move(hexahedra), rest, p);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const auto p = material(10, 0.3, HexahedronFEMMethod::large);
  EXPECT_NE(message({{0, 1, 2, 3, 4, 5, 6, 8}}, p).find("point 8 is outside [0, 8)"), std::string::npos);
  EXPECT_NE(message({{0, 1, 2, 3, 4, 5, 6, 0}}, p).find("point 0 repeats"), std::string::npos);
  EXPECT_NE(message({{0, 3, 2, 1, 4, 7, 6, 5}}, p).find("flat or inverted hexahedron"), std::string::npos);
  EXPECT_NE(message({}, p).find("no hexahedra"), std::string::npos);
  EXPECT_NE(message({kCube}, material(-1, 0.3, HexahedronFEMMethod::large)).find("youngModulus = -1"), std::string::npos);
  EXPECT_NE(message({kCube}, material(1, 0.5, HexahedronFEMMethod::large)).find("poissonRatio = 0.5"), std::string::npos);
  Field::Parameters two = p;
  two.young_modulus = {1, 2};
  EXPECT_NE(message({kCube}, two).find("youngModulus: 2 values given"), std::string::npos);
  EXPECT_NE(message({kCube}, p, 9).find("8 rest positions for 9 points"), std::string::npos);
  EXPECT_THROW(parse_hexahedron_fem_method("svd"), Error);
  Field field(8, {kCube}, rest, p);
  EXPECT_THROW(field.check_new_tetrahedra({}), Error);
}

}  // namespace
}  // namespace fastcorot
