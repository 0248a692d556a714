// StickContactForceField against SOFA's VectorSpringForceField formula (f = ks (y₂ − y₁ − R) +
// kd (v₂ − v₁) on side 1, its opposite on side 2), its stiffness against central differences of its
// force (weighted row blocks on several blocks, a rigid-like block with a cross-product row), the
// assembled matrix and diagonal against the product, an obstacle side, and bad springs refused.
#include "fastcorot/collision/stick_contact_force_field.h"

#include "fastcorot/core/error.h"

#include "support/linearisation.h"

#include <gtest/gtest.h>

#include <random>

namespace fastcorot {
namespace {

using V = Vec3<double>;
using M = Mat3<double>;

std::shared_ptr<const TetMesh> points(Index n) { return std::make_shared<const TetMesh>(n, std::vector<Tetrahedron>{}); }

TEST(StickContactForceField, SofasVectorSpringFormula) {
  // Two points, the spring made with rest R, then point 1 moved by u: f₀ = ks (u) + kd (v₁ − v₀).
  StickSpring<double> s;
  s.side1 = {{0, M::Identity()}};
  s.side2 = {{1, M::Identity()}};
  const std::vector<V> x = {V(0, 0, 0), V(1, 2, 0)};
  s.y1 = x[0];
  s.y2 = x[1];
  s.rest = V(1, 2, 0);
  s.stiffness = 60;
  s.damping = 1.5;
  s.relative_velocity = V(0, -2, 0);
  StickContactForceField<double> field(points(2));
  field.set_springs({s}, x);
  std::vector<V> f(2, V::Zero());
  const std::vector<V> moved = {V(0, 0, 0), V(1.1, 2, -0.3)};
  field.add_force(moved, f);
  const V expected = V(0.1, 0, -0.3) * 60 + V(0, -2, 0) * 1.5;
  EXPECT_LT((f[0] - expected).norm(), 1e-12);
  EXPECT_LT((f[0] + f[1]).norm(), 1e-15);
  EXPECT_NEAR(field.potential_energy(moved), 0.5 * 60 * (0.01 + 0.09), 1e-12);
}

TEST(StickContactForceField, StiffnessIsTheForcesDerivative) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<V> x(5);
  for (auto& p : x) p = V(u(rng), u(rng), u(rng));
  StickSpring<double> s;
  s.side1 = {{0, 0.2 * M::Identity()}, {1, 0.5 * M::Identity()}, {2, 0.3 * M::Identity()}};
  // Side 2 a point carried by a rigid body (blocks 3, 4): I on the linear block, −[r]× on the angular.
  const V r(0.3, -0.2, 0.5);
  M cross;
  cross << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  s.side2 = {{3, M::Identity()}, {4, -cross}};
  s.y1 = 0.2 * x[0] + 0.5 * x[1] + 0.3 * x[2];
  s.y2 = x[3] + r;
  s.rest = s.y2 - s.y1 + V(0.05, -0.1, 0.02);
  s.stiffness = 9;
  StickContactForceField<double> field(points(5));
  field.set_springs({s}, x);
  std::vector<V> dx(5);
  for (auto& p : dx) p = V(u(rng), u(rng), u(rng));
  testing::expect_linearisation_is_the_forces_derivative(field, field, x, dx);
  const Eigen::MatrixXd k(field.stiffness_matrix(2.0));
  EXPECT_LT((Eigen::MatrixXd(k) - Eigen::MatrixXd(k).transpose()).norm(), 1e-12) << "symmetric";
}

TEST(StickContactForceField, AnObstacleSideAndBadInput) {
  StickSpring<double> s;
  s.side2 = {{0, M::Identity()}};  // side 1: a still point
  s.y1 = V(0, -1, 0);
  s.y2 = V(0, 0, 0);
  s.rest = V(0, 1, 0);
  s.stiffness = 10;
  StickContactForceField<double> field(points(1));
  const std::vector<V> x = {V::Zero()};
  field.set_springs({s}, x);
  std::vector<V> f(1, V::Zero());
  field.add_force(std::vector<V>{V(0, 0.5, 0)}, f);
  EXPECT_LT((f[0] - V(0, -5, 0)).norm(), 1e-15) << "pulled back toward where it was made";
  s.damping = -1;
  EXPECT_THROW(field.set_springs({s}, x), Error);
  s.damping = 0;
  s.side2 = {{2, M::Identity()}};
  EXPECT_THROW(field.set_springs({s}, x), Error);
  s.side2 = {{0, M::Identity()}};
  s.rest = V(0, std::nan(""), 0);
  EXPECT_THROW(field.set_springs({s}, x), Error);
}

}  // namespace
}  // namespace fastcorot
