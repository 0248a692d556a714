#include "fastcorot/constraint/free_motion_animation_loop.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/phase_times.h"

#include <algorithm>
#include <chrono>
#include <string_view>

namespace fastcorot {

template <class Real>
Eigen::SparseMatrix<Real> projection_matrix(const MechanicalSystem<Real>& system) {
  if (!system.couplings.empty()) {
    throw make_error("AttachProjectiveConstraint and Lagrangian constraints on one object are not supported together");
  }
  const std::size_t n = static_cast<std::size_t>(system.size());
  std::vector<const Mat3<Real>*> block(n, nullptr);
  std::vector<char> held(n, 0);
  for (const auto& p : system.projections) block[static_cast<std::size_t>(p.point)] = &p.projector;
  for (const auto* list : {&system.fixed, &system.isolated, &system.moving}) {
    for (Index i : *list) held[static_cast<std::size_t>(i)] = 1;
  }
  std::vector<Eigen::Triplet<Real>> triplets;
  triplets.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (held[i]) continue;
    const auto base = static_cast<Index>(3 * i);
    if (!block[i]) {
      for (int k = 0; k < 3; ++k) triplets.emplace_back(base + k, base + k, Real(1));
      continue;
    }
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        if ((*block[i])(r, c) != 0) triplets.emplace_back(base + r, base + c, (*block[i])(r, c));
      }
    }
  }
  Eigen::SparseMatrix<Real> p(static_cast<Index>(3 * n), static_cast<Index>(3 * n));
  p.setFromTriplets(triplets.begin(), triplets.end());
  return p;
}

template <class Real>
FreeMotionAnimationLoop<Real>::FreeMotionAnimationLoop(Parameters parameters, std::unique_ptr<ConstraintSolver<Real>> solver)
    : parameters_(parameters), solver_(std::move(solver)) {
  if (!solver_) throw make_error("FreeMotionAnimationLoop: no constraint solver");
}

template <class Real>
ConstraintReport FreeMotionAnimationLoop<Real>::correct(std::span<SimulatedObject<Real>> objects,
                                                        std::span<const MechanicalState<Real>> start, Real dt, double time) {
  ConstraintReport report;
  const ConstraintOrder order = this->order();
  // SOFA's free motion ends with projectResponse on the free velocities: points a movement holds
  // (whose velocity its end-of-step projection set to the movement's rate) have none in the free
  // motion, so their free positions stay where the step began.
  for (auto& object : objects) object.system.project(object.system.state.velocity);
  if (order != ConstraintOrder::velocity) {
    // SOFA's free motion ends with x_free = x + dt v_free on every state (the same bits as the
    // ODE's own update, except where it damps the velocity after it: vdamping).
    for (std::size_t o = 0; o < objects.size(); ++o) {
      auto& x = objects[o].system.state.position;
      if (!objects[o].ode_solver->integration_factors(dt)) {
        // A static or explicit solve keeps its own free positions, but the points a movement holds
        // have no free motion (their free velocity was just projected to zero).
        for (Index i : objects[o].system.moving) x[static_cast<std::size_t>(i)] = start[o].position[static_cast<std::size_t>(i)];
        continue;
      }
      const auto& v = objects[o].system.state.velocity;
      for (std::size_t i = 0; i < x.size(); ++i) x[i] = start[o].position[i] + dt * v[i];
    }
  }
  for (auto& constraint : constraints) {
    for (ConstraintPoints<Real>* points : constraint->point_sets()) {
      // Last step's constraint forces were read by the free motion: this solve's replace them.
      if (points->constraint_force) points->constraint_force->assign(points->size(), Vec3<Real>::Zero());
      if (points->unsimulated) continue;
      points->prepare(start[points->object], objects[points->object].system.state, dt);
    }
  }
  for (auto& constraint : constraints) constraint->prepare(objects, dt);
  ConstraintRows<Real> rows(objects.size());
  for (auto& constraint : constraints) constraint->build(rows);
  const int n = rows.size();
  report.rows = n;
  forces_.setZero(n);
  if (n == 0) problem_.clear(0);
  if (n > 0) {
    problem_.clear(n);
    for (const auto& constraint : constraints) {
      try {
        constraint->violation(order, dt, problem_.dfree.data());
      } catch (const Error& error) {
        throw error_at(constraint->where(), error);
      }
    }
    for (auto& constraint : constraints) constraint->add_resolutions(problem_);
    // Hᵀ on each object's blocks, projected; W from each object's corrections.
    std::vector<Eigen::SparseMatrix<Real>> ht(objects.size());
    const auto w_start = std::chrono::steady_clock::now();
    for (std::size_t o = 0; o < objects.size(); ++o) {
      if (!rows.touches(o)) continue;
      bool corrected = false;
      try {
        ht[o] = projection_matrix(objects[o].system) * rows.transposed(o, objects[o].system.size());
      } catch (const Error& error) {
        throw error_at(objects[o].path, error);
      }
      for (auto& correction : corrections) {
        if (correction->object() != o) continue;
        correction->set_unbuilt(solver_->unbuilt());
        correction->add_compliance(objects[o], ht[o], order, dt, problem_.w);
        corrected = true;
      }
      if (!corrected && std::find(uncorrected.begin(), uncorrected.end(), o) == uncorrected.end()) {
        throw make_error(objects[o].path, ": Lagrangian constraints act on it but it has no constraint correction "
                         "(add a LinearSolverConstraintCorrection or an UncoupledConstraintCorrection)");
      }
    }
    report.compliance_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w_start).count();
    if (!problem_.w.allFinite()) throw make_error("the constraints' compliance W is not finite");
    for (int r = 0; r < n; ++r) {
      if (!std::isfinite(problem_.dfree[r])) {
        for (const auto& constraint : constraints) {
          if (r >= constraint->first_row() && r < constraint->first_row() + constraint->rows()) {
            throw make_error(constraint->where(), ": the violation of row ", r - constraint->first_row(), " is not finite");
          }
        }
      }
    }
    const auto solve_start = std::chrono::steady_clock::now();
    const ConstraintSolveReport solved = solver_->solve(problem_);
    report.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count();
    report.iterations = solved.iterations;
    report.error = solved.error;
    report.tolerance = solved.tolerance;
    report.converged = solved.converged;
    if (!problem_.f.allFinite()) {
      const bool jacobi = std::string_view(solver_->name()) == "ImprovedJacobiConstraintSolver";
      throw make_error(solver_->name(), ": the constraint impulses are not finite: the solve diverged",
                       jacobi ? " (Jacobi iterations diverge on strongly coupled rows, such as many contacts: set "
                                "useSpectralCorrection, or use a BlockGaussSeidelConstraintSolver)"
                              : "");
    }
    forces_ = problem_.f;
    if (solver_->stores_lambda()) rows.store_constraint_forces(problem_.f.data(), dt);
    // Each object corrected for the impulses Hᵀλ on its blocks.
    std::vector<Vec3<Real>> impulse;
    for (std::size_t o = 0; o < objects.size(); ++o) {
      if (!rows.touches(o)) continue;
      auto& object = objects[o];
      impulse.assign(static_cast<std::size_t>(object.system.size()), Vec3<Real>::Zero());
      Eigen::Map<DenseVector<Real>>(impulse.data()->data(), static_cast<Eigen::Index>(3 * impulse.size())) = ht[o] * problem_.f;
      // The free motion's rotations are folded first: SOFA adds the correction to the free pose.
      if (order != ConstraintOrder::velocity && object.system.rigids) object.system.rigids->rebase(object.system.state.position);
      for (auto& correction : corrections) {
        if (correction->object() == o) correction->correct(object, impulse, order, dt);
      }
    }
  }
  // SOFA's end-of-step projection moves states no solver integrates (at the step's start time).
  for (auto& constraint : constraints) {
    for (ConstraintPoints<Real>* points : constraint->point_sets()) {
      if (!points->unsimulated || !points->motion) continue;
      points->motion->apply(time, points->position);
      points->free_position = points->position;
    }
  }
  if (order == ConstraintOrder::velocity) {
    // SOFA's velocity order: positions follow the corrected velocities, x = x_start + dt v.
    for (std::size_t o = 0; o < objects.size(); ++o) {
      auto& x = objects[o].system.state.position;
      const auto& v = objects[o].system.state.velocity;
      for (std::size_t i = 0; i < x.size(); ++i) x[i] = start[o].position[i] + dt * v[i];
    }
  }
  return report;
}

template class FreeMotionAnimationLoop<float>;
template class FreeMotionAnimationLoop<double>;
template Eigen::SparseMatrix<float> projection_matrix(const MechanicalSystem<float>&);
template Eigen::SparseMatrix<double> projection_matrix(const MechanicalSystem<double>&);

}  // namespace fastcorot
