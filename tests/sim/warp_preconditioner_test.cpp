// WarpPreconditioner with its RotationMatrixSystem (SOFA's WarpPreconditioner.inl and
// RotationMatrixSystem.inl, 2a278d891f) and the rotation finders (rotation_finder.h). References:
// Eigen's dense solve of the matrix taken column by column from the matrix-free product, and a
// rigid rotation Q of the whole grid, whose every element rotation is Q.
#include "fastcorot/sim/warp_preconditioner.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/hexahedron_fem_force_field.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"
#include "fastcorot/sim/rotation_finder.h"
#include "support/random_rhs.h"
#include "support/solver_systems.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using Warp = WarpPreconditioner<double>;
using testing::dense_system_matrix;
using testing::flat_vector;

Warp::Parameters rate(int r) {
  Warp::Parameters p;
  p.assembling_rate = r;
  return p;
}

Eigen::VectorXd applied(const Warp& warp, const Eigen::VectorXd& r) {
  Eigen::VectorXd z(r.size());
  warp.apply(r.data(), z.data(), static_cast<Index>(r.size()));
  return z;
}

TEST(WarpPreconditioner, DefaultRateIsSofasAndZeroIsRefused) {
  EXPECT_EQ(Warp::Parameters{}.assembling_rate, 1);
  try {
    Warp warp(rate(0));
    ADD_FAILURE() << "accepted assemblingRate 0";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("assemblingRate"), std::string::npos) << error.what();
  }
}

TEST(WarpPreconditioner, WithTheIdentityRotationItIsTheDirectSolver) {
  // Rate 1: every build assembles, R = I, P = A^-1 of the current matrix.
  auto system = testing::grid_system(3, 0.15, Mat3<double>::Identity(), true);
  Warp warp(rate(1));
  const Eigen::VectorXd r = flat_vector(testing::projected_rhs(system, 4));
  for (const MatrixFactors<double>& factors : {testing::kEulerFactors, MatrixFactors<double>{2.0, -0.1, -0.02}}) {
    warp.build(system, factors);
    const Eigen::VectorXd expected = dense_system_matrix(system, factors).ldlt().solve(r);
    EXPECT_LT((applied(warp, r) - expected).norm() / expected.norm(), 1e-12);
    for (const auto& block : warp.rotations()) EXPECT_EQ(block, Mat3<double>::Identity());
  }
}

TEST(WarpPreconditioner, BetweenAssembliesItTurnsTheOldMatrixByThePointRotations) {
  // The grid turned rigidly by Q, TetrahedronFEMForceField: each point's rotation is Q. Rate 2: the
  // first build assembles A_1 (R = I), the second takes R = Q with A_1 kept, the third assembles.
  const Mat3<double> q = Eigen::AngleAxisd(0.7, Vec3<double>(1, 2, 2).normalized()).toRotationMatrix();
  auto system = testing::grid_system(0, 0.0, q, true);
  Warp warp(rate(2));
  const MatrixFactors<double> first = testing::kEulerFactors, second{3.0, -0.05, -0.01};
  const Eigen::VectorXd r = flat_vector(testing::projected_rhs(system, 5));
  warp.build(system, first);
  const Eigen::MatrixXd a1 = dense_system_matrix(system, first);
  EXPECT_LT((applied(warp, r) - a1.ldlt().solve(r)).norm() / r.norm(), 1e-12);
  warp.build(system, second);
  Eigen::MatrixXd turn = Eigen::MatrixXd::Zero(r.size(), r.size());
  for (Eigen::Index i = 0; i < r.size(); i += 3) turn.block<3, 3>(i, i) = q;
  const Eigen::VectorXd expected = turn * a1.ldlt().solve(turn.transpose() * r);
  EXPECT_LT((applied(warp, r) - expected).norm() / expected.norm(), 1e-10);
  warp.build(system, second);
  EXPECT_LT((applied(warp, r) - dense_system_matrix(system, second).ldlt().solve(r)).norm() / r.norm(), 1e-12);
}

TEST(WarpPreconditioner, HexahedraReportThePolarFactorOfTheMeanWithTheIdentityAdded) {
  // One cube turned by Q about z by 0.8 rad: SOFA's node rotation is polar((I + Q R0^T) / 1) with
  // R0 = I for the axis-aligned cube, the rotation about z by half the angle.
  const std::vector<Vec3<double>> rest = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  HexahedronFEMForceField<double>::Parameters p;
  auto field = std::make_shared<HexahedronFEMForceField<double>>(8, std::vector<Hexahedron>{{0, 1, 2, 3, 4, 5, 6, 7}}, rest, p);
  const Mat3<double> q = Eigen::AngleAxisd(0.8, Vec3<double>::UnitZ()).toRotationMatrix();
  std::vector<Vec3<double>> x;
  for (const auto& point : rest) x.push_back(q * point);
  std::vector<Vec3<double>> f(8, Vec3<double>::Zero());
  field->add_force(x, f);
  MechanicalSystem<double> system;
  system.state.position = x;
  system.state.rest_position = rest;
  system.force_fields.push_back(field);
  system.finalize();
  std::vector<Mat3<double>> initial;
  const auto rotations = find_rotations(system, initial);
  ASSERT_TRUE(rotations.has_value());
  const Mat3<double> half = Eigen::AngleAxisd(0.4, Vec3<double>::UnitZ()).toRotationMatrix();
  // The element frame R maps world to element (R = Q^T here), so R R0^T = Q^T: its half turn.
  for (const auto& block : *rotations) EXPECT_LT((block - half.transpose()).norm(), 1e-7) << block;
}

TEST(WarpPreconditioner, PcgWithRateOneSolvesInOneIteration) {
  auto system = testing::grid_system(8, 0.15, Mat3<double>::Identity(), true);
  using PCG = PreconditionedConjugateGradientSolver<double>;
  PCG::Parameters p;
  p.iterations = 100;
  p.tolerance = 1e-20;
  p.preconditioner = Preconditioner::solver;
  p.solver = std::make_shared<Warp>(rate(1));
  PCG solver(p, system.size());
  const Points b = testing::projected_rhs(system, 9);
  Points x(static_cast<std::size_t>(system.size()));
  EXPECT_LE(solver.solve(system, testing::kEulerFactors, b, x).iterations, 2);
  const Eigen::VectorXd exact = dense_system_matrix(system, testing::kEulerFactors).ldlt().solve(flat_vector(b));
  EXPECT_LT((flat_vector(x) - exact).norm() / exact.norm(), 1e-12);
  // The PCG carries the warp's state after its own: a resumed PCG (with a warp of its own) continues
  // bitwise the same.
  PCG::Parameters q = p;
  q.solver = std::make_shared<Warp>(rate(1));
  PCG resumed(q, system.size());
  resumed.restore_carried_state(solver.carried_state());
  Points y = x;
  const Points b2 = testing::projected_rhs(system, 10);
  solver.solve(system, {2.0, 0.0, -0.1}, b2, x);
  resumed.solve(system, {2.0, 0.0, -0.1}, b2, y);
  EXPECT_EQ(x, y);
}

TEST(WarpPreconditioner, CarriedStateRestoresCounterRotationsAndMatrix) {
  const Mat3<double> q = Eigen::AngleAxisd(0.3, Vec3<double>::UnitX()).toRotationMatrix();
  auto system = testing::grid_system(1, 0.05, q, true);
  Warp built(rate(3)), restored(rate(3));
  built.build(system, testing::kEulerFactors);
  built.build(system, testing::kEulerFactors);
  restored.restore_carried_state(built.carried_state());
  const Eigen::VectorXd r = flat_vector(testing::projected_rhs(system, 2));
  EXPECT_EQ(applied(built, r), applied(restored, r));
  built.build(system, {2, 0, -0.1});
  restored.build(system, {2, 0, -0.1});
  EXPECT_EQ(applied(built, r), applied(restored, r));
  EXPECT_THROW(restored.restore_carried_state(std::vector<std::int64_t>{9, 0, 0}), Error);  // counter above the rate
}

}  // namespace
}  // namespace fastcorot
