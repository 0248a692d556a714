#include "fastcorot/sim/simulation.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

namespace fastcorot {

namespace {

// Divergence messages: 6 significant digits are enough to see what happened (t = 0.06, not
// 0.059999999999999998).
template <class... Parts>
std::string brief(Parts&&... parts) {
  std::ostringstream out;
  out.precision(6);
  (out << ... << std::forward<Parts>(parts));
  return out.str();
}

// The first sign of divergence in one object's state after a step, if any: the first vertex with a
// non-finite position or velocity, else the vertex that went farthest beyond `bound`.
template <class Real>
std::optional<std::string> find_divergence(const MechanicalState<Real>& state, Real dt, Real bound,
                                           Real factor, Real scene_size) {
  const auto& x = state.position;
  const auto& v = state.velocity;
  const auto& rest = state.rest_position;
  auto vector_text = [](const Vec3<Real>& a) -> std::string {
    return brief("(", a.x(), ", ", a.y(), ", ", a.z(), ")");
  };
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!x[i].allFinite())
      return "vertex " + std::to_string(i) + " has a non-finite position " + vector_text(x[i]);
    if (!v[i].allFinite())
      return "vertex " + std::to_string(i) + " has a non-finite velocity " + vector_text(v[i]);
  }
  if (!(bound > 0) || !std::isfinite(bound)) return std::nullopt;
  std::size_t worst = 0;
  Real worst_excess = 0, worst_distance = 0;
  bool by_velocity = false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Real moved = (x[i] - rest[i]).norm();
    const Real stride = dt * v[i].norm();
    const Real distance = std::max(moved, stride);
    // Overflow in norm() makes a finite but huge state infinite here: still divergence.
    if (!(distance <= bound) && (worst_excess == 0 || distance / bound > worst_excess)) {
      worst = i;
      worst_excess = distance / bound;
      worst_distance = distance;
      by_velocity = stride > moved;
    }
  }
  if (worst_excess == 0) return std::nullopt;
  const std::string limit = brief(", beyond the divergence bound ", bound, " (", factor,
                                  " x the scene's size ", scene_size, ")");
  if (by_velocity) {
    return brief("vertex ", worst, " has velocity ", vector_text(v[worst]), " that carries it ",
                 worst_distance, " in one step", limit);
  }
  return brief("vertex ", worst, " is ", worst_distance, " from its rest position (now at ",
               vector_text(x[worst]), ")", limit);
}

// An object's free motion (its whole step under the default animation loop): the ODE solver's step,
// then (`rebase`) its rigids' rotations folded into their orientations. Under the constraint stage
// the rotations stay in the angular blocks until the stage has read the start orientations.
template <class Real>
StepReport free_motion(SimulatedObject<Real>& object, Real dt, long step_number, double clock, bool rebase = true) {
  StepReport report;
  try {
    object.system.update_mass();
    object.system.begin_step(clock);
    report = object.ode_solver->step(object.system, *object.linear_solver, dt);
  } catch (const Error& error) {
    const Real time = static_cast<Real>(step_number) * dt;
    throw Error(
        brief("diverged at step ", step_number, " (t = ", time, ") in ", object.path, ": ") +
        error.what());
  }
  if (rebase && object.system.rigids) object.system.rigids->rebase(object.system.state.position);
  return report;
}

// The end of an object's step: SOFA's projectPosition and projectVelocity, the divergence test and
// the force fields' end of step.
template <class Real>
void finish_step(SimulatedObject<Real>& object, Real dt, long step_number, double clock, Real bound, Real factor,
                 Real scene_size) {
  const Real time = static_cast<Real>(step_number) * dt;
  object.system.apply_placements(clock);
  for (Index i : object.system.zero_velocity) object.system.state.velocity[static_cast<std::size_t>(i)].setZero();
  if (auto problem = find_divergence(object.system.state, dt, bound, factor, scene_size)) {
    throw Error(
        brief("diverged at step ", step_number, " (t = ", time, "): ", object.path, " ", *problem));
  }
  for (auto& field : object.system.force_fields) field->end_step(object.system.state.position);
}

}  // namespace

template <class Real>
void Simulation<Real>::set_steps_done(long steps) {
  if (steps < 0) throw make_error("step count ", steps, ": must be >= 0");
  steps_done_ = steps;
  clock_ = 0;
  for (long s = 0; s < steps; ++s) clock_ += static_cast<double>(dt);
}

template <class Real>
Real Simulation<Real>::scene_size() const {
  bool any = false;
  Vec3<Real> lo = Vec3<Real>::Zero(), hi = Vec3<Real>::Zero();
  for (const auto& object : objects) {
    for (const auto& p : object.system.state.rest_position) {
      lo = any ? lo.cwiseMin(p).eval() : p;
      hi = any ? hi.cwiseMax(p).eval() : p;
      any = true;
    }
  }
  const Real size = (hi - lo).norm();
  return size > 0 && std::isfinite(size) ? size : Real(1);
}

template <class Real>
void Simulation<Real>::apply_topology_changes(long step_number, double clock) {
  for (auto& object : objects) {
    for (auto& script : object.topology_scripts) {
      try {
        script.apply_due(clock, object.system);
      } catch (const Error& error) {
        throw Error(brief("at step ", step_number, " (t = ", clock, "): ") + error.what());
      }
    }
  }
}

template <class Real>
void Simulation<Real>::replay_topology_changes(long steps) {
  double clock = clock_;
  for (long s = steps_done_ + 1; s <= steps; ++s) {
    apply_topology_changes(s, clock);
    clock += static_cast<double>(dt);
  }
}

template <class Real>
StepReport Simulation<Real>::step() {
  const long step_number = steps_done_ + 1;
  apply_topology_changes(step_number, clock_);
  if (collisions) {
    try {
      collisions->set_threads(threads);
      collision_report_ = collisions->begin_step(objects, dt, clock_);
    } catch (const Error& error) {
      throw Error(brief("at step ", step_number, " (t = ", clock_, "): ") + error.what());
    }
  }
  const Real size =
      divergence_factor > 0 && std::isfinite(divergence_factor) ? scene_size() : Real(0);
  const Real bound = divergence_factor * size;
  std::vector<StepReport> reports(objects.size());
  std::vector<std::exception_ptr> failures(objects.size());
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), objects.size());
  // Threads left over when there are fewer objects than threads go to each object's own kernels.
  const int per_object = std::max(1, std::max(threads, 1) / static_cast<int>(std::max<std::size_t>(objects.size(), 1)));
  for (auto& object : objects) {
    if (object.system.threads() != per_object) object.system.set_threads(per_object);
  }
  // Runs `task` on every object, spread over the workers; a failure is kept for its object.
  const auto for_each_object = [&](auto&& task) {
    auto work = [&](std::size_t first) {
      for (std::size_t o = first; o < objects.size(); o += workers) {
        try {
          task(o);
        } catch (...) {
          failures[o] = std::current_exception();
        }
      }
    };
    if (workers <= 1) {
      work(0);
    } else {
      std::vector<std::jthread> pool;
      for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work, w);
      work(0);
    }
  };
  // Report the first failure in scene order, whichever thread met it.
  const auto rethrow_first = [&] {
    for (const auto& failure : failures) {
      if (failure) std::rethrow_exception(failure);
    }
  };
  if (!constraints) {
    for_each_object([&](std::size_t o) {
      reports[o] = free_motion(objects[o], dt, step_number, clock_);
      finish_step(objects[o], dt, step_number, clock_, bound, divergence_factor, size);
    });
  } else {
    // SOFA's FreeMotionAnimationLoop: every object's free motion, then the constraints solved on
    // the free positions and the objects corrected, then each object's end of step.
    std::vector<MechanicalState<Real>> start(objects.size());
    for_each_object([&](std::size_t o) {
      start[o].position = objects[o].system.state.position;
      start[o].velocity = objects[o].system.state.velocity;
      reports[o] = free_motion(objects[o], dt, step_number, clock_, false);
    });
    rethrow_first();
    try {
      constraint_report_ = constraints->correct(objects, start, dt, clock_);
    } catch (const Error& error) {
      throw Error(brief("at step ", step_number, " (t = ", clock_, "): ") + error.what());
    }
    for_each_object([&](std::size_t o) {
      if (objects[o].system.rigids) objects[o].system.rigids->rebase(objects[o].system.state.position);
      finish_step(objects[o], dt, step_number, clock_, bound, divergence_factor, size);
    });
  }
  rethrow_first();
  if (collisions) collisions->end_step(objects, collision_report_);
  StepReport total;
  for (const auto& report : reports) {
    total.linear_solves += report.linear_solves;
    total.linear_iterations += report.linear_iterations;
  }
  steps_done_ = step_number;
  clock_ += static_cast<double>(dt);
  return total;
}

template class Simulation<float>;
template class Simulation<double>;

}  // namespace fastcorot
