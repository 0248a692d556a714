// The spring components of a scene: SpringForceField (StiffSpringForceField, its older name),
// RegularGridSpringForceField and RestShapeSpringsForceField (docs/springs.md). SpringForceField is
// SOFA's pair interaction force field: its springs join points of object1 and object2 (by default
// the state of its own node), which may be two objects of one ODE solver; it is built once the
// solver's objects are merged into one system, on the merged indices. Internal to src/scene
// (scene_builder.cpp); errors name the component and the attribute.
#pragma once

#include "fastcorot/fem/force_field.h"
#include "fastcorot/sim/simulation.h"
#include "scene_data.h"

#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace fastcorot::scene_detail {

// SpringForceField or its alias StiffSpringForceField: built by add_interaction_springs.
bool is_interaction_spring(std::string_view type);

// Throws fastcorot::Error naming spring c, which no ODE solver at or above its node integrates: the
// objects it joins would have to be integrated by one solver above them.
[[noreturn]] void refuse_spring_without_solver(const Component& c, const std::string& node_path);

// Adds every SpringForceField of `nodes` (a solver's nodes) to `object`, whose points are those of
// `states` one after the other (states[k]'s first point at offsets[k], sizes[k] points). Throws
// fastcorot::Error naming the component for an object1/object2 that is not among `states`, an index
// out of range, mismatched lists, a negative stiffness, damping or length, or what is not supported.
void add_interaction_springs(SceneData& data, const std::vector<GraphNode*>& nodes, const std::vector<Component*>& states,
                             const std::vector<Index>& offsets, const std::vector<Index>& sizes,
                             SimulatedObject<double>& object);

// RegularGridSpringForceField or RestShapeSpringsForceField: springs on one object's points, built
// with the object (build_point_springs).
bool is_point_spring(std::string_view type);

// RegularGridSpringForceField or RestShapeSpringsForceField c on `state`, whose rest positions are
// `rest`; `mesh` is the object's mesh for output (null: a mesh of its points alone).
std::shared_ptr<ForceField<double>> build_point_springs(SceneData& data, Component& c, Component& state,
                                                        std::span<const Vec3<double>> rest, std::shared_ptr<const TetMesh> mesh);

// RegularGridSpringForceField c on the state of `size` points: the grid's springs (when its topology
// is a RegularGridTopology, as SOFA's), after any springs listed one by one.
std::shared_ptr<ForceField<double>> build_regular_grid_springs(SceneData& data, Component& c, Index size);

// RestShapeSpringsForceField c on `state` (its rest positions `rest`, its mesh `mesh`).
std::shared_ptr<ForceField<double>> build_rest_shape_springs(SceneData& data, Component& c, Component& state,
                                                             std::span<const Vec3<double>> rest,
                                                             std::shared_ptr<const TetMesh> mesh);

}  // namespace fastcorot::scene_detail
