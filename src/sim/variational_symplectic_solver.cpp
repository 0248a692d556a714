#include "fastcorot/sim/variational_symplectic_solver.h"

#include "carried_vectors.h"
#include "coefficient_checks.h"
#include "fastcorot/core/error.h"

#include <cmath>

namespace fastcorot {

template <class Real>
VariationalSymplecticSolver<Real>::VariationalSymplecticSolver(Parameters parameters, Index points)
    : parameters_(parameters), momentum_(static_cast<std::size_t>(points), Vec3<Real>::Zero()) {
  detail::check_coefficient(parameters_.newton_error, "VariationalSymplecticSolver: newtonError");
  detail::check_coefficient(parameters_.rayleigh_stiffness, "VariationalSymplecticSolver: rayleighStiffness");
  detail::check_coefficient(parameters_.rayleigh_mass, "VariationalSymplecticSolver: rayleighMass");
  if (parameters_.newton_steps < 0) throw make_error("VariationalSymplecticSolver: steps = ", parameters_.newton_steps, ": must be >= 0");
}

template <class Real>
StepReport VariationalSymplecticSolver<Real>::step(MechanicalSystem<Real>& system, LinearSolver<Real>& solver, Real dt) {
  auto& x = system.state.position;
  auto& v = system.state.velocity;
  const std::size_t n = x.size();
  if (momentum_.size() != n) throw make_error("VariationalSymplecticSolver: made for ", momentum_.size(), " points, the system has ", n);
  if (system.mass.size() == 0) throw make_error("VariationalSymplecticSolver needs a mass: the object has none");
  const Real h = dt, rm = parameters_.rayleigh_mass, rk = parameters_.rayleigh_stiffness;
  if (!started_) {
    set_zero<Real>(momentum_);
    system.mass.add_mdx(v, momentum_, Real(1));  // p = M v (zero acceleration assumed)
    started_ = true;
  }
  force_.resize(n);
  rhs_.resize(n);
  increment_.assign(n, Vec3<Real>::Zero());
  StepReport report;
  const auto solve = [&](const MatrixFactors<Real>& factors) {
    const LinearSolveReport solved = solver.solve(system, factors, rhs_, increment_);
    report.linear_solves += 1;
    report.linear_iterations += solved.iterations;
  };
  if (parameters_.explicit_integration) {
    system.compute_force(x, force_);
    for (std::size_t i = 0; i < n; ++i) rhs_[i] = force_[i] + momentum_[i] / h;
    if (system.mass.is_lumped()) {
      const auto masses = system.mass.vertex_masses();
      for (std::size_t i = 0; i < n; ++i) increment_[i] = rhs_[i] / masses[i];
    } else {
      system.project(rhs_);
      solve({Real(1), Real(0), Real(0)});
    }
    for (std::size_t i = 0; i < n; ++i) increment_[i] -= v[i] * rm;
    system.project(increment_);
    for (std::size_t i = 0; i < n; ++i) {
      v[i] = increment_[i] * h;
      x[i] = x[i] + v[i] * h;
    }
    set_zero<Real>(momentum_);
    system.mass.add_mdx(v, momentum_, Real(1));
    return report;
  }
  start_ = x;
  previous_ = x;
  Real position_norm = 0;
  for (const auto& p : start_) position_norm += p.squaredNorm();
  position_norm = std::sqrt(position_norm);
  const MatrixFactors<Real> factors{4 / (h * h) + 4 * rm / h, Real(0), -1 - 4 * rk / h};
  Real error = 0;
  for (int iteration = 0; (iteration < parameters_.newton_steps && error > parameters_.newton_error) || iteration == 0;
       ++iteration) {
    system.compute_force(x, force_);
    for (std::size_t i = 0; i < n; ++i) rhs_[i] = force_[i] + momentum_[i] * (2 / h);
    for (const auto& field : system.force_fields) field->add_dforce(increment_, rhs_, Real(-1), Real(0));
    system.project(rhs_);
    solve(factors);
    Real change = 0;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = start_[i] + increment_[i];
      change += (x[i] - previous_[i]).squaredNorm();
      previous_[i] = x[i];
    }
    error = std::sqrt(change) / position_norm;
  }
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = increment_[i] * (2 / h);
    x[i] = start_[i] + v[i] * (h / 2);
  }
  system.compute_force(x, force_);
  system.project(force_);
  for (std::size_t i = 0; i < n; ++i) momentum_[i] = force_[i] * (h / 2);
  system.mass.add_mdx(v, momentum_, Real(1));
  for (std::size_t i = 0; i < n; ++i) x[i] = start_[i] + v[i] * (h / 2) + v[i] * (h / 2);
  return report;
}

template <class Real>
std::vector<std::int64_t> VariationalSymplecticSolver<Real>::carried_state() const {
  return detail::encode_carried(started_, momentum_);
}

template <class Real>
void VariationalSymplecticSolver<Real>::restore_carried_state(const std::vector<std::int64_t>& state) {
  started_ = detail::decode_carried(state, momentum_, "VariationalSymplecticSolver");
}

template class VariationalSymplecticSolver<double>;
template class VariationalSymplecticSolver<float>;

}  // namespace fastcorot
