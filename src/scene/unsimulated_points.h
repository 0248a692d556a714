// States no ODE solver integrates that a Lagrangian constraint names (SOFA's example scenes tie
// bodies to such targets and rails): their points, placed as the scene places them (under a
// RigidMapping from a still rigid: in that rigid's frame), and moved at each step's end by a
// LinearMovementProjectiveConstraint on them or on that rigid, as SOFA's loop projects every state
// (PrescribedMotion). Internal to src/scene (lagrangian_builder.cpp); docs/constraints.md.
#pragma once

#include "fastcorot/constraint/constraint_points.h"
#include "lagrangian_builder.h"
#include "scene_data.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

class UnsimulatedPoints {
 public:
  UnsimulatedPoints(SceneData& data, std::vector<std::string>& info, const LocateState& locate)
      : data_(data), info_(info), locate_(locate) {}

  // The points of `state` (which `user` names) when no ODE solver integrates it: nullopt when one
  // does or it is a Rigid3 state. Throws fastcorot::Error naming what is wrong (no points, a
  // mapping other than a RigidMapping from a still rigid, several movements).
  std::optional<ConstraintPoints<double>> points(Component& state, Component& user);

 private:
  static Component* linear_movement_in(const GraphNode& node);
  std::shared_ptr<PrescribedMotion<double>> own_movement(Component& state, const std::vector<Vec3<double>>& positions);
  void carried_by_still_rigid(Component& state, ConstraintPoints<double>& points);
  std::shared_ptr<PrescribedMotion<double>> carried_motion(Component& moving, const Numbers& poses, std::size_t index,
                                                           const std::vector<Vec3<double>>& positions, bool world);
  void warn_if_moved(Component& state, Component& user, bool followed);

  SceneData& data_;
  std::vector<std::string>& info_;
  const LocateState& locate_;
};

}  // namespace fastcorot::scene_detail
