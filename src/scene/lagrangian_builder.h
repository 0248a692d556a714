// SOFA's constraint-based animation in a scene: FreeMotionAnimationLoop, its constraint solver, the
// objects' constraint corrections and the Lagrangian constraints (docs/constraints.md), built once
// every simulated object exists. Internal to src/scene (scene_builder.cpp); errors name the
// component and the attribute.
#pragma once

#include "fastcorot/sim/simulation.h"
#include "scene_data.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// Where a MechanicalObject is simulated: its object, and its range of the object's blocks, or the
// mapped state that follows the object.
struct StateLocation {
  std::size_t object = 0;
  Index offset = 0;
  Index size = 0;
  bool rigid = false;
  const MappedState* mapped = nullptr;
};
using LocateState = std::function<std::optional<StateLocation>(const Component& state)>;

// Whether `type` is one of the components built here (animation loop, constraint solvers,
// corrections, Lagrangian constraints).
bool is_lagrangian_component(std::string_view type);

// Which scene components the loop's parts come from (for front ends that keep the scene tree).
struct LagrangianParts {
  std::vector<const SceneObject*> constraints;  // in the loop's order
  const SceneObject* solver = nullptr;          // null: SOFA's default solver, added
};

// Sets simulation.constraints when the root holds a FreeMotionAnimationLoop (with the constraint
// solver found in the scene, else SOFA's default BlockGaussSeidelConstraintSolver with a warning),
// with every correction and Lagrangian constraint of the scene in scene-graph order.
// `solver_nodes[o]` is the node of object o's ODE solver. Without the loop, Lagrangian components
// are reported in `info` (SOFA's default loop does not solve them). Throws fastcorot::Error naming
// the component for what is wrong or not supported.
LagrangianParts build_free_motion_loop(SceneData& data, std::vector<std::string>& info, Simulation<double>& simulation,
                                       const std::vector<const GraphNode*>& solver_nodes, const LocateState& locate);

}  // namespace fastcorot::scene_detail
