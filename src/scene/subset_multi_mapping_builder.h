// SOFA's SubsetMultiMapping<Vec3, Vec3> in a scene: the child state's point i is point j of input
// k (`indexPairs`, k j per point), each input a MechanicalObject the node's ODE solver integrates or
// one mapped from such an object (Identity, Subset, Barycentric or RigidMapping). Read once the
// solver's objects are merged, so every input is a mapping onto the merged degrees of freedom.
// Internal to src/scene (scene_builder.cpp); design in docs/mechanical-graph.md.
#pragma once

#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/sim/simulation.h"
#include "scene_data.h"

#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace fastcorot::scene_detail {

// The type of SOFA's SubsetMultiMapping; a node holding one is a multi-mapped node.
bool is_subset_multi_mapping(std::string_view type);

struct SubsetMultiMappingInputs {
  // Each input: linear (map) or carried by rigid bodies (rigid).
  struct Input {
    PointMapping<double> map;
    std::optional<RigidPoints<double>> rigid;
  };
  std::vector<Input> inputs;
  std::vector<std::pair<std::size_t, Index>> pairs;  // (input, point of that input) per child point

  // The child's points as one linear mapping when every input is linear; nullopt otherwise.
  std::optional<PointMapping<double>> linear() const;
  // The child's points as points carried by rigid bodies when every input is; nullopt otherwise.
  std::optional<RigidPoints<double>> carried() const;
  // The child's points in general: a SubsetMultiMapping over the inputs' own mappings.
  std::unique_ptr<MechanicalMapping<double>> mapping() const;
};

// The inputs of SubsetMultiMapping `c` (in `node`), for a solver whose points are those of `states`
// one after the other (states[k]'s first block at offsets[k], sizes[k] blocks) and whose mapped
// states are object.mapped_states. Throws fastcorot::Error naming the component for an input that is
// not a state of this solver, a Rigid3 input, an output other than the node's state, an odd or
// out-of-range indexPairs.
SubsetMultiMappingInputs read_subset_multi_mapping(SceneData& data, const GraphNode& node, Component& c,
                                                   const std::vector<Component*>& states, const std::vector<Index>& offsets,
                                                   const std::vector<Index>& sizes, const SimulatedObject<double>& object);

}  // namespace fastcorot::scene_detail
