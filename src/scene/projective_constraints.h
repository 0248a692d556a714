// The projective constraints beyond FixedProjectiveConstraint, built onto an object's
// MechanicalSystem as partial projections and end-of-step placements (mechanical_system.h):
// PartialFixed-, FixedPlane-, Plane- and LineProjectiveConstraint, each as SOFA defines it.
// Internal to src/scene (scene_builder.cpp).
#pragma once

#include "fastcorot/sim/mechanical_system.h"
#include "scene_data.h"

namespace fastcorot::scene_detail {

// Whether `type` is one of the constraints add_projective_constraint builds.
bool is_partial_projective_constraint(std::string_view type);

// Adds constraint c to `system` (whose positions are the state at init). Throws fastcorot::Error
// naming c for an index out of range or a malformed attribute.
void add_projective_constraint(SceneData& data, Component& c, MechanicalSystem<double>& system);

}  // namespace fastcorot::scene_detail
