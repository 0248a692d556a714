// SoftRobots' constraints in a scene (docs/softrobots.md): CableConstraint and
// SurfacePressureConstraint, built by the loop
// builder (lagrangian_builder.cpp) in scene-graph order among SOFA's Lagrangian constraints.
// Internal to src/scene.
#pragma once

#include "fastcorot/constraint/lagrangian_constraints.h"
#include "scene_data.h"

#include <memory>
#include <span>
#include <string_view>

namespace fastcorot::scene_detail {

bool is_softrobots_constraint(std::string_view type);

// The constraint component `c` describes, on `points` (its node's state) whose positions are
// `initial_positions` as the scene is built. Throws fastcorot::Error naming the attribute for what
// is wrong or not supported (a method other than point, a Vec2 template).
std::unique_ptr<LagrangianConstraint<double>> build_softrobots_constraint(SceneData& data, Component& c, ConstraintPoints<double> points,
                                                                          std::span<const Vec3<double>> initial_positions);

}  // namespace fastcorot::scene_detail
