#include "fastcorot/sim/simulation.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

template <class Real>
StepReport Simulation<Real>::step() {
  StepReport total;
  const long step_number = steps_done_ + 1;
  for (auto& object : objects) {
    StepReport report;
    try {
      report = object.ode_solver->step(object.system, *object.linear_solver, dt);
    } catch (const Error& error) {
      throw make_error("diverged at step ", step_number, " in ", object.path, ": ", error.what());
    }
    if (!all_finite<Real>(object.system.state.position) || !all_finite<Real>(object.system.state.velocity)) {
      throw make_error("diverged at step ", step_number, ": ", object.path,
                       " has non-finite positions or velocities");
    }
    total.linear_solves += report.linear_solves;
    total.linear_iterations += report.linear_iterations;
  }
  steps_done_ = step_number;
  return total;
}

template class Simulation<float>;
template class Simulation<double>;

}  // namespace fastcorot
