// PlaneForceField and ConicalForceField against their formulas worked out by hand, and their
// tangent against finite differences of the plane's forces (without damping, whose derivative
// SOFA leaves out) and against SOFA's normal-only tangent for the cone.
#include "fastcorot/fem/penalty_force_fields.h"

#include "fastcorot/core/error.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

#include <memory>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

std::shared_ptr<TetMesh> points_only(Index n) { return std::make_shared<TetMesh>(n, std::vector<Tetrahedron>{}); }

Eigen::VectorXd flat(const Points& p) {
  Eigen::VectorXd v(3 * static_cast<Eigen::Index>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i) v.segment<3>(3 * static_cast<Eigen::Index>(i)) = p[i];
  return v;
}

void expect_tangent_matches_differences(ForceField<double>& field, const Points& x) {
  Points f(x.size(), Vec3<double>::Zero());
  field.add_force(x, f);
  const auto force = [&](const Eigen::VectorXd& y) {
    Points p(x.size()), g(x.size(), Vec3<double>::Zero());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = y.segment<3>(3 * static_cast<Eigen::Index>(i));
    field.add_force_only(p, g);
    return flat(g);
  };
  const Eigen::MatrixXd k(field.stiffness_matrix());
  EXPECT_LT((k - testing::fd_jacobian(force, flat(x), 1e-7)).cwiseAbs().maxCoeff(), 1e-4 * std::max(1.0, k.cwiseAbs().maxCoeff()));
}

TEST(PlaneForceField, PushesPointsBelowThePlane) {
  PlaneForceField<double>::Parameters p;
  p.normal = {0, 1, 0};
  p.d = -1;
  p.stiffness = 100;
  p.damping = 2;
  PlaneForceField<double> field(points_only(3), p);
  const Points x = {{0, -1.5, 0}, {0, 0, 0}, {3, -1.25, 1}};
  const Points v = {{1, -2, 0}, {0, 0, 0}, {0, 0, 0}};
  Points f(3, Vec3<double>::Zero());
  field.set_velocity(v);
  field.add_force(x, f);
  // d = -0.5: f = -100 (-0.5) n + 2 (-0.5) v = (0, 50, 0) + (-1, 2, 0).
  EXPECT_NEAR((f[0] - Vec3<double>(-1, 52, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(f[1], Vec3<double>::Zero());
  EXPECT_NEAR(f[2].y(), 25, 1e-12);
  ASSERT_EQ(field.contacts().size(), 2u);
  EXPECT_NEAR(field.potential_energy(x), 100 * (0.25 + 0.0625) / 2, 1e-12);
  field.set_velocity({});
  expect_tangent_matches_differences(field, x);
  // maxForce scales the force down to that norm; bilateral acts above the plane too.
  p.max_force = 10;
  p.bilateral = true;
  PlaneForceField<double> limited(points_only(3), p);
  Points g(3, Vec3<double>::Zero());
  limited.add_force(x, g);
  EXPECT_NEAR(g[0].norm(), 10, 1e-12);
  EXPECT_NEAR(g[1].norm(), 10, 1e-12);  // d = 1 above: pushed down (-100), limited
  EXPECT_LT(g[1].y(), 0);
}

TEST(ConicalForceField, ThreeRegionsOutsideTheCone) {
  ConicalForceField<double>::Parameters p;
  p.center = {0, 0, 0};
  p.height = {0, 2, 0};
  p.angle = 45;
  p.stiffness = 10;
  p.damping = 0;
  ConicalForceField<double> field(points_only(4), p);
  const Points x = {{0, 1, 0.5},    // inside: no force
                    {0, 3, 0},      // beyond the base sphere: pulled back by 1 towards the apex
                    {1.2, 1, 0},    // beside: to the nearest point of the 45-degree surface
                    {0, -1, 0}};    // above the apex: back to it
  Points f(4, Vec3<double>::Zero());
  field.add_force(x, f);
  EXPECT_EQ(f[0], Vec3<double>::Zero());
  EXPECT_NEAR((f[1] - Vec3<double>(0, -10, 0)).norm(), 0, 1e-12);
  // (1.2, 1) to the line y = x: the foot (1.1, 1.1), distance 0.1 sqrt(2), direction (-1, 1)/sqrt(2).
  EXPECT_NEAR((f[2] - Vec3<double>(-1, 1, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((f[3] - Vec3<double>(0, 10, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(field.contacts().size(), 3u);
  // SOFA's tangent keeps the normal part only: -k n n^T at each contact.
  const Eigen::MatrixXd k(field.stiffness_matrix());
  const Vec3<double> n(-1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0);
  EXPECT_LT((k.block<3, 3>(6, 6) - Mat3<double>(-10 * n * n.transpose())).norm(), 1e-12);
  EXPECT_EQ((k.block<3, 3>(0, 0).norm()), 0);
  p.height = {0, 0, 0};
  EXPECT_THROW(ConicalForceField<double>(points_only(1), p), Error);
}

}  // namespace
}  // namespace fastcorot
