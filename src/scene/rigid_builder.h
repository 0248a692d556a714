// Rigid bodies in SOFA scenes: a MechanicalObject of template Rigid3 (Rigid3d, Rigid3f, Rigid)
// built as an object whose state holds two Vec3 blocks per rigid (state/rigid_blocks.h), with the
// components SOFA's rigid scenes put beside it (UniformMass, FixedProjectiveConstraint,
// ConstantForceField); and the RigidMapping of its mapped child nodes.
// Internal to src/scene (scene_builder.cpp); errors name the component.
#pragma once

#include "fastcorot/mapping/rigid_mapping.h"
#include "fastcorot/sim/simulation.h"
#include "scene_data.h"

#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// The rigid object of `state` with the components of `nodes` (its node and the unmapped nodes
// below it), not finalized: the caller folds its mapped nodes in (their RigidMapping'd mechanics,
// visual models and mapped states). Throws fastcorot::Error naming the component for what a Rigid3
// state does not support here.
SimulatedObject<double> build_rigid_object(SceneData& data, std::vector<std::string>& info, Component& state,
                                           const std::vector<GraphNode*>& nodes, const Vec3<double>& gravity);

// The RigidMapping `mapping` from the rigids of `object` onto points placed at `child_positions`
// (its attributes index, indexFromEnd, rigidIndexPerPoint, globalToLocalCoords, initialPoints, useX0).
RigidMapping<double> build_rigid_mapping(SceneData& data, Component& mapping, const SimulatedObject<double>& object,
                                         const std::vector<Vec3<double>>& child_positions,
                                         const std::vector<Vec3<double>>& child_rest_positions);

}  // namespace fastcorot::scene_detail
