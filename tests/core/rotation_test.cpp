#include "fastcorot/core/rotation.h"

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

Mat3<double> axis_rotation(double angle, Vec3<double> axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

TEST(QrFrame, RestFrameOfSpecExampleTetrahedron) {
  // SPEC.md example: points (0,0,0) (1,0,0) (0,1,0) (0,0,1), tetrahedron (2,3,1,0), so
  // p0 = (0,1,0), p1 = (0,0,1), p2 = (1,0,0). By hand: x = (0,-1,1)/√2, x × (p2-p0) ∝ (1,1,1),
  // z = (1,1,1)/√3, y = z × x = (2,-1,-1)/√6.
  const Vec3<double> p0(0, 1, 0), p1(0, 0, 1), p2(1, 0, 0);
  const Mat3<double> frame = qr_frame<double>(p1 - p0, p2 - p0);
  const double r2 = std::sqrt(2.0), r3 = std::sqrt(3.0), r6 = std::sqrt(6.0);
  Mat3<double> expected;
  expected << 0, -1 / r2, 1 / r2, 2 / r6, -1 / r6, -1 / r6, 1 / r3, 1 / r3, 1 / r3;
  EXPECT_LT((frame - expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(QrFrame, IsARotationWithFirstRowAlongA) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3<double> a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    const Mat3<double> frame = qr_frame(a, b);
    EXPECT_LT((frame * frame.transpose() - Mat3<double>::Identity()).norm(), 1e-14);
    EXPECT_NEAR(frame.determinant(), 1.0, 1e-14);
    EXPECT_LT((frame.row(0).transpose() - a.normalized()).norm(), 1e-15);
    // b lies in the plane of the first two rows, on the positive side of the second.
    EXPECT_NEAR(frame.row(2).dot(b), 0.0, 1e-14);
    EXPECT_GT(frame.row(1).dot(b), 0.0);
  }
}

TEST(QrFrame, CommutesWithRotations) {
  const Mat3<double> q = axis_rotation(0.9, Vec3<double>(1, -2, 0.5));
  const Vec3<double> a(0.3, 1.2, -0.4), b(-0.7, 0.2, 0.9);
  EXPECT_LT((qr_frame<double>(q * a, q * b) - qr_frame(a, b) * q.transpose()).norm(), 1e-14);
}

Mat3<double> svd_polar(const Mat3<double>& m) {
  Eigen::JacobiSVD<Mat3<double>> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

TEST(PolarFactor, RecoversTheRotationOfRotatedStretch) {
  // M = Q S with Q a rotation and S symmetric positive definite: the polar factor is Q.
  const Mat3<double> q = axis_rotation(0.7, Vec3<double>(1, 2, 3));
  Mat3<double> s;
  s << 1.1, 0.05, -0.02, 0.05, 0.95, 0.03, -0.02, 0.03, 1.02;
  EXPECT_LT((polar_factor<double>(q * s) - q).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((polar_factor<float>((q * s).cast<float>()) - q.cast<float>()).cwiseAbs().maxCoeff(), 1e-6f);
}

TEST(PolarFactor, AgreesWithSvdOnRandomMatrices) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Mat3<double> m;
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = u(rng);
    if (std::abs(m.determinant()) < 1e-3) continue;
    const Mat3<double> q = polar_factor(m);
    EXPECT_LT((q - svd_polar(m)).cwiseAbs().maxCoeff(), 1e-10) << m;
    EXPECT_LT((q.transpose() * q - Mat3<double>::Identity()).norm(), 1e-12);
    // Q^T M is the symmetric factor.
    const Mat3<double> s = q.transpose() * m;
    EXPECT_LT((s - s.transpose()).norm(), 1e-10);
  }
}

TEST(PolarFactor, InvertedMatrixGivesAReflectionLikeSofa) {
  // SPEC.md: for det F < 0 SOFA's iteration converges to an orthogonal matrix of determinant -1.
  const Mat3<double> q = axis_rotation(0.4, Vec3<double>(0, 1, 1));
  const Mat3<double> m = q * Vec3<double>(1.2, 0.9, -0.8).asDiagonal();
  const Mat3<double> factor = polar_factor(m);
  EXPECT_NEAR(factor.determinant(), -1.0, 1e-12);
  EXPECT_LT((factor - q * Vec3<double>(1, 1, -1).asDiagonal().toDenseMatrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(PolarFactor, SingularAndNonFiniteInputReturnWithoutHanging) {
  const Mat3<double> zero = Mat3<double>::Zero();
  EXPECT_EQ(polar_factor(zero), zero);  // a zero determinant stops the iteration at once
  Mat3<double> nan = Mat3<double>::Identity();
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(polar_factor(nan).allFinite());
}

// SOFA's iteration overflows into NaN for these (found while testing collapsed elements): a
// smallest singular value far below the largest makes the scaled iterate grow like its inverse
// square root until the determinant overflows; huge entries overflow the norms; tiny ones make
// the determinant underflow to zero. Each is a rotated diagonal matrix, whose polar factor is the
// rotation itself (a reflection for a negative entry).
template <class Real>
void expect_polar_factor_of_rotated_diagonal(const Vec3<Real>& diagonal, Real tolerance) {
  const Mat3<Real> q = axis_rotation(0.6, Vec3<double>(1, -1, 2)).cast<Real>();
  const Mat3<Real> factor = polar_factor<Real>(q * diagonal.asDiagonal());
  ASSERT_TRUE(factor.allFinite()) << diagonal.transpose();
  const Vec3<Real> signs = diagonal.unaryExpr([](Real v) { return v < 0 ? Real(-1) : Real(1); });
  EXPECT_LT((factor - q * signs.asDiagonal()).cwiseAbs().maxCoeff(), tolerance) << diagonal.transpose();
}

TEST(PolarFactor, NearlySingularHugeAndTinyMatricesGiveTheRotationNotNaN) {
  for (double small : {1e-250, 1e-300, -1e-300}) {
    expect_polar_factor_of_rotated_diagonal<double>(Vec3<double>(1, 0.5, small), 1e-12);
  }
  expect_polar_factor_of_rotated_diagonal<double>(Vec3<double>(1e160, 3e159, 2e159), 1e-12);
  expect_polar_factor_of_rotated_diagonal<double>(Vec3<double>(1e-200, 2e-200, 3e-200), 1e-12);
  for (float small : {1e-25f, 1e-38f}) {
    expect_polar_factor_of_rotated_diagonal<float>(Vec3<float>(1, 0.5f, small), 1e-5f);
  }
  expect_polar_factor_of_rotated_diagonal<float>(Vec3<float>(1e20f, 3e19f, 1), 1e-5f);
  expect_polar_factor_of_rotated_diagonal<float>(Vec3<float>(1e-20f, 2e-20f, 3e-20f), 1e-5f);
}

// Beyond that (a subnormal singular value, whose few bits of precision the cofactors lose, or
// singular values 1e300 apart) the result is finite but need not be the rotation: the contract is
// no NaN, not accuracy (docs/robustness.md, "Inverted and collapsed elements").
TEST(PolarFactor, ExtremelyIllConditionedMatricesGiveAFiniteResult) {
  const Mat3<double> q = axis_rotation(0.6, Vec3<double>(1, -1, 2));
  for (const Vec3<double>& diagonal : {Vec3<double>(1, 0.5, 1e-310), Vec3<double>(1, 0.5, 5e-324),
                                       Vec3<double>(1e300, 1, 1), Vec3<double>(1e300, 1e-300, 1)}) {
    EXPECT_TRUE(polar_factor<double>(q * diagonal.asDiagonal()).allFinite()) << diagonal.transpose();
  }
  const Mat3<float> qf = q.cast<float>();
  for (const Vec3<float>& diagonal : {Vec3<float>(1, 0.5f, 1e-44f), Vec3<float>(1e30f, 1, 1e-30f)}) {
    EXPECT_TRUE(polar_factor<float>(qf * diagonal.asDiagonal()).allFinite()) << diagonal.transpose();
  }
}

TEST(PolarFactor, ExactlySingularMatrixIsReturnedAsSofaDoes) {
  // Rank 2 with a zero determinant computed exactly: the first iterate stops the iteration.
  Mat3<double> flat;
  flat << 1, 2, 0, 3, 4, 0, 5, 6, 0;
  EXPECT_EQ(polar_factor(flat), flat);
}

// polar_factors (four lanes at a time) against polar_factor one by one, bit for bit: random
// matrices near rotations (as elements' edge matrices are), far from them, inverted, with the
// special inputs above mixed in (lanes computed again alone), and counts that leave a remainder.
template <class Real>
void expect_polar_factors_bitwise(std::mt19937& random) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> scale(-8, 8);
  std::vector<Mat3<Real>> m;
  for (int k = 0; k < 4000; ++k) {
    Mat3<double> a = axis_rotation(3 * u(random), Vec3<double>(u(random), u(random), u(random)));
    Mat3<double> noise;
    for (int i = 0; i < 9; ++i) noise.data()[i] = u(random);
    a += (k % 3 == 0 ? 1.0 : 0.05) * noise;                      // near a rotation, or anything
    if (k % 7 == 0) a.col(0) = -a.col(0);                          // inverted
    m.push_back((std::ldexp(1.0, scale(random)) * a).template cast<Real>());
  }
  Mat3<Real> flat;
  flat << 1, 2, 0, 3, 4, 0, 5, 6, 0;
  m[5] = flat;                                                      // singular: stops at once
  m[9] = (axis_rotation(0.6, Vec3<double>(1, -1, 2)) * Vec3<double>(1, 0.5, 1e-300).asDiagonal()).template cast<Real>();
  m[14](1, 1) = std::numeric_limits<Real>::quiet_NaN();             // not finite: returned as is
  m[22] = Mat3<Real>::Constant(Real(1e30));                         // huge and singular
  for (const int count : {4000, 3999, 3, 1}) {
    std::vector<Mat3<Real>> out(static_cast<std::size_t>(count));
    polar_factors(m.data(), out.data(), count);
    for (int k = 0; k < count; ++k) {
      const Mat3<Real> one = polar_factor(m[static_cast<std::size_t>(k)]);
      ASSERT_EQ(std::memcmp(one.data(), out[static_cast<std::size_t>(k)].data(), sizeof one), 0)
          << "matrix " << k << " of " << count << ":\n" << m[static_cast<std::size_t>(k)];
    }
  }
}

TEST(PolarFactors, FourAtATimeEqualOneByOneBitForBit) {
  std::mt19937 random(11);
  expect_polar_factors_bitwise<double>(random);
  expect_polar_factors_bitwise<float>(random);
}

// qr_frames (four lanes at a time) against qr_frame one by one, bit for bit, zero and parallel
// edges mixed in, with counts that leave a remainder.
template <class Real>
void expect_qr_frames_bitwise(std::mt19937& random) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3<Real>> a, b;
  for (int k = 0; k < 4001; ++k) {
    a.push_back(Vec3<double>(u(random), u(random), u(random)).template cast<Real>() * Real(1 + k % 5));
    b.push_back(Vec3<double>(u(random), u(random), u(random)).template cast<Real>());
  }
  a[6].setZero();                 // a zero edge
  b[9] = Real(3) * a[9];          // parallel edges: a zero normal
  a[13](1) = std::numeric_limits<Real>::quiet_NaN();
  for (const int count : {4001, 4000, 2}) {
    std::vector<Mat3<Real>> out(static_cast<std::size_t>(count));
    qr_frames(a.data(), b.data(), out.data(), count);
    for (int k = 0; k < count; ++k) {
      const Mat3<Real> one = qr_frame(a[static_cast<std::size_t>(k)], b[static_cast<std::size_t>(k)]);
      ASSERT_EQ(std::memcmp(one.data(), out[static_cast<std::size_t>(k)].data(), sizeof one), 0)
          << "frame " << k << " of " << count;
    }
  }
}

TEST(QrFrames, FourAtATimeEqualOneByOneBitForBit) {
  std::mt19937 random(12);
  expect_qr_frames_bitwise<double>(random);
  expect_qr_frames_bitwise<float>(random);
}

TEST(PolarFrame, IsThePolarFactorOfTheRowMatrix) {
  const Vec3<double> a(1, 0.1, 0), b(0.2, 1, 0.1), c(0, -0.1, 1.1);
  Mat3<double> rows;
  rows << a.transpose(), b.transpose(), c.transpose();
  EXPECT_LT((polar_frame(a, b, c) - svd_polar(rows)).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(PolarTolerance, IsSofas) {
  EXPECT_EQ(polar_tolerance<double>(), 1e-8);
  EXPECT_EQ(polar_tolerance<float>(), 1e-6f);
}

}  // namespace
}  // namespace fastcorot
