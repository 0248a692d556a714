#include "fastcorot/sim/topology_script.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <limits>

namespace fastcorot {

template <class Real>
void TopologyScript::apply_due(double time, MechanicalSystem<Real>& system) {
  const double reading = time + shift;
  while (next < events.size()) {
    TopologyEvent& event = events[next];
    const bool due = strictly_after ? !(event.time >= time)
                                    : event.time < reading || std::abs(event.time - reading) < std::numeric_limits<double>::epsilon();
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

template void TopologyScript::apply_due(double, MechanicalSystem<float>&);
template void TopologyScript::apply_due(double, MechanicalSystem<double>&);

}  // namespace fastcorot
