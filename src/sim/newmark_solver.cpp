#include "fastcorot/sim/newmark_solver.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/explicit_solvers.h"
#include "carried_vectors.h"
#include "coefficient_checks.h"

#include <cmath>

namespace fastcorot {

template <class Real>
NewmarkSolver<Real>::NewmarkSolver(Parameters parameters, Index points)
    : parameters_(parameters), acceleration_(static_cast<std::size_t>(points), Vec3<Real>::Zero()) {
  detail::check_coefficient(parameters_.rayleigh_stiffness, "NewmarkImplicitSolver: rayleighStiffness");
  detail::check_coefficient(parameters_.rayleigh_mass, "NewmarkImplicitSolver: rayleighMass");
  detail::check_coefficient(parameters_.velocity_damping, "NewmarkImplicitSolver: vdamping");
  detail::check_coefficient(parameters_.gamma, "NewmarkImplicitSolver: gamma");
  detail::check_coefficient(parameters_.beta, "NewmarkImplicitSolver: beta");
}

template <class Real>
StepReport NewmarkSolver<Real>::step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) {
  auto& x = system.state.position;
  auto& v = system.state.velocity;
  const std::size_t n = x.size();
  const Real h = dt, g = parameters_.gamma, beta = parameters_.beta;
  const Real rm = parameters_.rayleigh_mass, rk = parameters_.rayleigh_stiffness;
  StepReport report;
  if (acceleration_.size() != n) throw make_error("NewmarkImplicitSolver: made for ", acceleration_.size(), " points, the system has ", n);
  if (!started_) {
    acceleration_.assign(n, Vec3<Real>::Zero());
    report = explicit_acceleration<Real>(system, solver, x, {}, force_, acceleration_);
    started_ = true;
  }
  rhs_.resize(n);
  next_.resize(n);
  system.compute_force(x, rhs_);  // records the linearisation at x_t
  if (rm != 0 || rk != 0 || beta != Real(0.5)) {
    for (const auto& field : system.force_fields) {
      field->add_dforce(acceleration_, rhs_, h * (1 - g) * rk + h * h * (1 - 2 * beta) / 2, Real(0));
    }
    if (system.mass.size() != 0) system.mass.add_mdx(acceleration_, rhs_, -h * (1 - g) * rm);
  }
  for (const auto& field : system.force_fields) field->add_dforce(v, rhs_, rk + h, Real(0));
  if (rm != 0 && system.mass.size() != 0) system.mass.add_mdx(v, rhs_, -rm);
  system.project(rhs_);
  const MatrixFactors<Real> factors{1 + h * g * rm, -h * g, -h * h * beta - h * rk * g};
  const LinearSolveReport solved = solver.solve(system, factors, rhs_, next_);
  report.linear_solves += 1;
  report.linear_iterations += solved.iterations;
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = x[i] + v[i] * h + acceleration_[i] * (h * h * (Real(0.5) - beta)) + next_[i] * (h * h * beta);
    v[i] = v[i] + acceleration_[i] * (h * (1 - g)) + next_[i] * (h * g);
  }
  if (parameters_.velocity_damping != 0) {
    const Real decay = std::exp(-h * parameters_.velocity_damping);
    for (auto& vi : v) vi *= decay;
  }
  acceleration_ = next_;
  return report;
}

template <class Real>
std::vector<std::int64_t> NewmarkSolver<Real>::carried_state() const {
  return detail::encode_carried(started_, acceleration_);
}

template <class Real>
void NewmarkSolver<Real>::restore_carried_state(const std::vector<std::int64_t>& state) {
  started_ = detail::decode_carried(state, acceleration_, "NewmarkImplicitSolver");
}

template class NewmarkSolver<double>;
template class NewmarkSolver<float>;

}  // namespace fastcorot
