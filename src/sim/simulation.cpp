#include "fastcorot/sim/simulation.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <exception>
#include <thread>

namespace fastcorot {

namespace {

template <class Real>
StepReport step_object(SimulatedObject<Real>& object, Real dt, long step_number) {
  StepReport report;
  try {
    report = object.ode_solver->step(object.system, *object.linear_solver, dt);
  } catch (const Error& error) {
    throw make_error("diverged at step ", step_number, " in ", object.path, ": ", error.what());
  }
  for (Index i : object.system.zero_velocity) object.system.state.velocity[static_cast<std::size_t>(i)].setZero();
  if (!all_finite<Real>(object.system.state.position) || !all_finite<Real>(object.system.state.velocity)) {
    throw make_error("diverged at step ", step_number, ": ", object.path, " has non-finite positions or velocities");
  }
  return report;
}

}  // namespace

template <class Real>
StepReport Simulation<Real>::step() {
  const long step_number = steps_done_ + 1;
  std::vector<StepReport> reports(objects.size());
  std::vector<std::exception_ptr> failures(objects.size());
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), objects.size());
  // Threads left over when there are fewer objects than threads go to each object's own kernels.
  const int per_object = std::max(1, std::max(threads, 1) / static_cast<int>(std::max<std::size_t>(objects.size(), 1)));
  for (auto& object : objects) {
    if (object.system.threads() != per_object) object.system.set_threads(per_object);
  }
  auto work = [&](std::size_t first) {
    for (std::size_t o = first; o < objects.size(); o += workers) {
      try {
        reports[o] = step_object(objects[o], dt, step_number);
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
  // Report the first failure in scene order, whichever thread met it.
  for (const auto& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
  StepReport total;
  for (const auto& report : reports) {
    total.linear_solves += report.linear_solves;
    total.linear_iterations += report.linear_iterations;
  }
  steps_done_ = step_number;
  return total;
}

template class Simulation<float>;
template class Simulation<double>;

}  // namespace fastcorot
