// RestShapeSpringsForceField against its law written out here (SOFA's RestShapeSpringsForceField for
// Vec3, commit 2a278d891f: f_i -= k_i mask (x_i - p0_i), K = -k_i mask on point i, k_i = stiffness[i]
// when i < #stiffness else stiffness[0]), finite differences of its energy and forces, and bad input.
#include "fastcorot/fem/rest_shape_springs_force_field.h"

#include "fastcorot/core/error.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

std::shared_ptr<TetMesh> points_mesh(Index n) { return std::make_shared<TetMesh>(n, std::vector<Tetrahedron>{}); }

Eigen::VectorXd flat(const Points& p) {
  Eigen::VectorXd v(3 * static_cast<Eigen::Index>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i) v.segment<3>(3 * static_cast<Eigen::Index>(i)) = p[i];
  return v;
}
Points points(const Eigen::VectorXd& v) {
  Points p(static_cast<std::size_t>(v.size() / 3));
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = v.segment<3>(3 * static_cast<Eigen::Index>(i));
  return p;
}

RestShapeSpringsForceField<double>::Parameters two_points() {
  RestShapeSpringsForceField<double>::Parameters p;
  p.points = {0, 2};
  p.anchors = {{0, 0, 0}, {1, 1, 1}};
  p.stiffness = {10, 30};
  return p;
}

TEST(RestShapeSpringsForceField, PullsEachPointTowardsItsAnchor) {
  RestShapeSpringsForceField<double> field(points_mesh(3), two_points());
  const Points x = {{1, 2, 3}, {5, 5, 5}, {1, 1, 2}};
  Points f(3, Vec3<double>::Zero());
  field.add_force(x, f);
  EXPECT_TRUE(f[0].isApprox(Vec3<double>(-10, -20, -30)));
  EXPECT_EQ(f[1].norm(), 0);  // not listed
  EXPECT_TRUE(f[2].isApprox(Vec3<double>(0, 0, -30)));
  EXPECT_NEAR(field.potential_energy(x), 10 * 14 / 2.0 + 30 * 1 / 2.0, 1e-12);
  const Eigen::MatrixXd k(field.stiffness_matrix());
  EXPECT_EQ(k(0, 0), -10);
  EXPECT_EQ(k(8, 8), -30);
  EXPECT_EQ(k(3, 3), 0);
  EXPECT_EQ((k - Eigen::MatrixXd(k.diagonal().asDiagonal())).norm(), 0);  // diagonal
}

TEST(RestShapeSpringsForceField, OneStiffnessForAllAndActiveDirections) {
  auto p = two_points();
  p.stiffness = {4};  // SOFA: k[0] for every point beyond the list
  p.active_directions = {true, false, true};
  RestShapeSpringsForceField<double> field(points_mesh(3), p);
  const Points x = {{1, 2, 3}, {0, 0, 0}, {2, 2, 2}};
  Points f(3, Vec3<double>::Zero());
  field.add_force(x, f);
  EXPECT_TRUE(f[0].isApprox(Vec3<double>(-4, 0, -12)));
  EXPECT_TRUE(f[2].isApprox(Vec3<double>(-4, 0, -4)));
  const Eigen::MatrixXd k(field.stiffness_matrix());
  EXPECT_EQ(k(1, 1), 0);
  EXPECT_EQ(k(6, 6), -4);
}

TEST(RestShapeSpringsForceField, ForceIsMinusTheEnergyGradientAndTheTangentItsJacobian) {
  auto p = two_points();
  p.active_directions = {false, true, true};
  p.rayleigh_stiffness = 0.5;
  RestShapeSpringsForceField<double> field(points_mesh(3), p);
  const Points x = {{0.3, -0.2, 0.1}, {1, 2, 3}, {1.2, 0.7, 1.4}};
  Points f(3, Vec3<double>::Zero());
  field.add_force(x, f);
  const auto energy = [&](const Eigen::VectorXd& y) { return field.potential_energy(points(y)); };
  EXPECT_LT((flat(f) + testing::fd_gradient(energy, flat(x), 1e-6)).cwiseAbs().maxCoeff(), 1e-8);
  const auto force = [&](const Eigen::VectorXd& y) {
    Points g(3, Vec3<double>::Zero());
    field.add_force_only(points(y), g);
    return flat(g);
  };
  const Eigen::MatrixXd k(field.stiffness_matrix());
  EXPECT_LT((k - testing::fd_jacobian(force, flat(x), 1e-6)).cwiseAbs().maxCoeff(), 1e-8);
  const Points dx = {{1, 2, 3}, {4, 5, 6}, {-1, 0.5, 2}};
  Points df(3, Vec3<double>::Zero());
  field.add_dforce(dx, df, 2.0, 2.0);  // 2 + 2 * 0.5 = 3
  EXPECT_LT((flat(df) - 3 * k * flat(dx)).cwiseAbs().maxCoeff(), 1e-12);
  std::vector<Mat3<double>> diagonal(3, Mat3<double>::Zero());
  field.add_diagonal_blocks(diagonal, 1.0);
  for (Eigen::Index i = 0; i < 3; ++i) EXPECT_EQ((diagonal[static_cast<std::size_t>(i)] - k.block<3, 3>(3 * i, 3 * i)).norm(), 0);
}

TEST(RestShapeSpringsForceField, BadInputIsRefused) {
  auto p = two_points();
  p.points = {0, 3};
  EXPECT_THROW(RestShapeSpringsForceField<double>(points_mesh(3), p), Error);
  p = two_points();
  p.stiffness = {10, -1};
  EXPECT_THROW(RestShapeSpringsForceField<double>(points_mesh(3), p), Error);
  p = two_points();
  p.anchors.pop_back();
  EXPECT_THROW(RestShapeSpringsForceField<double>(points_mesh(3), p), Error);
  p = two_points();
  p.stiffness.clear();
  EXPECT_THROW(RestShapeSpringsForceField<double>(points_mesh(3), p), Error);
}

}  // namespace
}  // namespace fastcorot
