// Partial projections and end-of-step placements of MechanicalSystem (the projective constraints
// of SOFA beyond FixedProjectiveConstraint), against the dense P A P + (I - P) written out here.
#include "fastcorot/sim/mechanical_system.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/spring_force_field.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

MechanicalSystem<double> make_system() {
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const Points rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  MeshSpringParameters<double> p;
  p.tetrahedra_stiffness = 10;
  MechanicalSystem<double> system;
  system.state.position = {{0, 0, 0}, {1.2, 0.1, 0}, {0.1, 0.9, 0.2}, {0, 0.1, 1.3}};
  system.state.rest_position = rest;
  system.force_fields.push_back(std::make_shared<SpringForceField<double>>(mesh, mesh_springs<double>(*mesh, rest, p)));
  system.mass = Mass<double>::lumped({1, 2, 3, 4});
  return system;
}

Mat3<double> plane_projector(const Vec3<double>& normal) {
  const Vec3<double> n = normal.normalized();
  return Mat3<double>::Identity() - n * n.transpose();
}

TEST(Projections, AssembledMatrixIsPAPPlusTheComplement) {
  MechanicalSystem<double> system = make_system();
  const Mat3<double> plane = plane_projector({1, 2, 2});
  const Mat3<double> axis = Vec3<double>(1, 0, 1).asDiagonal();  // y held
  system.projections = {{2, plane}, {1, axis}, {2, axis}};      // point 2: plane, then axis
  system.fixed = {0};
  system.finalize();
  ASSERT_EQ(system.projections.size(), 2u);
  EXPECT_EQ(system.projections[0].point, 1);
  EXPECT_LT((system.projections[1].projector - axis * plane).norm(), 1e-15);
  Points f(4, Vec3<double>::Zero());
  system.compute_force(system.state.position, f);
  const MatrixFactors<double> factors{1.0, 0.0, -0.5};
  const Eigen::MatrixXd a(system.assemble(factors));

  // Dense reference: A0 = M - 0.5 K, P block diagonal, fixed point 0 cleared with a unit diagonal.
  Eigen::MatrixXd a0 = Eigen::MatrixXd::Zero(12, 12);
  for (int i = 0; i < 4; ++i) a0.block<3, 3>(3 * i, 3 * i) = (i + 1.0) * Mat3<double>::Identity();
  a0 += -0.5 * Eigen::MatrixXd(system.force_fields[0]->stiffness_matrix());
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(12, 12);
  p.block<3, 3>(0, 0).setZero();
  p.block<3, 3>(3, 3) = axis;
  p.block<3, 3>(6, 6) = axis * plane;
  Eigen::MatrixXd expected = p * a0 * p + (Eigen::MatrixXd::Identity(12, 12) - p);
  expected.block<3, 3>(0, 0).setIdentity();
  EXPECT_LT((a - expected).cwiseAbs().maxCoeff(), 1e-12);

  // The matrix-free product is P A0 dx (projected after the product).
  Eigen::VectorXd dx(12);
  for (int i = 0; i < 12; ++i) dx[i] = 0.1 * i - 0.4;
  Points dxp(4), out(4);
  for (int i = 0; i < 4; ++i) dxp[static_cast<std::size_t>(i)] = dx.segment<3>(3 * i);
  system.multiply(factors, dxp, out);
  Eigen::VectorXd product(12);
  for (int i = 0; i < 4; ++i) product.segment<3>(3 * i) = out[static_cast<std::size_t>(i)];
  EXPECT_LT((product - p * a0 * dx).cwiseAbs().maxCoeff(), 1e-12);
  std::vector<Mat3<double>> blocks(4);
  system.diagonal_blocks(factors, blocks);
  for (int i = 0; i < 4; ++i) EXPECT_LT((blocks[static_cast<std::size_t>(i)] - expected.block<3, 3>(3 * i, 3 * i)).norm(), 1e-12);
}

TEST(Projections, PlacementsProjectPositionsAndVelocities) {
  MechanicalSystem<double> system = make_system();
  const Vec3<double> origin(0, 0, 0.5);
  const Mat3<double> plane = plane_projector({0, 0, 1});
  system.placements = {{3, plane, origin, plane}};
  system.state.velocity = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 2, 3}};
  system.finalize();
  system.apply_placements();
  EXPECT_EQ(system.state.position[3], Vec3<double>(0, 0.1, 0.5));
  EXPECT_EQ(system.state.velocity[3], Vec3<double>(1, 2, 0));
  EXPECT_EQ(system.state.position[2], Vec3<double>(0.1, 0.9, 0.2));
}

TEST(Projections, MotionsFollowSofasLinearInterpolation) {
  MechanicalSystem<double> system = make_system();
  system.motions = {{1, Vec3<double>(1, 0, 0), Vec3<double>(3, 0, 0), 1.0, 3.0}};
  system.state.velocity.assign(4, Vec3<double>(1, 1, 1));
  system.finalize();
  system.apply_placements(0.5);  // before the motion: left where it is
  EXPECT_EQ(system.state.position[1], Vec3<double>(1.2, 0.1, 0));
  EXPECT_EQ(system.state.velocity[1], Vec3<double>::Zero());
  system.apply_placements(2.0);  // ((3 - 1) 2 + (1 * 3 - 3 * 1)) / 2
  EXPECT_EQ(system.state.position[1], Vec3<double>(2, 0, 0));
  system.apply_placements(5.0);
  EXPECT_EQ(system.state.position[1], Vec3<double>(3, 0, 0));
  EXPECT_EQ(system.state.velocity[0], Vec3<double>(1, 1, 1));
}

// Two tetrahedra (points 0-3 and 4-7) with springs, as two objects side by side.
MechanicalSystem<double> make_pair_system() {
  auto mesh = std::make_shared<TetMesh>(8, std::vector<Tetrahedron>{{0, 1, 2, 3}, {4, 5, 6, 7}});
  Points rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 4; ++i) rest.push_back(rest[static_cast<std::size_t>(i)] + Vec3<double>(0, 0, 1));
  MeshSpringParameters<double> p;
  p.tetrahedra_stiffness = 10;
  MechanicalSystem<double> system;
  system.state.position = rest;
  for (std::size_t i = 0; i < 8; ++i) system.state.position[i] += Vec3<double>(0.05 * i, -0.02 * i * i, 0.01);
  system.state.rest_position = rest;
  system.force_fields.push_back(std::make_shared<SpringForceField<double>>(mesh, mesh_springs<double>(*mesh, rest, p)));
  // Masses 1..8, filled in a loop: with GCC 12's AddressSanitizer and detect_stack_use_after_return,
  // an eight-value initializer list here read its backing array from a bad address.
  std::vector<double> masses;
  for (int i = 1; i <= 8; ++i) masses.push_back(i);
  system.mass = Mass<double>::lumped(std::move(masses));
  return system;
}

TEST(Projections, CouplingsAssembleAsTheirOperatorWritten) {
  MechanicalSystem<double> system = make_pair_system();
  const Mat3<double> axis = Vec3<double>(1, 0, 1).asDiagonal();
  // One way: point 4 follows point 3. Two ways: points 1 and 6 meet with factor 0.3.
  system.couplings = {{3, 4, false, 0.5, 0.5, 0.5}, {1, 6, true, 0.3, 0.2, 0.4}};
  system.projections = {{6, axis}};
  system.fixed = {0};
  system.finalize();
  Points f(8, Vec3<double>::Zero());
  system.compute_force(system.state.position, f);
  const MatrixFactors<double> factors{1.0, 0.0, -0.5};
  Eigen::MatrixXd a0 = Eigen::MatrixXd::Zero(24, 24);
  for (int i = 0; i < 8; ++i) a0.block<3, 3>(3 * i, 3 * i) = (i + 1.0) * Mat3<double>::Identity();
  a0 += -0.5 * Eigen::MatrixXd(system.force_fields[0]->stiffness_matrix());
  // P = Z Ppoints C2 C1, written densely.
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(24, 24);
  Eigen::MatrixXd c1 = identity, c2 = identity, points = identity, zero_fixed = identity;
  c1.block<3, 3>(12, 12).setZero();
  c2.block<3, 3>(3, 3) = 0.7 * Mat3<double>::Identity();
  c2.block<3, 3>(3, 18) = 0.3 * Mat3<double>::Identity();
  c2.block<3, 3>(18, 3) = 0.3 * Mat3<double>::Identity();
  c2.block<3, 3>(18, 18) = 0.7 * Mat3<double>::Identity();
  points.block<3, 3>(18, 18) = axis;
  zero_fixed.block<3, 3>(0, 0).setZero();
  const Eigen::MatrixXd p = zero_fixed * points * c2 * c1;
  const Eigen::MatrixXd expected = p * a0 * p + (identity - p);
  EXPECT_LT((Eigen::MatrixXd(system.assemble(factors)) - expected).cwiseAbs().maxCoeff(), 1e-12);

  Eigen::VectorXd dx(24);
  for (int i = 0; i < 24; ++i) dx[i] = 0.1 * i - 0.9;
  Points dxp(8), out(8);
  for (int i = 0; i < 8; ++i) dxp[static_cast<std::size_t>(i)] = dx.segment<3>(3 * i);
  system.multiply(factors, dxp, out);
  Eigen::VectorXd product(24);
  for (int i = 0; i < 8; ++i) product.segment<3>(3 * i) = out[static_cast<std::size_t>(i)];
  EXPECT_LT((product - p * a0 * dx).cwiseAbs().maxCoeff(), 1e-12);
  // No element joins the coupled points, so the diagonal blocks are exact.
  std::vector<Mat3<double>> blocks(8);
  system.diagonal_blocks(factors, blocks);
  for (int i = 0; i < 8; ++i) EXPECT_LT((blocks[static_cast<std::size_t>(i)] - expected.block<3, 3>(3 * i, 3 * i)).norm(), 1e-12) << i;
}

TEST(Projections, CouplingsPlaceTheSecondPointAndShareVelocities) {
  MechanicalSystem<double> system = make_pair_system();
  system.couplings = {{3, 4, false, 0.5, 0.5, 0.5}, {1, 6, true, 0.3, 0.2, 0.4}};
  for (std::size_t i = 0; i < 8; ++i) system.state.velocity.push_back(Vec3<double>(i, 1.0, -2.0 * i));
  system.finalize();
  const Points x = system.state.position, v = system.state.velocity;
  system.apply_placements();
  // SOFA: x2 -= (x2 - x1) positionFactor cf / 2, x1 stays; v1 += c (v2 - v1), v2 -= c (v2 - v1).
  EXPECT_LT((system.state.position[4] - (x[4] - 0.5 * (x[4] - x[3]))).norm(), 1e-15);
  EXPECT_EQ(system.state.position[3], x[3]);
  EXPECT_LT((system.state.velocity[3] - 0.5 * (v[3] + v[4])).norm(), 1e-15);
  EXPECT_LT((system.state.velocity[4] - 0.5 * (v[3] + v[4])).norm(), 1e-15);
  EXPECT_LT((system.state.position[6] - (x[6] - 0.2 * (x[6] - x[1]))).norm(), 1e-15);
  EXPECT_EQ(system.state.position[1], x[1]);
  EXPECT_LT((system.state.velocity[1] - (v[1] + 0.4 * (v[6] - v[1]))).norm(), 1e-15);
  EXPECT_LT((system.state.velocity[6] - (v[6] - 0.4 * (v[6] - v[1]))).norm(), 1e-15);
  EXPECT_EQ(system.state.velocity[5], v[5]);

  MechanicalSystem<double> bad = make_pair_system();
  bad.couplings = {{3, 8, false, 0.5, 0.5, 0.5}};
  EXPECT_THROW(bad.finalize(), Error);
}

TEST(Projections, BadEntriesAreRefused) {
  MechanicalSystem<double> system = make_system();
  system.projections = {{4, Mat3<double>::Identity()}};
  EXPECT_THROW(system.finalize(), Error);
  MechanicalSystem<double> other = make_system();
  other.placements = {{0, Mat3<double>::Identity() * std::numeric_limits<double>::quiet_NaN(), Vec3<double>::Zero(),
                       Mat3<double>::Identity()}};
  EXPECT_THROW(other.finalize(), Error);
}

}  // namespace
}  // namespace fastcorot
