// SSORPreconditioner: SOFA's SSORPreconditioner (SSORPreconditioner.inl / .cpp, SOFA 2a278d891f).
// Reference: the explicit matrix P = (2 - w) (D/w + L)^-1 (D/w) (D/w + U)^-1 of the dense system
// matrix (taken column by column from the matrix-free product), and Eigen's dense solve for PCG.
#include "fastcorot/sim/ssor_preconditioner.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/preconditioned_conjugate_gradient.h"
#include "support/random_rhs.h"
#include "support/solver_systems.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace fastcorot {
namespace {

using Points = std::vector<Vec3<double>>;
using SSOR = SSORPreconditioner<double>;
using testing::dense_system_matrix;
using testing::flat_vector;

SSOR::Parameters omega(double w, bool scaled = true) {
  SSOR::Parameters p;
  p.omega = w;
  p.scale_by_two_minus_omega = scaled;
  return p;
}

// The explicit SSOR matrix of `a`.
Eigen::MatrixXd explicit_ssor(const Eigen::MatrixXd& a, double w, bool scaled) {
  const Eigen::MatrixXd d = a.diagonal().asDiagonal();
  const Eigen::MatrixXd lower = a.triangularView<Eigen::StrictlyLower>();
  const Eigen::MatrixXd upper = a.triangularView<Eigen::StrictlyUpper>();
  const Eigen::MatrixXd p = (d / w + lower).inverse() * (d / w) * (d / w + upper).inverse();
  return scaled ? Eigen::MatrixXd((2 - w) * p) : p;
}

TEST(SSORPreconditioner, DefaultOmegaIsSofasAndBadOmegaIsRefused) {
  EXPECT_EQ(SSOR::Parameters{}.omega, 1.0);
  for (double w : {0.0, 2.0, -0.5, 2.5, std::nan("")}) {
    try {
      SSOR solver(omega(w));
      ADD_FAILURE() << "accepted omega " << w;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("omega"), std::string::npos) << error.what();
    }
  }
}

TEST(SSORPreconditioner, ApplicationIsTheExplicitSsorMatrix) {
  auto system = testing::grid_system(3);
  const Eigen::MatrixXd a = dense_system_matrix(system, testing::kEulerFactors);
  const Eigen::VectorXd r = flat_vector(testing::projected_rhs(system, 4));
  for (double w : {1.0, 0.7, 1.3}) {
    for (bool scaled : {true, false}) {
      SSOR solver(omega(w, scaled));
      solver.build(system, testing::kEulerFactors);
      Eigen::VectorXd z(r.size());
      solver.apply(r.data(), z.data(), static_cast<Index>(r.size()));
      const Eigen::VectorXd expected = explicit_ssor(a, w, scaled) * r;
      EXPECT_LT((z - expected).norm() / expected.norm(), 1e-12) << "omega " << w << (scaled ? "" : " block form");
    }
  }
  SSOR solver(omega(1.0));
  solver.build(system, testing::kEulerFactors);
  Eigen::VectorXd z(r.size());
  EXPECT_THROW(solver.apply(r.data(), z.data(), 3), Error);
}

TEST(SSORPreconditioner, PreconditionsPcgToTheDenseSolution) {
  auto system = testing::grid_system(6);
  const Points b = testing::projected_rhs(system, 7);
  const Eigen::VectorXd exact = dense_system_matrix(system, testing::kEulerFactors).ldlt().solve(flat_vector(b));
  using PCG = PreconditionedConjugateGradientSolver<double>;
  int iterations[2] = {};
  for (int with_ssor = 0; with_ssor < 2; ++with_ssor) {
    PCG::Parameters p;
    p.iterations = 500;
    p.tolerance = 1e-26;
    p.preconditioner = with_ssor ? Preconditioner::solver : Preconditioner::none;
    if (with_ssor) p.solver = std::make_shared<SSOR>(omega(1.2));
    PCG solver(p, system.size());
    Points x(static_cast<std::size_t>(system.size()));
    iterations[with_ssor] = solver.solve(system, testing::kEulerFactors, b, x).iterations;
    EXPECT_LT((flat_vector(x) - exact).norm() / exact.norm(), 1e-10);
  }
  EXPECT_LT(iterations[1], iterations[0]);
}

TEST(SSORPreconditioner, CarriedMatrixRestoresTheSameApplication) {
  auto system = testing::grid_system(2);
  SSOR built(omega(1.5)), restored(omega(1.5));
  built.build(system, testing::kEulerFactors);
  restored.restore_carried_state(built.carried_state());
  const Eigen::VectorXd r = flat_vector(testing::projected_rhs(system, 1));
  Eigen::VectorXd z1(r.size()), z2(r.size());
  built.apply(r.data(), z1.data(), static_cast<Index>(r.size()));
  restored.apply(r.data(), z2.data(), static_cast<Index>(r.size()));
  EXPECT_EQ(z1, z2);
  const std::vector<std::int64_t> bad = {6, 5};
  EXPECT_THROW(restored.restore_carried_state(bad), Error);
}

}  // namespace
}  // namespace fastcorot
