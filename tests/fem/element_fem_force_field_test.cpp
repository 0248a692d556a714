// SOFA master's element force fields (CorotationalFEMForceField, LinearSmallStrainFEMForceField) and
// their finite elements (finite_element.h). Reference values are independent formulas: the
// textbook linear tetrahedron V B^T C B from barycentric gradients and C in its E, nu form, an
// 8-point Gauss rule written with the exact 1/sqrt(3) in physical coordinates of a box, the
// closed-form trilinear mass matrix of a box, finite differences of the forces, and our
// TetrahedronFEMForceField (method small) where SOFA's two tetrahedra agree.
#include "fastcorot/fem/element_fem_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/finite_element.h"
#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using Tet = ElementFEMForceField<double, 4>;
using Hex = ElementFEMForceField<double, 8>;

constexpr double kE = 2e6, kNu = 0.45;

// E, nu form of the isotropic C (Voigt xx, yy, zz, yz, xz, xy; engineering shear).
Eigen::Matrix<double, 6, 6> textbook_c(double E, double nu) {
  Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
  const double s = E / ((1 + nu) * (1 - 2 * nu));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) C(i, j) = s * (i == j ? 1 - nu : nu);
    C(i + 3, i + 3) = s * (1 - 2 * nu) / 2;
  }
  return C;
}

// B (6 × 3N) from physical shape-function gradients (rows), Voigt xx, yy, zz, yz, xz, xy.
template <int N>
Eigen::Matrix<double, 6, 3 * N> textbook_b(const Eigen::Matrix<double, N, 3>& g) {
  Eigen::Matrix<double, 6, 3 * N> B = Eigen::Matrix<double, 6, 3 * N>::Zero();
  for (int n = 0; n < N; ++n) {
    B(0, 3 * n) = g(n, 0);
    B(1, 3 * n + 1) = g(n, 1);
    B(2, 3 * n + 2) = g(n, 2);
    B(3, 3 * n + 1) = g(n, 2), B(3, 3 * n + 2) = g(n, 1);
    B(4, 3 * n) = g(n, 2), B(4, 3 * n + 2) = g(n, 0);
    B(5, 3 * n) = g(n, 1), B(5, 3 * n + 1) = g(n, 0);
  }
  return B;
}

const ElementPoints<double, 4> kTetrahedron = {Vec3<double>(0.1, 0, 0), Vec3<double>(1.2, 0.1, 0.05),
                                               Vec3<double>(0.2, 0.9, -0.1), Vec3<double>(0.05, 0.2, 1.1)};

// The box [0, 2] × [0, 1] × [0, 0.5] with SOFA's corner order.
ElementPoints<double, 8> box(double a = 2, double b = 1, double c = 0.5) {
  return {Vec3<double>(0, 0, 0), Vec3<double>(a, 0, 0), Vec3<double>(a, b, 0), Vec3<double>(0, b, 0),
          Vec3<double>(0, 0, c), Vec3<double>(a, 0, c), Vec3<double>(a, b, c), Vec3<double>(0, b, c)};
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

TEST(ElementFemTetrahedron, StiffnessIsTheTextbookLinearTetrahedron) {
  // Barycentric gradients: rows 1..3 of the inverse of [1 x_j]^T.
  Eigen::Matrix4d A;
  for (int j = 0; j < 4; ++j) A.col(j) << 1, kTetrahedron[j];
  const Eigen::Matrix4d inverse = A.inverse();
  Eigen::Matrix<double, 4, 3> g = inverse.rightCols<3>();
  const double volume = std::abs(A.determinant()) / 6;
  const auto B = textbook_b<4>(g);
  const Eigen::MatrixXd expected = volume * B.transpose() * textbook_c(kE, kNu) * B;
  const double mu = kE / (2 * (1 + kNu)), lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  EXPECT_LT(relative(element_stiffness<double, 4>(kTetrahedron, mu, lambda), expected), 1e-13);
}

TEST(ElementFemHexahedron, StiffnessIsEightPointGaussOfTheBox) {
  const double a = 2, b = 1, c = 0.5;
  const double g = 1 / std::sqrt(3.0);
  const int corner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(24, 24);
  for (const auto& q : corner) {
    const double x = q[0] * g, y = q[1] * g, z = q[2] * g;
    Eigen::Matrix<double, 8, 3> grad;
    for (int i = 0; i < 8; ++i) {
      const double xi = corner[i][0], yi = corner[i][1], zi = corner[i][2];
      // d/dx of (1 + x xi)(1 + y yi)(1 + z zi) / 8 with x = 2 X / a - 1, ...
      grad(i, 0) = xi * (1 + y * yi) * (1 + z * zi) / 8 * (2 / a);
      grad(i, 1) = yi * (1 + x * xi) * (1 + z * zi) / 8 * (2 / b);
      grad(i, 2) = zi * (1 + x * xi) * (1 + y * yi) / 8 * (2 / c);
    }
    const auto B = textbook_b<8>(grad);
    expected += (a * b * c / 8) * B.transpose() * textbook_c(kE, kNu) * B;
  }
  const double mu = kE / (2 * (1 + kNu)), lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  // SOFA's 1.73205080757 for sqrt(3) moves K by ~1e-12.
  EXPECT_LT(relative(element_stiffness<double, 8>(box(a, b, c), mu, lambda), expected), 1e-10);
}

TEST(ElementFemHexahedron, StiffnessTurnsWithTheElement) {
  const Mat3<double> Q = Eigen::AngleAxisd(0.7, Vec3<double>(1, 2, 3).normalized()).toRotationMatrix();
  auto turned = box();
  for (auto& p : turned) p = Q * p + Vec3<double>(3, -1, 2);
  Eigen::MatrixXd big_q = Eigen::MatrixXd::Zero(24, 24);
  for (int i = 0; i < 8; ++i) big_q.block<3, 3>(3 * i, 3 * i) = Q;
  const Eigen::MatrixXd K = element_stiffness<double, 8>(box(), 1000.0, 3000.0);
  EXPECT_LT(relative(element_stiffness<double, 8>(turned, 1000.0, 3000.0), big_q * K * big_q.transpose()), 1e-12);
}

TEST(ElementFemMass, TetrahedronIsSofaOnePointRule) {
  // SOFA's FEMMass integrates N N^T at the centroid only: rho V / 16 in every entry (the exact
  // consistent matrix rho V (1 + delta_ij) / 20 has the same total and the same row sums).
  const double rho = 1100;
  Eigen::Matrix4d A;
  for (int j = 0; j < 4; ++j) A.col(j) << 1, kTetrahedron[j];
  const double volume = std::abs(A.determinant()) / 6;
  const Eigen::Matrix4d M = element_mass_matrix<double, 4>(kTetrahedron, {rho, rho, rho, rho});
  EXPECT_NEAR(M.sum(), rho * volume, 1e-12 * rho * volume);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(M.row(i).sum(), rho * volume / 4, 1e-12 * rho * volume);  // = sum_j rho V (1 + delta_ij) / 20
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(M(i, j), rho * volume / 16, 1e-12 * rho * volume);
  }
  // Densities per node enter through the shape functions at the centroid: their mean.
  const Eigen::Matrix4d varying = element_mass_matrix<double, 4>(kTetrahedron, {1, 2, 3, 6});
  EXPECT_NEAR(varying.sum(), 3 * volume, 1e-12);
}

TEST(ElementFemMass, HexahedronIsTheClosedFormTrilinearMass) {
  // M_ij = rho prod_d (h_d / 6)(1 + [corners i and j share coordinate d]) for a box.
  const double rho = 7, a = 2, b = 1, c = 0.5;
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const double h[3] = {a, b, c};
  std::array<double, 8> densities;
  densities.fill(rho);
  const Eigen::Matrix<double, 8, 8> M = element_mass_matrix<double, 8>(box(a, b, c), densities);
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      double expected = rho;
      for (int d = 0; d < 3; ++d) expected *= h[d] / 6 * (corner[i][d] == corner[j][d] ? 2 : 1);
      EXPECT_NEAR(M(i, j), expected, 1e-10 * expected) << i << ", " << j;
    }
  }
  EXPECT_NEAR(M.sum(), rho * a * b * c, 1e-10);
}

// A 3 × 2 × 2-point grid: 2 hexahedra, or 12 tetrahedra (6 per cell, hexahedra_tetrahedra).
struct Grid {
  Points rest;
  std::vector<Hexahedron> hexahedra;
  Grid() {
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) rest.emplace_back(0.5 * i, 0.4 * j, 0.3 * k + 0.02 * i);
    const auto p = [](int i, int j, int k) { return static_cast<Index>(i + 3 * j + 6 * k); };
    for (int i = 0; i < 2; ++i) {
      hexahedra.push_back({p(i, 0, 0), p(i + 1, 0, 0), p(i + 1, 1, 0), p(i, 1, 0), p(i, 0, 1), p(i + 1, 0, 1), p(i + 1, 1, 1), p(i, 1, 1)});
    }
  }
  std::shared_ptr<TetMesh> tetrahedra() const { return std::make_shared<TetMesh>(12, hexahedra_tetrahedra(hexahedra)); }
  std::shared_ptr<Tet> tet_field(ElementRotationMethod method) const {
    Tet::Parameters parameters;
    parameters.young_modulus = {kE};
    parameters.poisson_ratio = {kNu};
    parameters.method = method;
    parameters.rayleigh_stiffness = 0.1;
    const auto mesh = tetrahedra();
    return std::make_shared<Tet>(mesh, std::vector<Tetrahedron>(mesh->tetrahedra().begin(), mesh->tetrahedra().end()), rest, parameters);
  }
  std::shared_ptr<Hex> hex_field(ElementRotationMethod method) const {
    Hex::Parameters parameters;
    parameters.young_modulus = {kE};
    parameters.poisson_ratio = {kNu};
    parameters.method = method;
    parameters.rayleigh_stiffness = 0.1;
    return std::make_shared<Hex>(tetrahedra(), hexahedra, rest, parameters);
  }
};

Points forces(ForceField<double>& field, const Points& x) {
  Points f(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  return f;
}

Eigen::VectorXd flat(const Points& p) {
  Eigen::VectorXd v(3 * p.size());
  for (std::size_t i = 0; i < p.size(); ++i) v.segment<3>(3 * i) = p[i];
  return v;
}

// Central differences of the forces at x, column by column (3n × 3n).
Eigen::MatrixXd finite_difference_stiffness(ForceField<double>& field, const Points& x, double h) {
  const auto n = x.size();
  Eigen::MatrixXd K(3 * n, 3 * n);
  for (std::size_t p = 0; p < n; ++p) {
    for (int d = 0; d < 3; ++d) {
      Points plus = x, minus = x;
      plus[p][d] += h;
      minus[p][d] -= h;
      K.col(static_cast<Eigen::Index>(3 * p + d)) = (flat(forces(field, plus)) - flat(forces(field, minus))) / (2 * h);
    }
  }
  return K;
}

Points rigidly_moved(const Points& rest) {
  const Mat3<double> Q = Eigen::AngleAxisd(1.1, Vec3<double>(0.3, -1, 0.5).normalized()).toRotationMatrix();
  Points x = rest;
  for (auto& p : x) p = Q * p + Vec3<double>(0.7, -0.2, 1.5);
  return x;
}

Points deformed(const Points& rest, double amplitude) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Points x = rigidly_moved(rest);
  for (auto& p : x) p += Vec3<double>(u(random), u(random), u(random));
  return x;
}

const ElementRotationMethod kTetMethods[] = {ElementRotationMethod::triangle, ElementRotationMethod::polar,
                                             ElementRotationMethod::stable_polar};
const ElementRotationMethod kHexMethods[] = {ElementRotationMethod::hexahedron, ElementRotationMethod::polar,
                                             ElementRotationMethod::stable_polar};

TEST(ElementFemCorotational, RigidMotionOfTheRestShapeGivesNoForce) {
  const Grid grid;
  const Points x = rigidly_moved(grid.rest);
  for (auto method : kTetMethods) {
    const Points f = forces(*grid.tet_field(method), x);
    EXPECT_LT(flat(f).norm(), 1e-8 * kE) << to_string(method);
  }
  for (auto method : kHexMethods) {
    const Points f = forces(*grid.hex_field(method), x);
    EXPECT_LT(flat(f).norm(), 1e-8 * kE) << to_string(method);
  }
  // The force field's rotation is the motion's.
  auto field = grid.hex_field(ElementRotationMethod::hexahedron);
  forces(*field, x);
  const Mat3<double> Q = Eigen::AngleAxisd(1.1, Vec3<double>(0.3, -1, 0.5).normalized()).toRotationMatrix();
  EXPECT_LT((field->rotation(0) - Q).norm(), 1e-12);
}

TEST(ElementFemCorotational, StiffnessIsTheDerivativeOfTheForceAtRigidMotions) {
  // SOFA's tangent R K R^T leaves out dR/dx, whose term vanishes where d = 0 (rest shape, moved).
  const Grid grid;
  const Points x = rigidly_moved(grid.rest);
  std::vector<std::shared_ptr<ForceField<double>>> fields;
  for (auto method : kTetMethods) fields.push_back(grid.tet_field(method));
  for (auto method : kHexMethods) fields.push_back(grid.hex_field(method));
  for (auto& field : fields) {
    forces(*field, x);
    const Eigen::MatrixXd K = Eigen::MatrixXd(field->stiffness_matrix());
    auto copy = field;  // add_force inside the differences changes the recorded rotations only
    const Eigen::MatrixXd numeric = finite_difference_stiffness(*copy, x, 1e-6);
    EXPECT_LT(relative(K, numeric), 1e-6) << field->component() << " " << field->method_name();
  }
}

TEST(ElementFemLinearSmallStrain, StiffnessAndEnergyDerivatives) {
  const Grid grid;
  const Points x = deformed(grid.rest, 0.05);
  for (std::shared_ptr<ForceField<double>> field :
       {std::shared_ptr<ForceField<double>>(grid.tet_field(ElementRotationMethod::none)),
        std::shared_ptr<ForceField<double>>(grid.hex_field(ElementRotationMethod::none))}) {
    EXPECT_EQ(field->component(), "LinearSmallStrainFEMForceField");
    forces(*field, x);
    const Eigen::MatrixXd K = Eigen::MatrixXd(field->stiffness_matrix());
    EXPECT_LT(relative(K, finite_difference_stiffness(*field, x, 1e-6)), 1e-7);
    // f = -dE/dx.
    const Points f = forces(*field, x);
    for (std::size_t p = 0; p < x.size(); p += 5) {
      for (int d = 0; d < 3; ++d) {
        Points plus = x, minus = x;
        plus[p][d] += 1e-6;
        minus[p][d] -= 1e-6;
        const double dE = (field->potential_energy(plus) - field->potential_energy(minus)) / 2e-6;
        EXPECT_NEAR(-dE, f[p][d], 1e-5 * flat(f).norm());
      }
    }
  }
}

TEST(ElementFemLinearSmallStrain, TetrahedronAgreesWithTetrahedronFemSmall) {
  // SOFA's TetrahedronFEMForceField method small computes the same linear element in another way.
  const Grid grid;
  TetrahedronFEMForceField<double>::Parameters parameters;
  parameters.young_modulus = {kE};
  parameters.poisson_ratio = {kNu};
  parameters.method = TetrahedronFEMMethod::small;
  TetrahedronFEMForceField<double> reference(grid.tetrahedra(), grid.rest, parameters);
  auto field = grid.tet_field(ElementRotationMethod::none);
  const Points x = deformed(grid.rest, 0.02);
  EXPECT_LT((flat(forces(*field, x)) - flat(forces(reference, x))).norm(), 1e-10 * flat(forces(reference, x)).norm());
  EXPECT_LT(relative(Eigen::MatrixXd(field->stiffness_matrix()), Eigen::MatrixXd(reference.stiffness_matrix())), 1e-12);
}

TEST(ElementFemCorotational, DforceStiffnessAndDiagonalAgree) {
  const Grid grid;
  const Points x = deformed(grid.rest, 0.05);
  Points dx = deformed(grid.rest, 1.0);
  for (std::shared_ptr<ForceField<double>> field :
       {std::shared_ptr<ForceField<double>>(grid.tet_field(ElementRotationMethod::triangle)),
        std::shared_ptr<ForceField<double>>(grid.hex_field(ElementRotationMethod::hexahedron)),
        std::shared_ptr<ForceField<double>>(grid.hex_field(ElementRotationMethod::none))}) {
    forces(*field, x);
    // k = 0.3 + 2 * rayleighStiffness (0.1).
    Points df(x.size(), Vec3<double>::Zero());
    field->add_dforce(dx, df, 0.3, 2.0);
    const Eigen::MatrixXd K = Eigen::MatrixXd(field->stiffness_matrix(1.0));
    EXPECT_LT((flat(df) - 0.5 * K * flat(dx)).norm(), 1e-12 * (K * flat(dx)).norm());
    std::vector<Mat3<double>> diagonal(x.size(), Mat3<double>::Zero());
    field->add_diagonal_blocks(diagonal, 1.0);
    for (std::size_t p = 0; p < x.size(); ++p) {
      EXPECT_LT((diagonal[p] - K.block<3, 3>(3 * p, 3 * p)).norm(), 1e-12 * K.norm());
    }
    EXPECT_LT(relative(K, K.transpose()), 1e-14);
  }
}

TEST(ElementFemCorotational, ThreadCountDoesNotChangeTheBits) {
  // 18 × 10 × 10 cells: more elements than one parallel chunk.
  Points rest;
  std::vector<Hexahedron> hexahedra;
  const int nx = 19, ny = 11, nz = 11;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) rest.emplace_back(0.1 * i, 0.1 * j, 0.1 * k);
  const auto p = [&](int i, int j, int k) { return static_cast<Index>(i + nx * (j + ny * k)); };
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        hexahedra.push_back({p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k), p(i, j, k + 1),
                             p(i + 1, j, k + 1), p(i + 1, j + 1, k + 1), p(i, j + 1, k + 1)});
  const auto mesh = std::make_shared<TetMesh>(static_cast<Index>(rest.size()), hexahedra_tetrahedra(hexahedra));
  Hex one(mesh, hexahedra, rest, {}), four(mesh, hexahedra, rest, {});
  four.set_threads(4);
  const Points x = deformed(rest, 0.01);
  const Points f1 = forces(one, x), f4 = forces(four, x);
  Points d1(x.size(), Vec3<double>::Zero()), d4(x.size(), Vec3<double>::Zero());
  one.add_dforce(x, d1, 1.0);
  four.add_dforce(x, d4, 1.0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    ASSERT_EQ(f1[i], f4[i]);
    ASSERT_EQ(d1[i], d4[i]);
  }
}

TEST(ElementFemErrors, BadInputIsRefusedNamingTheValue) {
  const Grid grid;
  const auto message = [&](Hex::Parameters parameters, std::vector<Hexahedron> hexahedra) -> std::string {
    try {
      Hex field(grid.tetrahedra(), std::move(hexahedra), grid.rest, parameters);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  Hex::Parameters half;
  half.poisson_ratio = {0.5};
  EXPECT_NE(message(half, grid.hexahedra).find("oisson"), std::string::npos) << message(half, grid.hexahedra);
  Hex::Parameters three;
  three.young_modulus = {1, 2, 3};
  EXPECT_NE(message(three, grid.hexahedra).find("youngModulus: 3 values"), std::string::npos);
  Hex::Parameters negative;
  negative.young_modulus = {-1};
  EXPECT_NE(message(negative, grid.hexahedra).find("hexahedron 0"), std::string::npos);
  auto outside = grid.hexahedra;
  outside[1][3] = 99;
  EXPECT_NE(message({}, outside).find("hexahedron 1: point 99 outside"), std::string::npos);
  auto flat_element = grid.hexahedra;
  for (int j = 4; j < 8; ++j) flat_element[1][static_cast<std::size_t>(j)] = flat_element[1][static_cast<std::size_t>(j - 4)];
  EXPECT_NE(message({}, flat_element).find("hexahedron 1"), std::string::npos) << message({}, flat_element);
  EXPECT_THROW(parse_element_rotation_method("triangle", 8), Error);
  EXPECT_THROW(parse_element_rotation_method("large", 4), Error);
  EXPECT_EQ(parse_element_rotation_method("hexahedron", 8), ElementRotationMethod::hexahedron);
}

}  // namespace
}  // namespace fastcorot
