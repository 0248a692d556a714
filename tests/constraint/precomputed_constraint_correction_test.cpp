// PrecomputedConstraintCorrection against dense linear algebra: C = h P A⁻¹ P with A the implicit
// step's matrix written column by column from the matrix-free product and inverted by Eigen's LU
// (SOFA's column: the velocity after one step from rest under a unit force, times
// positionIntegrationFactor / dt = 1); W = Hᵀ C H (1/dt in velocity order) with SOFA's
// regularisation once per point a row touches; the correction x += C Hᵀλ, v += C Hᵀλ / dt; the
// rotated variant R C Rᵀ; SOFA's cache file (name, raw row-major doubles) and its refusals.
#include "fastcorot/constraint/precomputed_constraint_correction.h"

#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/core/error.h"
#include "fastcorot/fem/node_rotations.h"
#include "fastcorot/sim/conjugate_gradient.h"

#include "support/solver_systems.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <string>

namespace fastcorot {
namespace {

using testing::grid_system;

constexpr double kDt = 0.05;

// The 4 × 3 × 3 grid fixed at x = 0 (perturbed, so not at rest), implicit Euler with Rayleigh
// damping, a CG linear solver (the precomputation does not go through it).
SimulatedObject<double> grid_object(bool tetrahedron_fem = false, const Mat3<double>& turn = Mat3<double>::Identity()) {
  SimulatedObject<double> object;
  object.path = "grid";
  object.system = grid_system(3, 0.1, turn, tetrahedron_fem);
  ImplicitEulerSolver<double>::Parameters p;
  p.rayleigh_mass = 0.1;
  p.rayleigh_stiffness = 0.1;
  object.ode_solver = std::make_unique<ImplicitEulerSolver<double>>(p);
  object.linear_solver = std::make_unique<ConjugateGradientSolver<double>>(ConjugateGradientSolver<double>::Parameters{});
  return object;
}

// P as a dense matrix: identity but on the fixed points.
Eigen::MatrixXd dense_projection(const MechanicalSystem<double>& system) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(3 * system.size(), 3 * system.size());
  for (Index i : system.fixed) p.block<3, 3>(3 * i, 3 * i).setZero();
  return p;
}

Eigen::MatrixXd expected_compliance(const SimulatedObject<double>& object) {
  const auto factors = object.ode_solver->integration_factors(kDt);
  const Eigen::MatrixXd a = testing::dense_system_matrix(object.system, factors->matrix);
  const Eigen::MatrixXd p = dense_projection(object.system);
  return kDt * p * a.lu().solve(p);
}

// Five rows of H on points of the grid; row 2 touches two free points, row 3 a free one and a fixed
// one (projected away). Fixed: 0, 4, ..., 32.
Eigen::SparseMatrix<double> rows_transposed(Index points) {
  std::vector<Eigen::Triplet<double>> t;
  const auto add = [&](int row, Index point, const Vec3<double>& c) {
    for (int k = 0; k < 3; ++k) t.emplace_back(3 * point + k, row, c[k]);
  };
  add(0, 35, Vec3<double>(1, 0, 0));
  add(1, 35, Vec3<double>(0, 0.6, 0.8));
  add(2, 21, Vec3<double>(-1, 0, 0));
  add(2, 23, Vec3<double>(1, 0, 0));
  add(3, 10, Vec3<double>(0.3, -0.4, 0.5));
  add(3, 0, Vec3<double>(1, 1, 1));
  add(4, 17, Vec3<double>(0, 0, 1));
  Eigen::SparseMatrix<double> ht(3 * points, 5);
  ht.setFromTriplets(t.begin(), t.end());
  return ht;
}

Eigen::MatrixXd block_rotations(const std::vector<Mat3<double>>& r) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(r.size()), 3 * static_cast<Eigen::Index>(r.size()));
  for (std::size_t i = 0; i < r.size(); ++i) out.block<3, 3>(3 * static_cast<Eigen::Index>(i), 3 * static_cast<Eigen::Index>(i)) = r[i];
  return out;
}

TEST(PrecomputedConstraintCorrection, ComplianceIsHTimesTheProjectedInverseOfA) {
  SimulatedObject<double> object = grid_object();
  const DenseMatrix<double> c = precompute_compliance(object, kDt);
  const Eigen::MatrixXd expected = expected_compliance(object);
  ASSERT_EQ(c.rows(), expected.rows());
  EXPECT_LT((Eigen::MatrixXd(c) - expected).norm(), 1e-11 * expected.norm());
  EXPECT_EQ((c.block<3, 3>(0, 0).norm()), 0.0) << "a fixed point neither moves nor answers";
  EXPECT_LT((Eigen::MatrixXd(c) - Eigen::MatrixXd(c).transpose()).norm(), 1e-12 * expected.norm());
  // Threads change nothing.
  object.system.set_threads(2);
  EXPECT_EQ(Eigen::MatrixXd(precompute_compliance(object, kDt)), Eigen::MatrixXd(c));
}

TEST(PrecomputedConstraintCorrection, WIsHtCHWithSofasRegularisation) {
  SimulatedObject<double> object = grid_object();
  auto c = std::make_shared<DenseMatrix<double>>(precompute_compliance(object, kDt));
  const Eigen::SparseMatrix<double> ht = projection_matrix(object.system) * rows_transposed(object.system.size());
  const Eigen::MatrixXd h = Eigen::MatrixXd(ht);
  const Eigen::MatrixXd expected = h.transpose() * Eigen::MatrixXd(*c) * h;
  PrecomputedConstraintCorrection<double> correction("test", 0, c, {PrecomputedConstraintCorrection<double>::Rotations::none, 0.25});
  DenseMatrix<double> w = DenseMatrix<double>::Zero(5, 5);
  correction.add_compliance(object, ht, ConstraintOrder::position_and_velocity, kDt, w);
  // SOFA adds the regularisation once per point of the row: row 2 touches two points; row 3's
  // fixed point was projected away.
  Eigen::MatrixXd regularised = expected;
  for (int r = 0; r < 5; ++r) regularised(r, r) += r == 2 ? 0.5 : 0.25;
  EXPECT_LT((Eigen::MatrixXd(w) - regularised).norm(), 1e-14 * regularised.norm());
  PrecomputedConstraintCorrection<double> plain("test", 0, c, {});
  DenseMatrix<double> wv = DenseMatrix<double>::Zero(5, 5);
  plain.add_compliance(object, ht, ConstraintOrder::velocity, kDt, wv);
  EXPECT_LT((Eigen::MatrixXd(wv) - expected / kDt).norm(), 1e-14 * expected.norm() / kDt);
  // W equals LinearSolverConstraintCorrection's h Hᵀ A⁻¹ H with the same A.
  const auto factors = object.ode_solver->integration_factors(kDt);
  const Eigen::MatrixXd a = testing::dense_system_matrix(object.system, factors->matrix);
  EXPECT_LT((expected - kDt * h.transpose() * a.lu().solve(h)).norm(), 1e-11 * expected.norm());
}

TEST(PrecomputedConstraintCorrection, CorrectsByCHtLambda) {
  SimulatedObject<double> object = grid_object();
  auto c = std::make_shared<DenseMatrix<double>>(precompute_compliance(object, kDt));
  object.system.state.velocity.assign(object.system.state.position.size(), Vec3<double>(0.1, -0.2, 0.3));
  const auto x_free = object.system.state.position;
  const auto v_free = object.system.state.velocity;
  const Eigen::SparseMatrix<double> ht = projection_matrix(object.system) * rows_transposed(object.system.size());
  Eigen::VectorXd lambda(5);
  lambda << 0.3, -0.2, 0.5, 0.1, -0.4;
  const Eigen::VectorXd impulse = ht * lambda;
  const Eigen::VectorXd dx = Eigen::MatrixXd(*c) * impulse;
  PrecomputedConstraintCorrection<double> correction("test", 0, c, {});
  correction.correct(object, testing::points_of(impulse), ConstraintOrder::position_and_velocity, kDt);
  EXPECT_LT((testing::flat_vector(object.system.state.position) - testing::flat_vector(x_free) - dx).norm(), 1e-15);
  EXPECT_LT((testing::flat_vector(object.system.state.velocity) - testing::flat_vector(v_free) - dx / kDt).norm(), 1e-13);
  // Velocity order: SOFA's applyVelocityCorrection leaves the positions.
  const auto x_then = object.system.state.position;
  correction.correct(object, testing::points_of(impulse), ConstraintOrder::velocity, kDt);
  EXPECT_EQ(object.system.state.position, x_then);
  EXPECT_LT((testing::flat_vector(object.system.state.velocity) - testing::flat_vector(v_free) - 2 * dx / kDt).norm(), 1e-12);
}

TEST(PrecomputedConstraintCorrection, RotationsTurnTheComplianceByThePointRotations) {
  const Mat3<double> turn = Eigen::AngleAxisd(0.7, Vec3<double>(0.2, 1, 0.4).normalized()).toRotationMatrix();
  SimulatedObject<double> object = grid_object(true, turn);
  SimulatedObject<double> unturned = grid_object(true);
  auto c = std::make_shared<DenseMatrix<double>>(precompute_compliance(unturned, kDt));
  const Eigen::MatrixXd r = block_rotations(node_rotations(*object.system.force_fields[0], object.system.size()));
  EXPECT_GT((r - Eigen::MatrixXd::Identity(r.rows(), r.cols())).norm(), 1.0) << "the points turned";
  const Eigen::SparseMatrix<double> ht = projection_matrix(object.system) * rows_transposed(object.system.size());
  const Eigen::MatrixXd h = Eigen::MatrixXd(ht);
  const Eigen::MatrixXd turned = r * Eigen::MatrixXd(*c) * r.transpose();
  using Rotations = PrecomputedConstraintCorrection<double>::Rotations;
  PrecomputedConstraintCorrection<double> correction("test", 0, c, {Rotations::both, 0});
  DenseMatrix<double> w = DenseMatrix<double>::Zero(5, 5);
  correction.add_compliance(object, ht, ConstraintOrder::position_and_velocity, kDt, w);
  const Eigen::MatrixXd expected = h.transpose() * turned * h;
  EXPECT_LT((Eigen::MatrixXd(w) - expected).norm(), 1e-13 * expected.norm());
  const auto x_free = object.system.state.position;
  Eigen::VectorXd lambda(5);
  lambda << 0.3, -0.2, 0.5, 0.1, -0.4;
  const Eigen::VectorXd impulse = ht * lambda;
  correction.correct(object, testing::points_of(impulse), ConstraintOrder::position_and_velocity, kDt);
  const Eigen::VectorXd dx = turned * impulse;
  EXPECT_LT((testing::flat_vector(object.system.state.position) - testing::flat_vector(x_free) - dx).norm(), 1e-14);
  // SOFA's LCP path: W unrotated (H C Hᵀ), the response turned, dx = R C Hᵀλ.
  SimulatedObject<double> lcp = grid_object(true, turn);
  PrecomputedConstraintCorrection<double> response("test", 0, c, {Rotations::response, 0});
  DenseMatrix<double> w_response = DenseMatrix<double>::Zero(5, 5);
  response.add_compliance(lcp, ht, ConstraintOrder::position_and_velocity, kDt, w_response);
  const Eigen::MatrixXd unrotated = h.transpose() * Eigen::MatrixXd(*c) * h;
  EXPECT_LT((Eigen::MatrixXd(w_response) - unrotated).norm(), 1e-13 * unrotated.norm());
  const auto lcp_free = lcp.system.state.position;
  response.correct(lcp, testing::points_of(impulse), ConstraintOrder::position_and_velocity, kDt);
  const Eigen::VectorXd turned_response = r * (Eigen::MatrixXd(*c) * impulse);
  EXPECT_LT((testing::flat_vector(lcp.system.state.position) - testing::flat_vector(lcp_free) - turned_response).norm(), 1e-14);
  // Without a rotation finder (FastTetrahedralCorotationalForceField), rotating is an error.
  SimulatedObject<double> fast = grid_object();
  PrecomputedConstraintCorrection<double> unfound("test", 0, c, {Rotations::both, 0});
  try {
    unfound.add_compliance(fast, ht, ConstraintOrder::position_and_velocity, kDt, w);
    FAIL() << "accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("rotations"), std::string::npos) << error.what();
  }
}

TEST(PrecomputedConstraintCorrection, CacheFileIsSofasRawRowMajorDoubles) {
  EXPECT_EQ(compliance_file_name("Torus", 300, 0.01), "Torus-300-0.01.comp");
  EXPECT_EQ(compliance_file_name("liver", 2718, 1e-5), "liver-2718-1e-05.comp");
  // A matrix that is not symmetric, to see the order.
  DenseMatrix<double> c(6, 6);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) c(i, j) = 1.0 / (1 + i) + 0.001 * j * j - 0.37 * i * j;
  }
  const auto file = std::filesystem::temp_directory_path() / ("fastcorot_precomputed_round_trip_" + std::to_string(::getpid()) + ".comp");
  write_compliance_file(file, c);
  ASSERT_EQ(std::filesystem::file_size(file), 36 * sizeof(double));
  std::ifstream in(file, std::ios::binary);
  std::vector<char> bytes(36 * sizeof(double));
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  double value = 0;
  std::memcpy(&value, bytes.data() + (1 * 6 + 4) * sizeof(double), sizeof(double));
  EXPECT_EQ(value, c(1, 4)) << "row 1, column 4: the 11th number";
  EXPECT_EQ(read_compliance_file<double>(file, 6), c);
  // Another size, or a truncated file: refused, naming the file.
  for (std::size_t rows : {3, 9}) {
    try {
      read_compliance_file<double>(file, rows);
      FAIL() << "accepted " << rows;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
    }
  }
  std::filesystem::resize_file(file, 35 * sizeof(double));
  EXPECT_THROW(read_compliance_file<double>(file, 6), Error);
  std::filesystem::remove(file);
  EXPECT_THROW(read_compliance_file<double>(file, 6), Error);
}

TEST(PrecomputedConstraintCorrection, RefusesADenseComplianceTooBig) {
  EXPECT_NO_THROW(check_precomputed_compliance_size("here", 7000));  // 3.3 GiB
  try {
    check_precomputed_compliance_size("here", 100000);
    FAIL() << "accepted";
  } catch (const Error& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("here"), std::string::npos) << what;
    EXPECT_NE(what.find("670.5"), std::string::npos) << what;  // 300000² doubles = 670.55 GiB
  }
  const auto c = std::make_shared<DenseMatrix<double>>(DenseMatrix<double>::Identity(5, 5));
  EXPECT_THROW(PrecomputedConstraintCorrection<double>("test", 0, c, {}), Error) << "not 3 rows per point";
}

}  // namespace
}  // namespace fastcorot
