#include "fastcorot/sim/explicit_solvers.h"

#include "fastcorot/core/error.h"

#include <Eigen/Cholesky>

namespace fastcorot {

template <class Real>
StepReport explicit_acceleration(MechanicalSystem<Real>& system, LinearSolver<Real>& solver,
                                 std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v,
                                 std::vector<Vec3<Real>>& force, std::span<Vec3<Real>> acceleration) {
  if (system.mass.size() == 0) throw make_error("an explicit solver needs a mass: the object has none");
  force.resize(static_cast<std::size_t>(system.size()));
  system.compute_force(x, force, v);
  StepReport report;
  if (system.mass.is_block_diagonal()) {
    // SOFA's accFromF of a rigid mass: the linear part divided by m, the angular part times the
    // inverse of m·inertia (a block that is m I₃ divides; any other is inverted).
    const auto blocks = system.mass.blocks();
    for (std::size_t i = 0; i < force.size(); ++i) {
      const Mat3<Real>& b = blocks[i];
      const bool scalar = b.isDiagonal(Real(0)) && b(0, 0) == b(1, 1) && b(1, 1) == b(2, 2);
      acceleration[i] = scalar ? Vec3<Real>(force[i] / b(0, 0)) : Vec3<Real>(b.inverse() * force[i]);
    }
    // A rigid carrying masses couples its two blocks: their accelerations solve the 6×6 system.
    for (const auto& c : system.mass.couplings()) {
      const auto a = static_cast<std::size_t>(c.first), d = static_cast<std::size_t>(c.second);
      Eigen::Matrix<Real, 6, 6> m;
      m << blocks[a], c.block, c.block.transpose(), blocks[d];
      Eigen::Matrix<Real, 6, 1> f;
      f << force[a], force[d];
      const Eigen::Matrix<Real, 6, 1> solved = m.ldlt().solve(f);
      acceleration[a] = solved.template head<3>();
      acceleration[d] = solved.template tail<3>();
    }
    system.project(acceleration);
  } else if (system.mass.is_lumped()) {
    // SOFA's accFromF, then projectResponse.
    const auto masses = system.mass.vertex_masses();
    for (std::size_t i = 0; i < force.size(); ++i) acceleration[i] = force[i] / masses[i];
    system.project(acceleration);
  } else {
    // SOFA projects f, assembles M (projected) and solves M a = P f.
    system.project(force);
    const LinearSolveReport solved = solver.solve(system, {Real(1), Real(0), Real(0)}, force, acceleration);
    report = {1, solved.iterations};
  }
  return report;
}

namespace {

void add(StepReport& total, const StepReport& part) {
  total.linear_solves += part.linear_solves;
  total.linear_iterations += part.linear_iterations;
}

}  // namespace

template <class Real>
StepReport ExplicitEulerSolver<Real>::step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) {
  auto& x = system.state.position;
  auto& v = system.state.velocity;
  acceleration_.resize(x.size());
  const StepReport report = explicit_acceleration<Real>(system, solver, x, {}, force_, acceleration_);
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (symplectic_) {
      v[i] += dt * acceleration_[i];
      x[i] += dt * v[i];
    } else {
      x[i] += dt * v[i];
      v[i] += dt * acceleration_[i];
    }
  }
  return report;
}

template <class Real>
StepReport RungeKutta4Solver<Real>::step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) {
  auto& x = system.state.position;
  auto& v = system.state.velocity;
  const std::size_t n = x.size();
  x0_ = x;
  v0_ = v;
  xs_.resize(n);
  for (int k = 0; k < 4; ++k) k_acceleration_[k].resize(n);
  // Stage k evaluates the acceleration at x0 + c h v_{k-1}, its velocity being v0 + c h a_{k-1}
  // (c = 0, 1/2, 1/2, 1), as SOFA's RungeKutta4Solver (k1v is the velocity itself).
  const Real c[4] = {Real(0), dt / 2, dt / 2, dt};
  StepReport report;
  k_velocity_[0] = v0_;
  for (int k = 0; k < 4; ++k) {
    if (k > 0) {
      k_velocity_[k].resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        xs_[i] = x0_[i] + k_velocity_[k - 1][i] * c[k];
        k_velocity_[k][i] = v0_[i] + k_acceleration_[k - 1][i] * c[k];
      }
    }
    add(report, explicit_acceleration<Real>(system, solver, k == 0 ? std::span<const Vec3<Real>>(x0_) : xs_,
                                            k_velocity_[k], force_, k_acceleration_[k]));
  }
  const Real sixth = dt / 6, third = dt / 3;
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = x0_[i] + k_velocity_[0][i] * sixth + k_velocity_[1][i] * third + k_velocity_[2][i] * third +
           k_velocity_[3][i] * sixth;
    v[i] = v0_[i] + k_acceleration_[0][i] * sixth + k_acceleration_[1][i] * third + k_acceleration_[2][i] * third +
           k_acceleration_[3][i] * sixth;
  }
  return report;
}

template StepReport explicit_acceleration(MechanicalSystem<double>&, LinearSolver<double>&, std::span<const Vec3<double>>,
                                          std::span<const Vec3<double>>, std::vector<Vec3<double>>&, std::span<Vec3<double>>);
template StepReport explicit_acceleration(MechanicalSystem<float>&, LinearSolver<float>&, std::span<const Vec3<float>>,
                                          std::span<const Vec3<float>>, std::vector<Vec3<float>>&, std::span<Vec3<float>>);
template class ExplicitEulerSolver<double>;
template class ExplicitEulerSolver<float>;
template class RungeKutta4Solver<double>;
template class RungeKutta4Solver<float>;

}  // namespace fastcorot
