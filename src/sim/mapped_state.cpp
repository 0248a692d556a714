#include "fastcorot/sim/mapped_state.h"

#include "fastcorot/sim/simulation.h"

namespace fastcorot {

std::vector<StateSnapshot> state_snapshots(const SimulatedObject<double>& object) {
  const auto& state = object.system.state;
  std::vector<StateSnapshot> out;
  out.reserve(object.states.size() + object.mapped_states.size());
  for (const StateRange& range : object.states) {
    const auto first = static_cast<std::ptrdiff_t>(range.offset), last = first + static_cast<std::ptrdiff_t>(range.size);
    out.push_back({range.node, range.name, false, {state.position.begin() + first, state.position.begin() + last},
                   {state.velocity.begin() + first, state.velocity.begin() + last}});
  }
  for (const MappedState& mapped : object.mapped_states) {
    StateSnapshot snapshot{mapped.node, mapped.name, true, std::vector<Vec3<double>>(mapped.map.size()),
                           std::vector<Vec3<double>>(mapped.map.size())};
    mapped.map.apply(state.position, snapshot.position);
    mapped.map.apply(state.velocity, snapshot.velocity);
    out.push_back(std::move(snapshot));
  }
  return out;
}

}  // namespace fastcorot
