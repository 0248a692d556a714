// Rigid3 positions and SOFA's `x += dx` (RigidCoord.h). References are closed forms: rotations
// built with Eigen's AngleAxis (independent of the code under test), the angle turned at
// constant angular velocity, and the exponential map of a rotation vector.
#include "fastcorot/state/rigid3.h"

#include "fastcorot/core/error.h"

#include "../support/error_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

using Quat = Eigen::Quaterniond;
using V3 = Vec3<double>;
using M3 = Mat3<double>;

using testing::contains;
using testing::error_of;

TEST(Rigid3, RotationAndRotateMatchAngleAxis) {
  const Eigen::AngleAxisd turn(1.3, V3(1, -2, 0.5).normalized());
  RigidCoord<double> x;
  x.center = V3(0.5, -1, 2);
  x.orientation = Quat(turn);
  const M3 expected = turn.toRotationMatrix();
  EXPECT_LT((x.rotation() - expected).norm(), 1e-14);
  const V3 p(0.3, 0.7, -1.1);
  EXPECT_LT((x.rotate(p) - expected * p).norm(), 1e-14);
  EXPECT_LT((x.inverse_rotate(p) - expected.transpose() * p).norm(), 1e-14);
  EXPECT_LT((x.project_point(p) - (expected * p + x.center)).norm(), 1e-14);
}

TEST(Rigid3, ProductComposesRotationsRightFirst) {
  const Quat a(Eigen::AngleAxisd(0.4, V3::UnitX()));
  const Quat b(Eigen::AngleAxisd(-1.1, V3(0, 1, 1).normalized()));
  RigidCoord<double> ab;
  ab.orientation = quaternion_product(a, b);
  EXPECT_LT((ab.rotation() - a.toRotationMatrix() * b.toRotationMatrix()).norm(), 1e-14);
}

TEST(Rigid3, IntegrateMovesCentreAndTurnsInTheWorldFrame) {
  // A body turned 90° about z, then a world rotation of 0.3 rad about x: R = Rx(0.3) Rz(90°).
  RigidCoord<double> x;
  x.center = V3(1, 2, 3);
  x.orientation = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, V3::UnitZ()));
  integrate(x, V3(0.1, -0.2, 0.3), V3(0.3, 0, 0));
  EXPECT_LT((x.center - V3(1.1, 1.8, 3.3)).norm(), 1e-15);
  const M3 expected = Eigen::AngleAxisd(0.3, V3::UnitX()).toRotationMatrix() *
                      Eigen::AngleAxisd(std::numbers::pi / 2, V3::UnitZ()).toRotationMatrix();
  EXPECT_LT((x.rotation() - expected).norm(), 1e-14);
}

TEST(Rigid3, ConstantAngularVelocityTurnsBy_N_h_Omega) {
  const V3 omega = V3(0.3, -1.2, 2.0);
  const double h = 0.01;
  const int steps = 1000;
  RigidCoord<double> x;
  const Quat start(Eigen::AngleAxisd(0.7, V3(1, 1, 0).normalized()));
  x.orientation = start;
  for (int s = 0; s < steps; ++s) integrate(x, V3::Zero(), V3(h * omega));
  // Closed form: a rotation of angle N h |ω| about ω, applied on the left of the start.
  const M3 expected = Eigen::AngleAxisd(steps * h * omega.norm(), omega.normalized()).toRotationMatrix() *
                      start.toRotationMatrix();
  EXPECT_LT((x.rotation() - expected).norm(), 1e-12);
  EXPECT_NEAR(x.orientation.norm(), 1.0, 1e-13);  // SOFA does not renormalise: round-off only
  // The angle turned, measured from the relative rotation.
  const Eigen::AngleAxisd turned(x.rotation() * start.toRotationMatrix().transpose());
  EXPECT_NEAR(turned.angle(), std::abs(std::remainder(steps * h * omega.norm(), 2 * std::numbers::pi)), 1e-11);
}

TEST(Rigid3, SmallAngleBranchContinuousWithTheExponential) {
  const Quat start(Eigen::AngleAxisd(2.1, V3(0, 0.6, 0.8)));
  const V3 axis = V3(1, 2, -2).normalized();
  const double eps = std::numeric_limits<double>::epsilon();
  // |dθ/2| just below and just above epsilon: the gnomonic branch and the exponential one.
  for (const double half : {0.5 * eps, 0.999 * eps, 1.001 * eps, 2 * eps}) {
    RigidCoord<double> x;
    x.orientation = start;
    integrate(x, V3::Zero(), V3(2 * half * axis));
    // exp(dθ/2) = (sin θ/θ · dθ/2, cos θ) to first order: (dθ/2, 1).
    const Quat e(1.0, half * axis[0], half * axis[1], half * axis[2]);
    const Quat expected = e * start;
    EXPECT_LT((x.orientation.coeffs() - expected.coeffs()).norm(), 4 * eps) << "half angle " << half;
    EXPECT_NEAR(x.orientation.norm(), 1.0, 4 * eps);
  }
  // A zero rotation leaves the orientation exactly as it was.
  RigidCoord<double> x;
  x.orientation = start;
  integrate(x, V3::Zero(), V3::Zero());
  EXPECT_EQ(x.orientation.coeffs(), start.coeffs());
}

TEST(Rigid3, IntegrateInFloat) {
  RigidCoord<float> x;
  for (int s = 0; s < 100; ++s) integrate(x, Vec3<float>::Zero(), Vec3<float>(0, 0, 0.01f));
  const Mat3<float> expected = Eigen::AngleAxisf(1.0f, Vec3<float>::UnitZ()).toRotationMatrix();
  EXPECT_LT((x.rotation() - expected).norm(), 1e-5f);
}

TEST(Rigid3, SofaNormalizeOnlyBeyondItsTolerance) {
  Quat q(1 + 1e-12, 0, 0, 0);  // within SOFA's 1e-10 on |q|²: unchanged
  normalize_as_sofa(q);
  EXPECT_EQ(q.w(), 1 + 1e-12);
  Quat r = quaternion_xyzw(0.0, 0.0, 3.0, 4.0);
  normalize_as_sofa(r);
  EXPECT_NEAR(r.z(), 0.6, 1e-15);
  EXPECT_NEAR(r.w(), 0.8, 1e-15);
  Quat zero = quaternion_xyzw(0.0, 0.0, 0.0, 0.0);
  normalize_as_sofa(zero);
  EXPECT_EQ(zero.w(), 1.0);
}

TEST(Rigid3, ParsesTextInSofaOrderAndBack) {
  const std::vector<double> values = {1, 2, 3, 0, 0, 0.6, 0.8, -1, -2, -3, 0, 0, 0, 1};
  const auto coords = parse_rigid_coords<double>(values, "scene.scn:4 MechanicalObject position");
  ASSERT_EQ(coords.size(), 2u);
  EXPECT_EQ(coords[0].center, V3(1, 2, 3));
  EXPECT_EQ(coords[0].orientation.z(), 0.6);
  EXPECT_EQ(coords[0].orientation.w(), 0.8);
  EXPECT_EQ(to_values<double>(coords), values);
  // Kept as written, as SOFA's release build reads it (no normalisation).
  const std::vector<double> long_q = {0, 0, 0, 0, 0, 0.7071, 0.7071};
  EXPECT_EQ(parse_rigid_coords<double>(long_q, "x")[0].orientation.w(), 0.7071);
}

TEST(Rigid3, ParseErrorsNameTheObjectAndRigid) {
  const std::string where = "scene.scn:4 MechanicalObject position";
  const std::vector<double> eight = {1, 2, 3, 0, 0, 0, 1, 5};
  std::string e = error_of([&] { parse_rigid_coords<double>(eight, where); });
  EXPECT_TRUE(contains(e, where)) << e;
  EXPECT_TRUE(contains(e, "7 numbers per rigid")) << e;
  const std::vector<double> zero_q = {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 0, 0, 0, 0};
  e = error_of([&] { parse_rigid_coords<double>(zero_q, where); });
  EXPECT_TRUE(contains(e, "rigid 1 has a zero quaternion")) << e;
  const std::vector<double> nan = {0, 0, 0, 0, 0, 0, 1, 0, std::nan(""), 0, 0, 0, 0, 1};
  e = error_of([&] { parse_rigid_coords<double>(nan, where); });
  EXPECT_TRUE(contains(e, "rigid 1 has a non-finite value")) << e;
}

TEST(Rigid3, VelocitiesAreTwoBlocksPerRigid) {
  const std::vector<double> values = {1, 2, 3, 4, 5, 6, -1, -2, -3, -4, -5, -6};
  const auto blocks = parse_rigid_derivs<double>(values, "velocity");
  ASSERT_EQ(blocks.size(), 4u);
  EXPECT_EQ(blocks[0], V3(1, 2, 3));  // v0
  EXPECT_EQ(blocks[1], V3(4, 5, 6));  // ω0
  EXPECT_EQ(blocks[3], V3(-4, -5, -6));
  EXPECT_EQ(rigid_deriv_values<double>(blocks), values);
  const std::vector<double> seven = {1, 2, 3, 4, 5, 6, 7};
  const std::string e = error_of([&] { parse_rigid_derivs<double>(seven, "obj velocity"); });
  EXPECT_TRUE(contains(e, "obj velocity")) << e;
  EXPECT_TRUE(contains(e, "6 numbers per rigid")) << e;
}

}  // namespace
}  // namespace fastcorot
