// The Rigid3 Fixed and Bilateral Lagrangian constraints against independent rotations (Eigen's
// angle-axis and Euler angles of rotation matrices): SOFA's quaternion helpers (toEulerVector,
// quatToRotationVector, quatDiff), the rows of H on the centres' and rotations' blocks, the
// violations on the free poses (a rotation offset in the angular block turning the start
// orientation), keepOrientationDifference, the resolutions, and indices out of range.
#include "fastcorot/constraint/rigid_lagrangian_constraints.h"
#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace fastcorot {
namespace {

using Quaternion = Eigen::Quaterniond;

Quaternion rotation(double angle, const Vec3<double>& axis) { return Quaternion(Eigen::AngleAxisd(angle, axis.normalized())); }

// The rotation vector (axis × angle in [0, π]) of a rotation matrix, from Eigen.
Vec3<double> rotation_vector(const Mat3<double>& r) {
  const Eigen::AngleAxisd aa(r);
  return aa.angle() * aa.axis();
}

TEST(RigidLagrangianConstraints, SofasQuaternionHelpers) {
  // toEulerVector: q = Rz(yaw) Ry(pitch) Rx(roll) gives (roll, pitch, yaw).
  const Quaternion q = Quaternion(Eigen::AngleAxisd(0.7, Vec3<double>::UnitZ()) * Eigen::AngleAxisd(-0.2, Vec3<double>::UnitY()) *
                                  Eigen::AngleAxisd(0.3, Vec3<double>::UnitX()));
  EXPECT_LT((sofa_euler_vector(q) - Vec3<double>(0.3, -0.2, 0.7)).norm(), 1e-14);
  // ... also from a quaternion that is not unit (normalised first).
  Quaternion scaled = q;
  scaled.coeffs() *= 2;
  EXPECT_LT((sofa_euler_vector(scaled) - Vec3<double>(0.3, -0.2, 0.7)).norm(), 1e-14);
  // quatToRotationVector: axis × angle, on both branches (w > 0.999 and not), and past π.
  const Vec3<double> n = Vec3<double>(1, -2, 0.5).normalized();
  EXPECT_LT((sofa_rotation_vector(rotation(0.8, n)) - 0.8 * n).norm(), 1e-14);
  EXPECT_LT((sofa_rotation_vector(rotation(0.01, n)) - 0.01 * n).norm(), 1e-15);
  EXPECT_LT((sofa_rotation_vector(rotation(3.5, n)) + (2 * std::numbers::pi - 3.5) * n).norm(), 1e-13);
  EXPECT_EQ(sofa_rotation_vector(Quaternion::Identity()), Vec3<double>::Zero());
  // quatDiff(a, b) = b⁻¹ a, a negated when a·b < 0 (the same rotation).
  const Quaternion a = rotation(0.4, {0, 1, 1}), b = rotation(-1.1, {1, 0, 2});
  const Mat3<double> expected = b.toRotationMatrix().transpose() * a.toRotationMatrix();
  EXPECT_LT((sofa_quaternion_difference(a, b).toRotationMatrix() - expected).norm(), 1e-14);
  Quaternion minus_a = a;
  minus_a.coeffs() *= -1;
  const Quaternion d = sofa_quaternion_difference(minus_a, b);
  EXPECT_LT((d.coeffs() - sofa_quaternion_difference(a, b).coeffs()).norm(), 1e-15) << "the sign follows b";
}

// Two rigids of object `object` at blocks (0, 1) and (2, 3): orientations q0, q1 at the step's
// start, centres c, free centres cf and free rotation offsets theta (the angular blocks).
RigidConstraintFrames<double> frames(std::size_t object, const std::vector<Quaternion>& q, const std::vector<Vec3<double>>& c,
                                     const std::vector<Vec3<double>>& cf, const std::vector<Vec3<double>>& theta) {
  auto rigids = std::make_shared<RigidBlocks<double>>();
  rigids->block = {0, 2};
  rigids->orientation = q;
  rigids->rest_orientation = {Quaternion::Identity(), rotation(0.5, {0, 0, 1})};
  RigidConstraintFrames<double> f;
  f.rigids = rigids;
  f.index = {0, 1};
  for (auto* points : {&f.linear, &f.angular}) points->object = object;
  f.linear.blocks = {0, 2};
  f.angular.blocks = {1, 3};
  f.linear.position = c;
  f.linear.free_position = cf;
  f.angular.position = {Vec3<double>::Zero(), Vec3<double>::Zero()};
  f.angular.free_position = theta;
  for (auto* points : {&f.linear, &f.angular}) points->free_velocity.assign(2, Vec3<double>::Zero());
  f.linear.rest_position = {{0, 0, 0}, {1, 2, 3}};
  f.angular.rest_position.assign(2, Vec3<double>::Zero());
  for (std::size_t k = 0; k < 2; ++k) {
    RigidCoord<double> rest;
    rest.center = f.linear.rest_position[k];
    rest.orientation = rigids->rest_orientation[k];
    f.rest.push_back(rest);
    RigidCoord<double> now;
    now.center = c[k];
    now.orientation = q[k];
    f.initial.push_back(now);
  }
  return f;
}

// The free orientation matrix: the start orientation turned by theta (world frame).
Mat3<double> turned(const Quaternion& q, const Vec3<double>& theta) {
  return Eigen::AngleAxisd(theta.norm(), theta.normalized()).toRotationMatrix() * q.toRotationMatrix();
}

TEST(RigidLagrangianConstraints, FixedRowsAndViolationsOnTheFreePose) {
  const Quaternion q1 = rotation(0.6, {1, 1, 0});
  const Vec3<double> theta(0.01, -0.02, 0.015), cf(1.1, 2.05, 2.9);
  RigidFixedLagrangianConstraint<double> fixed("test", frames(0, {Quaternion::Identity(), q1}, {{0, 0, 0}, {1, 2, 3}},
                                                              {{0, 0, 0}, cf}, {Vec3<double>::Zero(), theta}),
                                               {1});
  ConstraintRows<double> rows(1);
  fixed.build(rows);
  ASSERT_EQ(fixed.rows(), 6);
  const Eigen::MatrixXd ht(rows.transposed(0, 4));
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(12, 6);
  expected.block<3, 3>(6, 0).setIdentity();  // the centre of rigid 1 (block 2)
  expected.block<3, 3>(9, 3).setIdentity();  // its rotation (block 3)
  EXPECT_EQ(ht, expected);

  double dfree[6];
  fixed.violation(ConstraintOrder::position_and_velocity, 0.01, dfree);
  const Vec3<double> linear = cf - Vec3<double>(1, 2, 3);
  // q_free q_rest⁻¹ as a matrix, and its roll, pitch, yaw (R = Rz Ry Rx).
  const Mat3<double> difference = turned(q1, theta) * rotation(0.5, {0, 0, 1}).toRotationMatrix().transpose();
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(dfree[a], linear[a], 1e-15);
  // The angles (roll, pitch, yaw) rebuild it as Rz(yaw) Ry(pitch) Rx(roll), pitch in [-π/2, π/2].
  const Mat3<double> rebuilt = (Eigen::AngleAxisd(dfree[5], Vec3<double>::UnitZ()) * Eigen::AngleAxisd(dfree[4], Vec3<double>::UnitY()) *
                                Eigen::AngleAxisd(dfree[3], Vec3<double>::UnitX()))
                                   .toRotationMatrix();
  EXPECT_LT((rebuilt - difference).norm(), 1e-12);
  EXPECT_LE(std::abs(dfree[4]), std::numbers::pi / 2);
  EXPECT_GT(Vec3<double>(dfree[3], dfree[4], dfree[5]).norm(), 0.1) << "a rotation worth measuring";

  ConstraintProblem<double> problem;
  problem.clear(6);
  fixed.add_resolutions(problem);
  ASSERT_EQ(problem.resolutions.size(), 2u);
  for (const auto& r : problem.resolutions) EXPECT_NE(dynamic_cast<BilateralResolution3<double>*>(r.get()), nullptr);
}

TEST(RigidLagrangianConstraints, BilateralRowsAndViolations) {
  const Quaternion qp = rotation(0.3, {0, 0, 1}), qq = rotation(-0.4, {1, 2, 0});
  const Vec3<double> theta_p(0.02, 0, 0.01), theta_q(0, -0.03, 0);
  auto first = frames(0, {Quaternion::Identity(), qp}, {{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1.01, 0.02, 0}},
                      {Vec3<double>::Zero(), theta_p});
  auto second = frames(1, {qq, Quaternion::Identity()}, {{3, 1, 0}, {5, 0, 0}}, {{3.1, 0.9, 0.05}, {5, 0, 0}},
                       {theta_q, Vec3<double>::Zero()});
  RigidBilateralLagrangianConstraint<double>::Parameters p;
  p.first = {1};
  p.second = {0, 1};  // the shorter list decides: one pair
  p.rest = {{0.5, 0.25, 0, 0.01, 0.02, 0.03}};
  RigidBilateralLagrangianConstraint<double> tie("test", first, second, p);
  ConstraintRows<double> rows(2);
  tie.build(rows);
  ASSERT_EQ(tie.rows(), 6);
  Eigen::MatrixXd h1 = Eigen::MatrixXd::Zero(12, 6), h2 = Eigen::MatrixXd::Zero(12, 6);
  h1.block<3, 3>(6, 0) = -Mat3<double>::Identity();
  h1.block<3, 3>(9, 3) = -Mat3<double>::Identity();
  h2.block<3, 3>(0, 0).setIdentity();
  h2.block<3, 3>(3, 3).setIdentity();
  EXPECT_EQ(Eigen::MatrixXd(rows.transposed(0, 4)), h1);
  EXPECT_EQ(Eigen::MatrixXd(rows.transposed(1, 4)), h2);

  double dfree[6];
  tie.violation(ConstraintOrder::position_and_velocity, 0.01, dfree);
  const Vec3<double> linear = Vec3<double>(3.1, 0.9, 0.05) - Vec3<double>(1.01, 0.02, 0) - Vec3<double>(0.5, 0.25, 0);
  // P.rotate(log(P⁻¹ Q)) is the world rotation vector of Q Pᵀ.
  const Vec3<double> angular = rotation_vector(turned(qq, theta_q) * turned(qp, theta_p).transpose()) - Vec3<double>(0.01, 0.02, 0.03);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(dfree[a], linear[a], 1e-15);
    EXPECT_NEAR(dfree[3 + a], angular[a], 1e-13);
  }
  ConstraintProblem<double> problem;
  problem.clear(6);
  tie.add_resolutions(problem);
  EXPECT_EQ(problem.resolutions.size(), 2u);
}

TEST(RigidLagrangianConstraints, BilateralKeepsTheInitialDifference) {
  // At init P = (c 0, qp), Q = (c (2, 0, 0), qq); the free poses move both by the same rigid
  // translation, so the kept difference gives no linear violation, and Q's turn alone the angular one.
  const Quaternion qp = rotation(0.3, {0, 0, 1}), qq = rotation(-0.4, {1, 2, 0});
  const Vec3<double> shift(0.1, -0.2, 0.05), theta_q(0, 0.02, 0);
  auto first = frames(0, {qp, Quaternion::Identity()}, {{0, 0, 0}, {9, 9, 9}}, {shift, {9, 9, 9}}, {Vec3<double>::Zero(), Vec3<double>::Zero()});
  auto second = frames(1, {qq, Quaternion::Identity()}, {{2, 0, 0}, {8, 8, 8}}, {Vec3<double>(2, 0, 0) + shift, {8, 8, 8}},
                       {theta_q, Vec3<double>::Zero()});
  RigidBilateralLagrangianConstraint<double>::Parameters p;
  p.first = {0};
  p.second = {0};
  p.rest = {{1, 1, 1, 1, 1, 1}};  // ignored with keepOrientationDifference
  p.keep_orientation_difference = true;
  RigidBilateralLagrangianConstraint<double> tie("test", first, second, p);
  ConstraintRows<double> rows(2);
  tie.build(rows);
  double dfree[6];
  tie.violation(ConstraintOrder::position_and_velocity, 0.01, dfree);
  // P' = P ⊗ (P₀⁻¹ Q₀) = Q₀ here (P did not turn): the violation is Q's turn, theta_q.
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(dfree[a], 0, 1e-15);
    EXPECT_NEAR(dfree[3 + a], theta_q[a], 1e-13);
  }
}

TEST(RigidLagrangianConstraints, IndicesOutOfRangeAreNamed) {
  const auto f = [] {
    return frames(0, {Quaternion::Identity(), Quaternion::Identity()}, {{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}},
                  {Vec3<double>::Zero(), Vec3<double>::Zero()});
  };
  try {
    RigidFixedLagrangianConstraint<double>("test", f(), {0, 2});
    FAIL() << "accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("indices[1] = 2 is out of range: the Rigid3 state has 2 rigids"), std::string::npos) << error.what();
  }
  RigidBilateralLagrangianConstraint<double>::Parameters p;
  p.first = {0};
  p.second = {-1};
  EXPECT_THROW(RigidBilateralLagrangianConstraint<double>("test", f(), f(), p), Error);
  p.second = {1};
  p.rest = {{0, 0, 0, std::nan(""), 0, 0}};
  EXPECT_THROW(RigidBilateralLagrangianConstraint<double>("test", f(), f(), p), Error);
}

}  // namespace
}  // namespace fastcorot
