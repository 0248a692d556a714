// EulerExplicitSolver, RungeKutta4Solver and NewmarkImplicitSolver (SOFA's schemes, as
// include/fastcorot/sim/explicit_solvers.h and newmark_solver.h write them), each step compared
// with the scheme written out here on dense matrices built independently of MechanicalSystem: the
// forces of a separate spring force field, and the masses by hand.
#include "fastcorot/sim/explicit_solvers.h"
#include "fastcorot/sim/newmark_solver.h"
#include "fastcorot/sim/variational_symplectic_solver.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/spring_force_field.h"
#include "fastcorot/sim/sparse_direct_solver.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;

std::shared_ptr<TetMesh> two_tets() {
  return std::make_shared<TetMesh>(5, std::vector<Tetrahedron>{{0, 1, 2, 3}, {0, 2, 1, 4}});
}
Points rest() { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -2}}; }
const std::vector<double> kMasses = {0.75, 0.75, 0.75, 0.25, 0.5};
const Vec3<double> kGravity(0.3, -9.81, 0.1);

std::vector<Spring<double>> springs() {
  MeshSpringParameters<double> p;
  p.tetrahedra_stiffness = 50;
  p.tetrahedra_damping = 0.5;
  return mesh_springs<double>(*two_tets(), rest(), p);
}

Points start_positions() { return {{0, 0, 0}, {1.1, 0.05, 0}, {0, 0.9, 0.1}, {0.05, 0, 1.1}, {0.1, 0, -1.9}}; }
Points start_velocities() { return {{0, 0, 0}, {0.2, 0, -0.1}, {0, 0.3, 0}, {0.1, 0.1, 0.1}, {-0.2, 0, 0}}; }

MechanicalSystem<double> make_system(bool consistent) {
  MechanicalSystem<double> system;
  system.state.position = start_positions();
  system.state.velocity = start_velocities();
  system.state.rest_position = rest();
  system.force_fields.push_back(std::make_shared<SpringForceField<double>>(two_tets(), springs()));
  if (consistent) {
    Eigen::SparseMatrix<double> m(5, 5);
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < 5; ++i) t.emplace_back(i, i, kMasses[static_cast<std::size_t>(i)]);
    t.emplace_back(1, 2, 0.1);
    t.emplace_back(2, 1, 0.1);
    m.setFromTriplets(t.begin(), t.end());
    system.mass = Mass<double>::consistent(m);
  } else {
    system.mass = Mass<double>::lumped(kMasses);
  }
  system.gravity = kGravity;
  system.fixed = {0};
  system.finalize();
  return system;
}

// The dense model: f(x, v) from an independent spring field, M, and the projection P (point 0 fixed).
struct Dense {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(15, 15);
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(15, 15);
  explicit Dense(bool consistent) {
    for (int i = 0; i < 5; ++i) m.block<3, 3>(3 * i, 3 * i) = kMasses[static_cast<std::size_t>(i)] * Mat3<double>::Identity();
    if (consistent) {
      m.block<3, 3>(3, 6) = 0.1 * Mat3<double>::Identity();
      m.block<3, 3>(6, 3) = 0.1 * Mat3<double>::Identity();
    }
    p.block<3, 3>(0, 0).setZero();
  }
  Eigen::VectorXd force(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::MatrixXd* k = nullptr) const {
    SpringForceField<double> field(two_tets(), springs());
    Points xp(5), vp(5), f(5, Vec3<double>::Zero());
    for (int i = 0; i < 5; ++i) {
      xp[static_cast<std::size_t>(i)] = x.segment<3>(3 * i);
      vp[static_cast<std::size_t>(i)] = v.segment<3>(3 * i);
    }
    field.set_velocity(vp);
    field.add_force(xp, f);
    if (k) *k = Eigen::MatrixXd(field.stiffness_matrix());
    Eigen::VectorXd out(15);
    for (int i = 0; i < 5; ++i) out.segment<3>(3 * i) = f[static_cast<std::size_t>(i)];
    Eigen::VectorXd g(15);
    for (int i = 0; i < 5; ++i) g.segment<3>(3 * i) = kGravity;
    return out + m * g;
  }
  // a = M^-1 P f on the free points.
  Eigen::VectorXd acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const {
    const Eigen::VectorXd f = p * force(x, v);
    const Eigen::MatrixXd a = p * m * p + (Eigen::MatrixXd::Identity(15, 15) - p);
    return p * a.fullPivLu().solve(f);
  }
};

Eigen::VectorXd flat(const Points& points) {
  Eigen::VectorXd v(15);
  for (int i = 0; i < 5; ++i) v.segment<3>(3 * i) = points[static_cast<std::size_t>(i)];
  return v;
}

void expect_close(const Points& actual, const Eigen::VectorXd& expected, double tolerance) {
  EXPECT_LT((flat(actual) - expected).cwiseAbs().maxCoeff(), tolerance * std::max(1.0, expected.cwiseAbs().maxCoeff()));
}

class Explicit : public ::testing::TestWithParam<bool> {};

TEST_P(Explicit, EulerStepsAsTheSchemeSays) {
  const bool consistent = GetParam();
  const Dense dense(consistent);
  const double h = 1e-3;
  for (bool symplectic : {true, false}) {
    MechanicalSystem<double> system = make_system(consistent);
    SparseDirectSolver<double> solver;
    ExplicitEulerSolver<double> euler(symplectic);
    Eigen::VectorXd x = flat(start_positions()), v = flat(start_velocities());
    for (int step = 0; step < 3; ++step) {
      const StepReport report = euler.step(system, solver, h);
      EXPECT_EQ(report.linear_solves, consistent ? 1 : 0);
      const Eigen::VectorXd a = dense.acceleration(x, v);
      if (symplectic) {
        v += h * a;
        x += h * v;
      } else {
        x += h * v;
        v += h * a;
      }
    }
    expect_close(system.state.position, x, 1e-12);
    expect_close(system.state.velocity, v, 1e-12);
  }
}

TEST_P(Explicit, RungeKutta4StepsAsTheSchemeSays) {
  const bool consistent = GetParam();
  const Dense dense(consistent);
  const double h = 2e-3;
  MechanicalSystem<double> system = make_system(consistent);
  SparseDirectSolver<double> solver;
  RungeKutta4Solver<double> rk4;
  Eigen::VectorXd x = flat(start_positions()), v = flat(start_velocities());
  for (int step = 0; step < 3; ++step) {
    rk4.step(system, solver, h);
    const Eigen::VectorXd k1v = v, k1a = dense.acceleration(x, v);
    const Eigen::VectorXd k2v = v + h / 2 * k1a, k2a = dense.acceleration(x + h / 2 * k1v, k2v);
    const Eigen::VectorXd k3v = v + h / 2 * k2a, k3a = dense.acceleration(x + h / 2 * k2v, k3v);
    const Eigen::VectorXd k4v = v + h * k3a, k4a = dense.acceleration(x + h * k3v, k4v);
    x += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    v += h / 6 * (k1a + 2 * k2a + 2 * k3a + k4a);
  }
  expect_close(system.state.position, x, 1e-12);
  expect_close(system.state.velocity, v, 1e-12);
}

TEST_P(Explicit, NewmarkStepsAsSofaWritesIt) {
  const bool consistent = GetParam();
  const Dense dense(consistent);
  const double h = 0.01, g = 0.6, beta = 0.3, rm = 0.2, rk = 0.05;
  MechanicalSystem<double> system = make_system(consistent);
  SparseDirectSolver<double> solver;
  NewmarkSolver<double> newmark({rk, rm, 0.0, g, beta}, 5);
  Eigen::VectorXd x = flat(start_positions()), v = flat(start_velocities());
  Eigen::VectorXd a = dense.acceleration(x, v);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(15, 15);
  for (int step = 0; step < 3; ++step) {
    newmark.step(system, solver, h);
    Eigen::MatrixXd k;
    const Eigen::VectorXd f = dense.force(x, v, &k);
    Eigen::VectorXd b = f + (h * (1 - g) * rk + h * h * (1 - 2 * beta) / 2) * k * a - h * (1 - g) * rm * dense.m * a +
                        (rk + h) * k * v - rm * dense.m * v;
    b = dense.p * b;
    const Eigen::MatrixXd system_matrix = (1 + h * g * rm) * dense.m - (h * h * beta + h * rk * g) * k;
    const Eigen::VectorXd next =
        dense.p * (dense.p * system_matrix * dense.p + (identity - dense.p)).fullPivLu().solve(b);
    x += h * v + h * h * (0.5 - beta) * a + h * h * beta * next;
    v += h * (1 - g) * a + h * g * next;
    a = next;
  }
  expect_close(system.state.position, x, 1e-11);
  expect_close(system.state.velocity, v, 1e-11);
  // What it carries is a_t: a solver restored from it continues the same.
  NewmarkSolver<double> resumed({rk, rm, 0.0, g, beta}, 5);
  resumed.restore_carried_state(newmark.carried_state());
  MechanicalSystem<double> copy = make_system(consistent);
  copy.state = system.state;
  newmark.step(system, solver, h);
  resumed.step(copy, solver, h);
  EXPECT_EQ(flat(system.state.position), flat(copy.state.position));
  EXPECT_THROW(resumed.restore_carried_state({1, 2}), Error);
}

TEST_P(Explicit, VariationalSymplecticStepsAsSofaWritesIt) {
  const bool consistent = GetParam();
  const Dense dense(consistent);
  const double h = 0.01, rm = 0.1, rk = 0.02;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(15, 15);
  for (bool explicit_form : {false, true}) {
    MechanicalSystem<double> system = make_system(consistent);
    SparseDirectSolver<double> solver;
    VariationalSymplecticSolver<double> variational({1e-12, 4, rk, rm, explicit_form}, 5);
    Eigen::VectorXd x = flat(start_positions()), v = flat(start_velocities());
    Eigen::VectorXd p = dense.m * v;
    const auto solve = [&](const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
      return Eigen::VectorXd(dense.p * (dense.p * a * dense.p + (identity - dense.p)).fullPivLu().solve(dense.p * b));
    };
    for (int step = 0; step < 3; ++step) {
      variational.step(system, solver, h);
      if (explicit_form) {
        const Eigen::VectorXd a = dense.p * (solve(dense.m, dense.force(x, v) + p / h) - rm * v);
        v = h * a;
        x += h * v;
        p = dense.m * v;
        continue;
      }
      const Eigen::VectorXd x0 = x;
      Eigen::VectorXd r = Eigen::VectorXd::Zero(15), previous = x0;
      double error = 0;
      for (int i = 0; (i < 4 && error > 1e-12) || i == 0; ++i) {
        Eigen::MatrixXd k;
        const Eigen::VectorXd f = dense.force(x0 + r, v, &k);
        const Eigen::MatrixXd a = (4 / (h * h) + 4 * rm / h) * dense.m - (1 + 4 * rk / h) * k;
        r = solve(a, f + (2 / h) * p - k * r);
        error = (x0 + r - previous).norm() / x0.norm();
        previous = x0 + r;
      }
      v = (2 / h) * r;
      p = (h / 2) * dense.p * dense.force(x0 + (h / 2) * v, v) + dense.m * v;
      x = x0 + h * v;
    }
    expect_close(system.state.position, x, 1e-11);
    expect_close(system.state.velocity, v, 1e-11);
    EXPECT_EQ(variational.carried_state().size(), 16u);
  }
}

INSTANTIATE_TEST_SUITE_P(Masses, Explicit, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Consistent" : "Lumped"; });

TEST(Explicit, NoMassIsRefused) {
  MechanicalSystem<double> system;
  system.state.position = rest();
  system.finalize();
  SparseDirectSolver<double> solver;
  ExplicitEulerSolver<double> euler(true);
  EXPECT_THROW(euler.step(system, solver, 0.01), Error);
  EXPECT_THROW(NewmarkSolver<double>({-1.0, 0.0, 0.0, 0.5, 0.25}, 5), Error);
}

}  // namespace
}  // namespace fastcorot
