#include "fastcorot/sim/mapped_state.h"

#include "fastcorot/sim/simulation.h"

namespace fastcorot {

namespace {

StateSnapshot rigid_snapshot(const StateRange& range, const RigidBlocks<double>& rigids, const MechanicalState<double>& state) {
  StateSnapshot snapshot{range.node, range.name, false, {}, {}, true, {}, {}};
  const std::vector<RigidCoord<double>> coords = rigids.coords(state.position);
  for (std::size_t k = 0; k < rigids.size(); ++k) {
    // The rigids of this range only (several objects may be solved together).
    if (rigids.block[k] < range.offset || rigids.block[k] >= range.offset + range.size) continue;
    const auto b = static_cast<std::size_t>(rigids.block[k]);
    const std::vector<double> values = to_values<double>(std::span<const RigidCoord<double>>(&coords[k], 1));
    snapshot.rigid_position.insert(snapshot.rigid_position.end(), values.begin(), values.end());
    snapshot.position.push_back(coords[k].center);
    snapshot.velocity.push_back(state.velocity[b]);
    for (std::size_t j = 0; j < 2; ++j) {
      for (int c = 0; c < 3; ++c) snapshot.rigid_velocity.push_back(state.velocity[b + j][c]);
    }
  }
  return snapshot;
}

}  // namespace

std::vector<StateSnapshot> state_snapshots(const SimulatedObject<double>& object) {
  const auto& state = object.system.state;
  std::vector<StateSnapshot> out;
  out.reserve(object.states.size() + object.mapped_states.size());
  for (const StateRange& range : object.states) {
    const auto first = static_cast<std::ptrdiff_t>(range.offset), last = first + static_cast<std::ptrdiff_t>(range.size);
    StateSnapshot snapshot{range.node, range.name, false, {state.position.begin() + first, state.position.begin() + last},
                           {state.velocity.begin() + first, state.velocity.begin() + last}};
    if (range.rigid && object.system.rigids) snapshot = rigid_snapshot(range, *object.system.rigids, state);
    out.push_back(std::move(snapshot));
  }
  for (const MappedState& mapped : object.mapped_states) {
    StateSnapshot snapshot{mapped.node, mapped.name, true, std::vector<Vec3<double>>(mapped.size()),
                           std::vector<Vec3<double>>(mapped.size())};
    snapshot.coordinates = mapped.coordinates;
    if (mapped.rigid) {
      mapped.rigid->positions(state.position, snapshot.position);
      mapped.rigid->velocities(state.position, state.velocity, snapshot.velocity);
    } else if (mapped.through) {
      std::vector<Vec3<double>> x(mapped.through->size()), v(mapped.through->size());
      const auto first = static_cast<std::size_t>(mapped.through_offset);
      const std::span<const Vec3<double>> positions(state.position), velocities(state.velocity);
      mapped.through->positions(positions.subspan(first), x);
      mapped.through->velocities(positions.subspan(first), velocities.subspan(first), v);
      mapped.map.apply(x, snapshot.position);
      mapped.map.apply(v, snapshot.velocity);
    } else {
      mapped.map.apply(state.position, snapshot.position);
      mapped.map.apply(state.velocity, snapshot.velocity);
    }
    out.push_back(std::move(snapshot));
  }
  return out;
}

}  // namespace fastcorot
