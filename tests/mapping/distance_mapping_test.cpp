// DistanceMapping (SOFA's DistanceMapping<Vec3, Vec1>) against references computed here: edge
// lengths minus rest lengths, J against central differences of the mapping, Jᵀ as J's transpose,
// row blocks as J, and the geometric stiffness against central differences of Jᵀ(x) F.
#include "fastcorot/mapping/distance_mapping.h"

#include "fastcorot/core/error.h"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

std::vector<Vec3<double>> random_points(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3<double>> x(n);
  for (auto& p : x) p = Vec3<double>(u(rng), u(rng), u(rng));
  return x;
}

const std::vector<Edge> kEdges = {{0, 1}, {1, 2}, {3, 2}, {0, 3}, {4, 1}};

TEST(DistanceMapping, ValuesAreLengthsMinusRestLengthsInX) {
  const auto rest = random_points(5, 1);
  const auto x = random_points(5, 2);
  DistanceMapping<double> mapping(kEdges, rest);
  std::vector<Vec3<double>> y(kEdges.size());
  mapping.apply(x, y);
  for (std::size_t i = 0; i < kEdges.size(); ++i) {
    const auto a = static_cast<std::size_t>(kEdges[i][0]), b = static_cast<std::size_t>(kEdges[i][1]);
    const double expected = std::sqrt((x[b] - x[a]).squaredNorm()) - std::sqrt((rest[b] - rest[a]).squaredNorm());
    EXPECT_NEAR(y[i][0], expected, 1e-15);
    EXPECT_EQ(y[i][1], 0.0);
    EXPECT_EQ(y[i][2], 0.0);
  }
  // At its own rest configuration every extension is zero.
  mapping.apply(rest, y);
  for (const auto& v : y) EXPECT_NEAR(v[0], 0.0, 1e-15);
}

TEST(DistanceMapping, JacobianIsTheDerivativeOfTheMapping) {
  const auto rest = random_points(5, 3);
  const auto x = random_points(5, 4);
  const auto dx = random_points(5, 5);
  DistanceMapping<double> mapping(kEdges, rest);
  std::vector<Vec3<double>> y(kEdges.size()), jdx(kEdges.size()), plus(kEdges.size()), minus(kEdges.size());
  mapping.apply(x, y);
  mapping.apply_j(dx, jdx);
  const double h = 1e-6;
  std::vector<Vec3<double>> xp(x), xm(x);
  for (std::size_t p = 0; p < x.size(); ++p) xp[p] += h * dx[p], xm[p] -= h * dx[p];
  mapping.positions(xp, plus);
  mapping.positions(xm, minus);
  for (std::size_t i = 0; i < kEdges.size(); ++i) {
    EXPECT_NEAR(jdx[i][0], (plus[i][0] - minus[i][0]) / (2 * h), 1e-8);
    EXPECT_EQ(jdx[i][1], 0.0);
  }
  // The velocities outputs show are J v at the same positions.
  std::vector<Vec3<double>> v(kEdges.size());
  mapping.velocities(x, dx, v);
  for (std::size_t i = 0; i < kEdges.size(); ++i) EXPECT_NEAR(v[i][0], jdx[i][0], 1e-15);
}

TEST(DistanceMapping, TransposeAndRowBlocksAgreeWithJ) {
  const auto rest = random_points(5, 6);
  const auto x = random_points(5, 7);
  const auto dx = random_points(5, 8);
  DistanceMapping<double> mapping(kEdges, rest);
  std::vector<Vec3<double>> y(kEdges.size()), jdx(kEdges.size());
  mapping.apply(x, y);
  mapping.apply_j(dx, jdx);
  std::vector<Vec3<double>> f(kEdges.size());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = Vec3<double>(0.3 * static_cast<double>(i) - 0.7, 0, 0);
  std::vector<Vec3<double>> jtf(5, Vec3<double>::Zero());
  mapping.apply_jt(f, jtf);
  double lhs = 0, rhs = 0;  // <J dx, f> = <dx, Jᵀ f>
  for (std::size_t i = 0; i < f.size(); ++i) lhs += jdx[i].dot(f[i]);
  for (std::size_t p = 0; p < dx.size(); ++p) rhs += dx[p].dot(jtf[p]);
  EXPECT_NEAR(lhs, rhs, 1e-14);
  std::vector<std::pair<Index, Mat3<double>>> blocks;
  for (std::size_t i = 0; i < kEdges.size(); ++i) {
    mapping.row_blocks(i, blocks);
    ASSERT_EQ(blocks.size(), 2u);
    EXPECT_LT(blocks[0].first, blocks[1].first);  // increasing parent order, as SOFA inserts them
    Vec3<double> sum = Vec3<double>::Zero();
    for (const auto& [p, j] : blocks) sum += j * dx[static_cast<std::size_t>(p)];
    EXPECT_NEAR(sum[0], jdx[i][0], 1e-15);
    EXPECT_EQ(sum[1], 0.0);
    EXPECT_EQ(sum[2], 0.0);
  }
}

TEST(DistanceMapping, ShortEdgeTakesSofasArbitraryDirection) {
  const std::vector<Vec3<double>> rest = {Vec3<double>::Zero(), Vec3<double>(1, 0, 0)};
  const auto d = DistanceMapping<double>::direction(Vec3<double>(1, 2, 3), Vec3<double>(1, 2, 3));
  EXPECT_EQ(d.inverse_length, 0.0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(d.u[k], 1 / std::sqrt(3.0), 1e-16);
  DistanceMapping<double> mapping({{0, 1}}, rest);
  std::vector<Vec3<double>> y(1);
  mapping.apply(std::vector<Vec3<double>>{Vec3<double>::Zero(), Vec3<double>::Zero()}, y);
  EXPECT_EQ(y[0][0], -1.0);
  EXPECT_TRUE(y[0].allFinite());
}

TEST(DistanceMapping, RestLengthsGivenOrZeroAndBadInputRefused) {
  const auto rest = random_points(5, 9);
  DistanceMapping<double> given(kEdges, rest, std::vector<double>(kEdges.size(), 0.0));
  std::vector<Vec3<double>> y(kEdges.size());
  given.apply(rest, y);
  EXPECT_NEAR(y[0][0], (rest[1] - rest[0]).norm(), 1e-15);
  EXPECT_THROW(DistanceMapping<double>(kEdges, rest, std::vector<double>(2, 1.0)), Error);
  EXPECT_THROW(DistanceMapping<double>({{0, 7}}, rest), Error);
  EXPECT_THROW(DistanceMapping<double>({{-1, 0}}, rest), Error);
}

// The parent force of a child force F is Jᵀ(x) F; its derivative with respect to x (F held) is the
// geometric stiffness.
std::vector<Vec3<double>> parent_force(const std::vector<Edge>& edges, const std::vector<Vec3<double>>& rest,
                                       const std::vector<Vec3<double>>& x, const std::vector<Vec3<double>>& child) {
  DistanceMapping<double> mapping(edges, rest);
  std::vector<Vec3<double>> y(edges.size()), f(x.size(), Vec3<double>::Zero());
  mapping.apply(x, y);
  mapping.apply_jt(child, f);
  return f;
}

TEST(DistanceGeometricStiffness, ExactIsTheDerivativeOfJTransposeF) {
  const auto rest = random_points(5, 10);
  const auto x = random_points(5, 11);
  const auto dx = random_points(5, 12);
  auto child = std::make_shared<std::vector<Vec3<double>>>();
  for (std::size_t i = 0; i < kEdges.size(); ++i) child->push_back(Vec3<double>(0.5 - 0.4 * static_cast<double>(i), 0, 0));
  const auto mesh = std::make_shared<const TetMesh>(5, std::vector<Tetrahedron>{});
  DistanceGeometricStiffness<double> field(mesh, kEdges, child, GeometricStiffnessMethod::exact);
  std::vector<Vec3<double>> no_force(5, Vec3<double>::Zero());
  field.add_force(x, no_force);
  for (const auto& f : no_force) EXPECT_EQ(f, Vec3<double>::Zero());
  std::vector<Vec3<double>> df(5, Vec3<double>::Zero());
  field.add_dforce(dx, df, 1.0);
  const double h = 1e-6;
  std::vector<Vec3<double>> xp(x), xm(x);
  for (std::size_t p = 0; p < x.size(); ++p) xp[p] += h * dx[p], xm[p] -= h * dx[p];
  const auto fp = parent_force(kEdges, rest, xp, *child), fm = parent_force(kEdges, rest, xm, *child);
  for (std::size_t p = 0; p < x.size(); ++p) {
    EXPECT_LT((df[p] - (fp[p] - fm[p]) / (2 * h)).norm(), 1e-8) << "point " << p;
  }
  // Assembled, and its diagonal, the same operator.
  const Eigen::SparseMatrix<double> k = field.stiffness_matrix(2.0);
  Eigen::VectorXd flat(15);
  for (std::size_t p = 0; p < 5; ++p) flat.segment<3>(static_cast<Eigen::Index>(3 * p)) = dx[p];
  const Eigen::VectorXd kdx = k * flat;
  std::vector<Mat3<double>> diagonal(5, Mat3<double>::Zero());
  field.add_diagonal_blocks(diagonal, 2.0);
  for (std::size_t p = 0; p < 5; ++p) {
    EXPECT_LT((kdx.segment<3>(static_cast<Eigen::Index>(3 * p)) - 2.0 * df[p]).norm(), 1e-14);
    const auto b = static_cast<Eigen::Index>(3 * p);
    EXPECT_LT((Mat3<double>(Eigen::MatrixXd(k).block(b, b, 3, 3)) - diagonal[p]).norm(), 1e-14);
  }
}

TEST(DistanceGeometricStiffness, StabilizedKeepsOnlyEdgesInTension) {
  const auto x = random_points(5, 13);
  const auto dx = random_points(5, 14);
  auto child = std::make_shared<std::vector<Vec3<double>>>(kEdges.size(), Vec3<double>(0.8, 0, 0));
  (*child)[2] = Vec3<double>(-0.6, 0, 0);  // only edge 2 pulls its ends together
  const auto mesh = std::make_shared<const TetMesh>(5, std::vector<Tetrahedron>{});
  DistanceGeometricStiffness<double> stabilized(mesh, kEdges, child, GeometricStiffnessMethod::stabilized);
  auto tension_only = std::make_shared<std::vector<Vec3<double>>>(kEdges.size(), Vec3<double>::Zero());
  (*tension_only)[2] = (*child)[2];
  DistanceGeometricStiffness<double> exact(mesh, kEdges, tension_only, GeometricStiffnessMethod::exact);
  std::vector<Vec3<double>> unused(5, Vec3<double>::Zero()), a(5, Vec3<double>::Zero()), b(5, Vec3<double>::Zero());
  stabilized.add_force(x, unused);
  exact.add_force(x, unused);
  stabilized.add_dforce(dx, a, 1.0);
  exact.add_dforce(dx, b, 1.0);
  for (std::size_t p = 0; p < 5; ++p) EXPECT_EQ(a[p], b[p]);
  // A stiffness in tension is negative semi-definite (the implicit step stays well posed).
  const Eigen::MatrixXd k(stabilized.stiffness_matrix());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k);
  EXPECT_LE(eigen.eigenvalues().maxCoeff(), 1e-12);
  EXPECT_LT(eigen.eigenvalues().minCoeff(), -1e-3);
  EXPECT_THROW(DistanceGeometricStiffness<double>(mesh, kEdges, child, GeometricStiffnessMethod::none), Error);
  EXPECT_THROW(DistanceGeometricStiffness<double>(mesh, {{0, 9}}, child, GeometricStiffnessMethod::exact), Error);
}

}  // namespace
}  // namespace fastcorot
