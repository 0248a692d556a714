// The projective constraints beyond FixedProjectiveConstraint, built onto an object's
// MechanicalSystem as partial projections and end-of-step placements (mechanical_system.h):
// PartialFixed-, FixedPlane-, Plane-, Line-, Point-, AffineMovement-, PatchTestMovement-, LinearMovement- and
// AttachProjectiveConstraint, each
// as SOFA defines it.
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

// LinearMovementProjectiveConstraint c on a state of `count` points, or of `count` rigid bodies
// (`rigid`: movements of 6 numbers, the centre's and Euler angles; the rigid k's centre is block
// 2k). Throws fastcorot::Error naming c for an index out of range, key times not in order or not
// finite, or a movement count that does not match them.
LinearMovement<double> build_linear_movement(SceneData& data, Component& c, Index count, bool rigid);

// FixedProjectiveConstraint c: its indices (SOFA's default: point 0; fixAll: every point) held,
// their velocities zeroed after each step with activate_projectVelocity. Throws fastcorot::Error
// naming c for an index out of range.
void add_fixed_constraint(SceneData& data, Component& c, MechanicalSystem<double>& system);

// Adds AttachProjectiveConstraint c to `system`, whose points are those of `states` one after the
// other (states[k]'s first point at offsets[k], sizes[k] points). Throws fastcorot::Error naming c
// when an object is not among `states` (another solver's), for an index out of range, mismatched
// lists, or the point-releasing options (minDistance, lastDir) that are not supported.
void add_attach_constraint(SceneData& data, Component& c, const std::vector<Component*>& states,
                           const std::vector<Index>& offsets, const std::vector<Index>& sizes,
                           MechanicalSystem<double>& system);

}  // namespace fastcorot::scene_detail
