// SlidingLagrangianConstraint against rows written by hand: H on the sliding point and on the
// segment's ends (weighted by the projection's barycentric coordinate), the violations on the free
// positions, the blocks' resolutions (two bilateral rows, two unilateral ones), the point on the
// line (SOFA's fallback direction), the ends together (three bilateral rows), unsimulated points
// (no entries), and indices out of range.
#include "fastcorot/constraint/sliding_lagrangian_constraint.h"
#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fastcorot {
namespace {

// Own points of object `object`, at `start` when the step begins and `free` after the free motion.
ConstraintPoints<double> own_points(std::size_t object, const std::vector<Vec3<double>>& start, const std::vector<Vec3<double>>& free) {
  ConstraintPoints<double> points;
  points.object = object;
  for (std::size_t i = 0; i < start.size(); ++i) points.blocks.push_back(static_cast<Index>(i));
  points.rest_position = start;
  points.position = start;
  points.free_position = free;
  points.free_velocity.assign(start.size(), Vec3<double>::Zero());
  return points;
}

// Column `row` of Hᵀ on object o as one dense vector (3 per point).
Eigen::VectorXd column(const ConstraintRows<double>& rows, std::size_t o, Index points, int row) {
  return Eigen::MatrixXd(rows.transposed(o, points)).col(row);
}

Eigen::VectorXd stacked(std::initializer_list<Vec3<double>> blocks) {
  Eigen::VectorXd v(3 * static_cast<Eigen::Index>(blocks.size()));
  Eigen::Index k = 0;
  for (const auto& b : blocks) v.segment<3>(3 * k++) = b;
  return v;
}

void expect_near(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  EXPECT_LT((a - b).norm(), 1e-14) << what << "\n" << a.transpose() << "\nexpected\n" << b.transpose();
}

TEST(SlidingLagrangianConstraint, RowsViolationsAndResolutionsAsWrittenByHand) {
  // Segment A = (0, 0, 0) to B = (2, 0, 0) (object 1); P = (0.5, 0.3, 0.4) (object 0): axis a = x,
  // P projects at 0.5, β = 0.25, n = (0, 0.6, 0.8), n × a = (0, 0.8, -0.6).
  const Vec3<double> free_p(0.6, 0.35, 0.4), free_a(0, 0.01, 0), free_b(2, 0.01, 0);
  SlidingLagrangianConstraint<double> sliding("test", own_points(0, {{0.5, 0.3, 0.4}}, {free_p}),
                                              own_points(1, {{0, 0, 0}, {2, 0, 0}}, {free_a, free_b}), {0, 0, 1});
  ConstraintRows<double> rows(2);
  rows.add_rows(1);  // a row of another constraint before it
  sliding.build(rows);
  ASSERT_EQ(sliding.first_row(), 1);
  ASSERT_EQ(sliding.rows(), 4);
  EXPECT_DOUBLE_EQ(sliding.barycentric_coordinate(), 0.25);
  const Vec3<double> n(0, 0.6, 0.8), o(0, 0.8, -0.6), a(1, 0, 0), zero = Vec3<double>::Zero();
  expect_near(column(rows, 0, 1, 1), stacked({n}), "row 0 on P");
  expect_near(column(rows, 1, 2, 1), stacked({-0.75 * n, -0.25 * n}), "row 0 on A, B");
  expect_near(column(rows, 0, 1, 2), stacked({o}), "row 1 on P");
  expect_near(column(rows, 1, 2, 2), stacked({-0.75 * o, -0.25 * o}), "row 1 on A, B");
  expect_near(column(rows, 0, 1, 3), stacked({a}), "row 2 on P");
  expect_near(column(rows, 1, 2, 3), stacked({-a, zero}), "row 2 on A, B");
  expect_near(column(rows, 0, 1, 4), stacked({-a}), "row 3 on P");
  expect_near(column(rows, 1, 2, 4), stacked({zero, a}), "row 3 on A, B");
  EXPECT_EQ(column(rows, 0, 1, 0).norm(), 0);

  // Violations: P_f - (β B_f + (1 - β) A_f) = (0.1, 0.34, 0.4) on n and n × a; (P_f - A_f)·a; (P_f - B_f)·(-a).
  double dfree[5] = {7, 0, 0, 0, 0};
  sliding.violation(ConstraintOrder::position_and_velocity, 0.01, dfree);
  EXPECT_EQ(dfree[0], 7) << "another constraint's row is left alone";
  EXPECT_NEAR(dfree[1], 0.34 * 0.6 + 0.4 * 0.8, 1e-15);
  EXPECT_NEAR(dfree[2], 0.34 * 0.8 - 0.4 * 0.6, 1e-15);
  EXPECT_NEAR(dfree[3], 0.6, 1e-15);
  EXPECT_NEAR(dfree[4], 1.4, 1e-15);

  ConstraintProblem<double> problem;
  problem.clear(5);
  problem.add_block(std::make_unique<UnilateralResolution<double>>());
  sliding.add_resolutions(problem);
  ASSERT_EQ(problem.resolutions.size(), 5u);
  for (std::size_t b = 1; b < 5; ++b) EXPECT_EQ(problem.resolutions[b]->lines(), 1);
  EXPECT_NE(dynamic_cast<BilateralResolution1<double>*>(problem.resolutions[1].get()), nullptr);
  EXPECT_NE(dynamic_cast<BilateralResolution1<double>*>(problem.resolutions[2].get()), nullptr);
  EXPECT_NE(dynamic_cast<UnilateralResolution<double>*>(problem.resolutions[3].get()), nullptr);
  EXPECT_NE(dynamic_cast<UnilateralResolution<double>*>(problem.resolutions[4].get()), nullptr);
  EXPECT_NO_THROW(problem.check_blocks());
}

TEST(SlidingLagrangianConstraint, PointBeyondAnEndClampsTheProjectionThere) {
  // P projects at 3 on a segment of length 2: β = 1, rows 0 and 1 act on B alone.
  SlidingLagrangianConstraint<double> sliding("test", own_points(0, {{3, 0, 1}}, {{3, 0, 1}}),
                                              own_points(1, {{0, 0, 0}, {2, 0, 0}}, {{0, 0, 0}, {2, 0, 0}}), {0, 0, 1});
  ConstraintRows<double> rows(2);
  sliding.build(rows);
  EXPECT_EQ(sliding.barycentric_coordinate(), 1);
  const Vec3<double> n(0, 0, 1);
  expect_near(column(rows, 1, 2, 0), stacked({Vec3<double>::Zero(), -n}), "row 0 on A, B");
  double dfree[4];
  sliding.violation(ConstraintOrder::position_and_velocity, 0.01, dfree);
  EXPECT_NEAR(dfree[0], 1, 1e-15);   // P - B on n
  EXPECT_NEAR(dfree[3], -1, 1e-15);  // beyond B: the stop row is violated
}

TEST(SlidingLagrangianConstraint, PointOnTheLineTakesSofasDirectionAcross) {
  // a = x: (1, 0, 0) × a vanishes, so SOFA takes (1, 1, 0) × a = (0, 0, -1); then n × a = (0, -1, 0).
  SlidingLagrangianConstraint<double> sliding("test", own_points(0, {{1, 0, 0}}, {{1, 0, 0}}),
                                              own_points(1, {{0, 0, 0}, {4, 0, 0}}, {{0, 0, 0}, {4, 0, 0}}), {0, 0, 1});
  ConstraintRows<double> rows(2);
  sliding.build(rows);
  expect_near(column(rows, 0, 1, 0), stacked({{0, 0, -1}}), "row 0 on P");
  expect_near(column(rows, 0, 1, 1), stacked({{0, -1, 0}}), "row 1 on P");
  // Along z: (1, 0, 0) × z = (0, -1, 0).
  SlidingLagrangianConstraint<double> vertical("test", own_points(0, {{0, 0, 1}}, {{0, 0, 1}}),
                                               own_points(1, {{0, 0, 0}, {0, 0, 4}}, {{0, 0, 0}, {0, 0, 4}}), {0, 0, 1});
  ConstraintRows<double> rows_z(2);
  vertical.build(rows_z);
  expect_near(column(rows_z, 0, 1, 0), stacked({{0, -1, 0}}), "row 0 on P (axis z)");
  expect_near(column(rows_z, 0, 1, 1), stacked({{-1, 0, 0}}), "row 1 on P (axis z)");
}

TEST(SlidingLagrangianConstraint, EndsTogetherHoldThePointOnThem) {
  SlidingLagrangianConstraint<double> sliding("test", own_points(0, {{1, 2, 3}}, {{1.5, 2, 3}}),
                                              own_points(1, {{0, 0, 0}, {0, 0, 0}}, {{0.25, 0, 0}, {0, 0, 0}}), {0, 0, 1});
  ConstraintRows<double> rows(2);
  sliding.build(rows);
  ASSERT_EQ(sliding.rows(), 3);
  for (int k = 0; k < 3; ++k) {
    Vec3<double> e = Vec3<double>::Zero();
    e[k] = 1;
    expect_near(column(rows, 0, 1, k), stacked({e}), "on P");
    expect_near(column(rows, 1, 2, k), stacked({-e, Vec3<double>::Zero()}), "on A");
  }
  double dfree[3];
  sliding.violation(ConstraintOrder::velocity, 0.01, dfree);
  EXPECT_EQ(dfree[0], 1.25);
  EXPECT_EQ(dfree[1], 2);
  EXPECT_EQ(dfree[2], 3);
  ConstraintProblem<double> problem;
  problem.clear(3);
  sliding.add_resolutions(problem);
  ASSERT_EQ(problem.resolutions.size(), 3u);
  for (const auto& r : problem.resolutions) EXPECT_NE(dynamic_cast<BilateralResolution1<double>*>(r.get()), nullptr);
}

TEST(SlidingLagrangianConstraint, UnsimulatedPointsGetNoEntries) {
  ConstraintPoints<double> rail;
  rail.unsimulated = true;
  rail.position = rail.free_position = {{0, 0, 0}, {2, 0, 0}};
  SlidingLagrangianConstraint<double> sliding("test", own_points(0, {{0.5, 0.3, 0.4}}, {{0.5, 0.3, 0.4}}), rail, {0, 0, 1});
  ConstraintRows<double> rows(1);
  sliding.build(rows);
  EXPECT_EQ(rows.size(), 4);
  EXPECT_TRUE(rows.touches(0));
  expect_near(column(rows, 0, 1, 0), stacked({{0, 0.6, 0.8}}), "row 0 on P");
}

TEST(SlidingLagrangianConstraint, IndicesOutOfRangeAreNamed) {
  const auto make = [](SlidingLagrangianConstraint<double>::Parameters p) {
    SlidingLagrangianConstraint<double>("test", own_points(0, {{0, 0, 0}}, {{0, 0, 0}}),
                                        own_points(1, {{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}), p);
  };
  const auto message = [&](SlidingLagrangianConstraint<double>::Parameters p) -> std::string {
    try {
      make(p);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(message({1, 0, 1}).find("sliding_point = 1 is out of range"), std::string::npos) << message({1, 0, 1});
  EXPECT_NE(message({0, -1, 1}).find("axis_1 = -1"), std::string::npos);
  EXPECT_NE(message({0, 0, 2}).find("axis_2 = 2 is out of range: object2 has 2 points"), std::string::npos) << message({0, 0, 2});
  EXPECT_EQ(message({0, 0, 1}), "");
}

}  // namespace
}  // namespace fastcorot
