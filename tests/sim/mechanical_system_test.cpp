// MechanicalSystem: the operations of SOFA's mechanical visitors (docs/sofa-solvers.md, notation
// and §2.2; docs/sofa-components.md §4 FixedProjectiveConstraint, §6 ConstantForceField).
// References are built independently in each test: a second force field with the same parameters,
// hand-written masses, dense Eigen matrices.
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/mechanical_system.h"

#include "fastcorot/core/error.h"
#include "support/deformations.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

using Field = CorotationalForceField<double>;
using Points = std::vector<Vec3<double>>;
using testing::flatten;
using testing::relative_error;

// Two tetrahedra sharing the face (0, 1, 2); |V_A| = 1/6, |V_B| = 1/3 (see mass_test.cpp).
std::shared_ptr<TetMesh> two_tets_mesh() {
  return std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{{0, 1, 2, 3}, {0, 2, 1, 4}});
}
Points two_tets_rest() {
  return {Vec3<double>(0, 0, 0), Vec3<double>(1, 0, 0), Vec3<double>(0, 1, 0), Vec3<double>(0, 0, 1),
          Vec3<double>(0, 0, -2)};
}
// Lumped masses at density 6, by hand: A gives 1/4 to 0,1,2,3; B gives 1/2 to 0,1,2,4.
const std::vector<double> kMasses = {0.75, 0.75, 0.75, 0.25, 0.5};

Field::Parameters field_parameters(RotationMethod method = RotationMethod::qr, double rayleigh = 0) {
  Field::Parameters p;
  p.young_modulus = {1000.0};
  p.poisson_ratio = {0.3};
  p.method = method;
  p.rayleigh_stiffness = rayleigh;
  return p;
}

Points deformed(const Points& rest, unsigned seed, double amplitude = 0.08) {
  std::mt19937 rng(seed);
  return testing::perturbed(rest, amplitude, rng);
}

Eigen::MatrixXd expand(const Eigen::MatrixXd& m) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3 * m.rows(), 3 * m.cols());
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.block<3, 3>(3 * i, 3 * j) = m(i, j) * Eigen::Matrix3d::Identity();
  }
  return out;
}

Eigen::MatrixXd lumped_dense() {
  return expand(Eigen::VectorXd::Map(kMasses.data(), 5).asDiagonal().toDenseMatrix());
}

// The system of the tests: two tetrahedra, lumped masses, gravity, two constant-force components
// (vertex 4 appears in both: the forces add), points 3 and 1 fixed (given unsorted and repeated).
MechanicalSystem<double> make_system(const Field::Parameters& parameters, const Points& x) {
  MechanicalSystem<double> system;
  const auto rest = two_tets_rest();
  system.state.position = x;
  system.state.rest_position = rest;
  system.force_fields.push_back(std::make_shared<Field>(two_tets_mesh(), rest, parameters));
  system.mass = Mass<double>::lumped(kMasses);
  system.gravity = Vec3<double>(0, -9.81, 0.5);
  system.constant_forces.push_back({{4, 1}, {Vec3<double>(1, 2, 3), Vec3<double>(-0.5, 0, 0.25)}});
  system.constant_forces.push_back({{4}, {Vec3<double>(0, 0, -10)}});
  system.fixed = {3, 1, 3};
  system.finalize();
  return system;
}

// P = identity with the rows of fixed points zeroed.
Eigen::MatrixXd projector(const std::vector<Index>& fixed, Index n) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(3 * n, 3 * n);
  for (Index i : fixed) p.block<3, 3>(3 * i, 3 * i).setZero();
  return p;
}

TEST(MechanicalSystem, FinalizeSortsFixedAndFillsVelocityAndRest) {
  MechanicalSystem<double> system;
  system.state.position = two_tets_rest();
  system.fixed = {4, 0, 4, 2, 0};
  system.finalize();
  EXPECT_EQ(system.fixed, (std::vector<Index>{0, 2, 4}));
  ASSERT_EQ(system.state.velocity.size(), 5u);
  for (const auto& v : system.state.velocity) EXPECT_EQ(v, Vec3<double>::Zero());
  EXPECT_EQ(system.state.rest_position, system.state.position);
  EXPECT_EQ(system.size(), 5);
}

TEST(MechanicalSystem, FinalizeRejectsOutOfRangeIndicesByValue) {
  const auto expect_error = [](MechanicalSystem<double> system, const std::string& needle) {
    try {
      system.finalize();
      ADD_FAILURE() << "no error, expected one naming " << needle;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
    }
  };
  MechanicalSystem<double> base;
  base.state.position = two_tets_rest();

  auto fixed_high = base;
  fixed_high.fixed = {0, 5};
  expect_error(fixed_high, "fixed point index 5");
  auto fixed_negative = base;
  fixed_negative.fixed = {-1};
  expect_error(fixed_negative, "fixed point index -1");

  auto zero_velocity_high = base;
  zero_velocity_high.zero_velocity = {5};
  expect_error(zero_velocity_high, "index 5");

  auto constant_high = base;
  constant_high.constant_forces.push_back({{2, 7}, {Vec3<double>::Zero(), Vec3<double>::Zero()}});
  expect_error(constant_high, "constant force index 7");

  auto constant_count = base;
  constant_count.constant_forces.push_back({{1, 2}, {Vec3<double>::Zero()}});
  expect_error(constant_count, "2 indices");

  auto mass_size = base;
  mass_size.mass = Mass<double>::lumped({1.0, 1.0});
  expect_error(mass_size, "mass");

  auto velocity_size = base;
  velocity_size.state.velocity.assign(3, Vec3<double>::Zero());
  expect_error(velocity_size, "velocit");
}

TEST(MechanicalSystem, ComputeForceIsFieldsPlusWeightPlusConstantForcesAndOverwrites) {
  const auto parameters = field_parameters();
  const Points x = deformed(two_tets_rest(), 1);
  auto system = make_system(parameters, x);
  Points f(5, Vec3<double>(123, -456, 789));  // garbage: compute_force overwrites
  system.compute_force(x, f);

  Field reference(two_tets_mesh(), two_tets_rest(), parameters);
  Points expected(5, Vec3<double>::Zero());
  reference.add_force(x, expected);
  for (std::size_t i = 0; i < 5; ++i) expected[i] += kMasses[i] * Vec3<double>(0, -9.81, 0.5);
  expected[4] += Vec3<double>(1, 2, 3) + Vec3<double>(0, 0, -10);
  expected[1] += Vec3<double>(-0.5, 0, 0.25);
  EXPECT_LT(relative_error(flatten(f), flatten(expected)), 1e-14);
  // The total force is not projected (docs/sofa-solvers.md §1.2 step 1): fixed point 3 keeps its force.
  EXPECT_GT(f[3].norm(), 1.0);
  // Fields are linearised at x: the stiffness equals the reference's.
  EXPECT_LT(relative_error(Eigen::MatrixXd(system.force_fields[0]->stiffness_matrix()),
                           Eigen::MatrixXd(reference.stiffness_matrix())),
            1e-14);
}

TEST(MechanicalSystem, ComputeForceAtRestIsTheExternalLoadOnly) {
  // At x = rest the elastic force vanishes: f_i = m_i g (+ constants).
  const auto rest = two_tets_rest();
  auto system = make_system(field_parameters(), rest);
  Points f(5);
  system.compute_force(rest, f);
  EXPECT_LT((f[0] - 0.75 * Vec3<double>(0, -9.81, 0.5)).norm(), 1e-12);
  EXPECT_LT((f[4] - (0.5 * Vec3<double>(0, -9.81, 0.5) + Vec3<double>(1, 2, -7))).norm(), 1e-12);
}

TEST(MechanicalSystem, MultiplyIsMassPlusStiffnessProjected) {
  // out = P (m M + (k + b·ff.rs) K) dx: the field's own Rayleigh coefficient scales K through b
  // (docs/sofa-solvers.md §1.4 / §2.2). Here k + b·rs = -0.3 + (-0.7)(0.4) = -0.58.
  const auto parameters = field_parameters(RotationMethod::qr, 0.4);
  const Points x = deformed(two_tets_rest(), 2);
  auto system = make_system(parameters, x);
  Points f(5);
  system.compute_force(x, f);
  Field reference(two_tets_mesh(), two_tets_rest(), parameters);
  Points scratch(5, Vec3<double>::Zero());
  reference.add_force(x, scratch);
  const Eigen::MatrixXd k(reference.stiffness_matrix(1.0));

  const Points dx = deformed(Points(5, Vec3<double>::Zero()), 3, 1.0);
  Points out(5, Vec3<double>(7, 7, 7));  // garbage: multiply overwrites
  system.multiply({2.0, -0.7, -0.3}, dx, out);
  const Eigen::VectorXd expected = projector(system.fixed, 5) * (2.0 * lumped_dense() - 0.58 * k) * flatten(dx);
  EXPECT_LT(relative_error(flatten(out), expected), 1e-13);
  EXPECT_EQ(out[1], Vec3<double>::Zero());
  EXPECT_EQ(out[3], Vec3<double>::Zero());

  // m = 0 leaves the mass out; k = b = 0 leaves only the mass.
  system.multiply({0.0, 0.0, 1.0}, dx, out);
  EXPECT_LT(relative_error(flatten(out), projector(system.fixed, 5) * k * flatten(dx)), 1e-13);
  system.multiply({1.5, 0.0, 0.0}, dx, out);
  EXPECT_LT(relative_error(flatten(out), projector(system.fixed, 5) * 1.5 * lumped_dense() * flatten(dx)), 1e-15);
}

TEST(MechanicalSystem, MultiplyWithoutMassComponent) {
  auto system = make_system(field_parameters(), two_tets_rest());
  system.mass = Mass<double>();
  const Points dx = deformed(Points(5, Vec3<double>::Zero()), 4, 1.0);
  Points out(5);
  system.multiply({1.0, 0.0, 0.0}, dx, out);  // no mass, no stiffness factor: zero
  EXPECT_EQ(flatten(out).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(system.kinetic_energy(), 0.0);
}

void expect_assembly_matches_multiply(MechanicalSystem<double>& system, const MatrixFactors<double>& factors) {
  const Eigen::MatrixXd assembled(system.assemble(factors));
  const Index n = system.size();
  ASSERT_EQ(assembled.rows(), 3 * n);
  ASSERT_EQ(assembled.cols(), 3 * n);
  std::vector<bool> is_fixed(static_cast<std::size_t>(n), false);
  for (Index i : system.fixed) is_fixed[static_cast<std::size_t>(i)] = true;
  const double scale = assembled.cwiseAbs().maxCoeff();
  // The diagonal blocks alone (for block-Jacobi preconditioning) are the assembled ones (up to the
  // order in which the assembly sums the mass and stiffness terms).
  std::vector<Mat3<double>> blocks(static_cast<std::size_t>(n));
  system.diagonal_blocks(factors, blocks);
  for (Index i = 0; i < n; ++i) {
    const Mat3<double> expected = assembled.block<3, 3>(3 * i, 3 * i);
    EXPECT_LT((blocks[static_cast<std::size_t>(i)] - expected).cwiseAbs().maxCoeff(), 1e-14 * scale) << "point " << i;
  }
  for (Index j = 0; j < 3 * n; ++j) {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(3 * n);
    unit[j] = 1;
    const Points e = testing::unflatten(unit);
    Points column(static_cast<std::size_t>(n));
    system.multiply(factors, e, column);
    if (is_fixed[static_cast<std::size_t>(j / 3)]) {
      // Fixed: column cleared, 1 on the diagonal (docs/sofa-components.md §4, docs/sofa-solvers.md §4.1).
      EXPECT_EQ((assembled.col(j) - unit).cwiseAbs().maxCoeff(), 0.0) << "column " << j;
    } else {
      EXPECT_LT((assembled.col(j) - flatten(column)).cwiseAbs().maxCoeff(), 1e-13 * scale) << "column " << j;
    }
  }
  // Fixed rows: zero apart from the diagonal.
  for (Index i : system.fixed) {
    for (Index c = 0; c < 3; ++c) {
      Eigen::VectorXd unit = Eigen::VectorXd::Zero(3 * n);
      unit[3 * i + c] = 1;
      EXPECT_EQ((assembled.row(3 * i + c).transpose() - unit).cwiseAbs().maxCoeff(), 0.0);
    }
  }
  EXPECT_LT((assembled - assembled.transpose()).cwiseAbs().maxCoeff(), 1e-13 * scale);
}

TEST(MechanicalSystem, AssembleEqualsMultiplyColumnByColumn) {
  const auto parameters = field_parameters(RotationMethod::qr, 0.25);
  const Points x = deformed(two_tets_rest(), 5);
  auto system = make_system(parameters, x);
  Points f(5);
  system.compute_force(x, f);
  // Implicit Euler's factors for h = 0.01, rs = rm = 0.1 (docs/sofa-solvers.md §1.2 step 3).
  expect_assembly_matches_multiply(system, {1.001, -0.01, -0.01 * 0.11});
  expect_assembly_matches_multiply(system, {0.0, 0.0, -1.0});

  // A consistent mass and a different fixed set.
  system.mass = Mass<double>::consistent(tetrahedral_mass_matrix<double>(system.force_fields[0]->mesh(),
                                                                         two_tets_rest(), 6.0));
  system.fixed = {0};
  system.finalize();
  expect_assembly_matches_multiply(system, {2.0, -0.5, -0.3});
}

TEST(MechanicalSystem, ProjectZeroesOnlyFixedEntries) {
  auto system = make_system(field_parameters(), two_tets_rest());
  Points v = {Vec3<double>(1, 2, 3), Vec3<double>(4, 5, 6), Vec3<double>(7, 8, 9), Vec3<double>(1, 1, 1),
              Vec3<double>(2, 2, 2)};
  system.project(v);
  EXPECT_EQ(v[0], Vec3<double>(1, 2, 3));
  EXPECT_EQ(v[1], Vec3<double>::Zero());
  EXPECT_EQ(v[2], Vec3<double>(7, 8, 9));
  EXPECT_EQ(v[3], Vec3<double>::Zero());
  EXPECT_EQ(v[4], Vec3<double>(2, 2, 2));
}

TEST(MechanicalSystem, PotentialEnergyOfGravityAndConstantForcesByHand) {
  MechanicalSystem<double> system;
  system.state.position = two_tets_rest();
  system.mass = Mass<double>::lumped(kMasses);
  system.gravity = Vec3<double>(0, -10, 0);
  system.constant_forces.push_back({{1}, {Vec3<double>(1, 2, 3)}});
  system.finalize();
  // -Σ m_i g·x_i: only vertex 2 has y ≠ 0 (y = 1): -(0.75 · (-10) · 1) = 7.5.
  // -f·x_1 = -(1, 2, 3)·(1, 0, 0) = -1.  Total 6.5.
  EXPECT_DOUBLE_EQ(system.potential_energy(system.state.position), 6.5);
}

TEST(MechanicalSystem, PotentialEnergyIsElasticPlusExternalAndItsGradientIsMinusForce) {
  // With method `none` the elastic energy's gradient is exactly -f (corotational_force_field.h).
  const auto parameters = field_parameters(RotationMethod::none);
  const Points x = deformed(two_tets_rest(), 6);
  auto system = make_system(parameters, x);
  Field reference(two_tets_mesh(), two_tets_rest(), parameters);
  double expected = reference.potential_energy(x);
  for (std::size_t i = 0; i < 5; ++i) expected -= kMasses[i] * Vec3<double>(0, -9.81, 0.5).dot(x[i]);
  expected -= Vec3<double>(1, 2, 3).dot(x[4]) + Vec3<double>(-0.5, 0, 0.25).dot(x[1]) +
              Vec3<double>(0, 0, -10).dot(x[4]);
  EXPECT_NEAR(system.potential_energy(x), expected, 1e-12 * std::abs(expected));

  const Eigen::VectorXd gradient = testing::fd_gradient(
      [&](const Eigen::VectorXd& flat) { return system.potential_energy(testing::unflatten(flat)); }, flatten(x),
      1e-6);
  Points f(5);
  system.compute_force(x, f);
  EXPECT_LT(relative_error(-gradient, flatten(f)), 1e-7);
}

TEST(MechanicalSystem, KineticEnergyUsesTheStateVelocity) {
  auto system = make_system(field_parameters(), two_tets_rest());
  system.state.velocity[4] = Vec3<double>(0, 2, 0);
  system.state.velocity[0] = Vec3<double>(1, 0, 0);
  // 1/2 (0.5 · 4 + 0.75 · 1) = 1.375.
  EXPECT_DOUBLE_EQ(system.kinetic_energy(), 1.375);
}

}  // namespace
}  // namespace fastcorot
