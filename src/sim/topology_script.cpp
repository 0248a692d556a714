#include "fastcorot/sim/topology_script.h"

#include "fastcorot/core/error.h"

namespace fastcorot {

template <class Real>
void TopologyScript::apply_due(double time, double dt, MechanicalSystem<Real>& system) {
  // Times are step counts times dt: a millionth of a step absorbs their rounding.
  const double slack = 1e-6 * dt;
  while (next < events.size()) {
    TopologyEvent& event = events[next];
    const bool due = strictly_after ? time > event.time + slack : time >= event.time - slack;
    if (!due) return;
    try {
      if (!event.remove.empty()) system.remove_tetrahedra(*mesh, event.remove);
      if (!event.add.empty()) system.add_tetrahedra(*mesh, event.add);
    } catch (const Error& error) {
      throw make_error(where, ": ", event.where, " at t = ", time, ": ", error.what());
    }
    if (interval > 0) {
      event.time += interval;  // fires again later, at most once per step (SOFA's rule)
      return;
    } else {
      ++next;
    }
  }
}

template void TopologyScript::apply_due(double, double, MechanicalSystem<float>&);
template void TopologyScript::apply_due(double, double, MechanicalSystem<double>&);

}  // namespace fastcorot
