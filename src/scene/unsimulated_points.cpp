#include "unsimulated_points.h"

#include "fastcorot/core/error.h"
#include "fastcorot/state/rigid3.h"
#include "projective_constraints.h"

namespace fastcorot::scene_detail {

// A Vec3 MechanicalObject with no ODE solver at or above its node: SOFA integrates nothing there
// and its rows reach no correction, so its points stay where the scene puts them.
std::optional<ConstraintPoints<double>> UnsimulatedPoints::points(Component& state, Component& user) {
  for (const GraphNode* node = state.node; node; node = node->parent) {
    if (!node->of_category("odesolver").empty()) return std::nullopt;
  }
  if (is_rigid_template(data_.text(state, "template", "Vec3d"))) return std::nullopt;
  ConstraintPoints<double> points;
  points.unsimulated = true;
  points.position = data_.points(state, "position");  // placed (translation, rotation, scale) as the state places them
  if (points.position.empty()) throw make_error(state.where(), ": no position: ", user.type(), " has no point to act on");
  carried_by_still_rigid(state, points);
  if (!points.motion) points.motion = own_movement(state, points.position);
  if (points.motion) {
    points.motion->apply(0.0, points.position);  // SOFA's init projects at time 0 (x0 recorded there)
    info_.push_back(user.where() + ": " + state.where() + " is not simulated (no ODE solver): its LinearMovementProjectiveConstraint "
                    "moves it at each step's end, as SOFA's FreeMotionAnimationLoop does");
  }
  warn_if_moved(state, user, points.motion != nullptr);
  points.free_position = points.position;
  points.free_velocity.assign(points.position.size(), Vec3<double>::Zero());
  points.rest_position = points.position;
  if (!points.motion) info_.push_back(user.where() + ": " + state.where() + " is not simulated (no ODE solver): its points stay put, as in SOFA");
  return points;
}

// The LinearMovementProjectiveConstraint in `node` acting on its state, if any.
// Throws fastcorot::Error when the node has several (only one is followed).
Component* UnsimulatedPoints::linear_movement_in(const GraphNode& node) {
  Component* found = nullptr;
  for (const auto& c : node.components) {
    if (c->type() != "LinearMovementProjectiveConstraint") continue;
    if (found) {
      throw make_error(c->where(), ": a second LinearMovementProjectiveConstraint on a state no ODE solver integrates (",
                       found->where(), "): only one is followed");
    }
    found = c.get();
  }
  return found;
}

// An unsimulated Vec3 state's own LinearMovementProjectiveConstraint (null when it has none).
std::shared_ptr<PrescribedMotion<double>> UnsimulatedPoints::own_movement(Component& state, const std::vector<Vec3<double>>& positions) {
  Component* c = linear_movement_in(*state.node);
  if (!c) return nullptr;
  auto motion = std::make_shared<PrescribedMotion<double>>();
  try {
    motion->movement = build_linear_movement(data_, *c, static_cast<Index>(positions.size()), false);
  } catch (const Error& error) {
    throw error_at(c->where(), error);
  }
  motion->state.position = positions;
  motion->state.velocity.assign(positions.size(), Vec3<double>::Zero());
  return motion;
}

// An unsimulated state under a RigidMapping from an unsimulated rigid (SOFA's example scenes
// attach points to a still rigid frame): its positions are local coordinates in the rigid's frame
// (SOFA's default) unless globalToLocalCoords. Other mappings from unsimulated states are refused.
void UnsimulatedPoints::carried_by_still_rigid(Component& state, ConstraintPoints<double>& points) {
  auto& positions = points.position;
  for (Component* m : state.node->of_category("visualmapping")) {
    if (m->has("output") && &data_.resolve_object(*m->node, m->object->attributes.at("output"), *m) != &state) continue;
    if (m->type() != "RigidMapping") {
      throw make_error(state.where(), " is mapped by ", m->where(), " from a state no ODE solver integrates: only a "
                       "RigidMapping is followed there");
    }
    for (const char* data : {"rigidIndexPerPoint", "indexFromEnd", "initialPoints", "useX0"}) {
      if (m->has(data)) throw make_error(m->where(), ": ", data, " on a rigid no ODE solver integrates is not supported");
    }
    Component* parent = nullptr;
    if (m->has("input")) {
      parent = &data_.resolve_state(*m->node, m->object->attributes.at("input"), *m);
    } else if (state.node->parent && !state.node->parent->of_category("state").empty()) {
      parent = state.node->parent->of_category("state").front();
    }
    if (!parent || !is_rigid_template(data_.text(*parent, "template", "Vec3d"))) {
      throw make_error(m->where(), ": its input is not a Rigid3 MechanicalObject");
    }
    for (const GraphNode* node = parent->node; node; node = node->parent) {
      if (!node->of_category("odesolver").empty() || locate_(*parent)) {
        // The rigid moves (SOFA's loop carries the point with it and Jᵀ gives the rigid the
        // constraint's force); a point off a simulated rigid's own subtree is not followed here.
        throw make_error(state.where(), " is carried by ", parent->where(), ", which an ODE solver moves, from outside that "
                         "solver's node: Lagrangian constraints on it are not supported (put the mapped node under the rigid's)");
      }
    }
    Component& input = *parent;
    const Numbers poses = data_.data(input, "position");
    const Index index = data_.whole_number(*m, "index", 0);
    if (poses.size() % 7 != 0 || index < 0 || static_cast<std::size_t>(7 * index + 7) > poses.size()) {
      throw make_error(m->where(), ": index ", index, " is not a rigid of ", input.where());
    }
    const double* pose = &poses[static_cast<std::size_t>(7 * index)];
    const Eigen::Quaterniond q(pose[6], pose[3], pose[4], pose[5]);
    const Vec3<double> centre(pose[0], pose[1], pose[2]);
    const bool world = data_.boolean(*m, "globalToLocalCoords", false);
    if (Component* moving = linear_movement_in(*input.node)) {
      points.motion = carried_motion(*moving, poses, static_cast<std::size_t>(index), positions, world);
      return;
    }
    if (world) return;  // already in the world
    for (auto& x : positions) x = centre + q.normalized() * x;
    return;
  }
}

// Points carried by rigid `index` of an unsimulated Rigid3 state (poses, 7 numbers each) that a
// LinearMovementProjectiveConstraint moves: the rigids' centres and orientations follow the
// movement, the points their rigid (local coordinates, or world ones brought into its frame).
std::shared_ptr<PrescribedMotion<double>> UnsimulatedPoints::carried_motion(Component& moving, const Numbers& poses, std::size_t index,
                                                                          const std::vector<Vec3<double>>& positions, bool world) {
  const std::size_t rigids = poses.size() / 7;
  auto motion = std::make_shared<PrescribedMotion<double>>();
  try {
    motion->movement = build_linear_movement(data_, moving, static_cast<Index>(rigids), true);
  } catch (const Error& error) {
    throw error_at(moving.where(), error);
  }
  motion->frames = std::make_shared<RigidBlocks<double>>();
  for (std::size_t k = 0; k < rigids; ++k) {
    const double* pose = &poses[7 * k];
    const Eigen::Quaterniond q = Eigen::Quaterniond(pose[6], pose[3], pose[4], pose[5]).normalized();
    motion->state.position.insert(motion->state.position.end(), {Vec3<double>(pose[0], pose[1], pose[2]), Vec3<double>::Zero()});
    motion->frames->block.push_back(static_cast<Index>(2 * k));
    motion->frames->orientation.push_back(q);
    motion->frames->rest_orientation.push_back(q);
  }
  motion->state.velocity.assign(motion->state.position.size(), Vec3<double>::Zero());
  const RigidCoord<double> frame = motion->frames->coord(motion->state.position, index);
  for (const auto& x : positions) {
    motion->rigid.push_back(index);
    motion->local.push_back(world ? frame.inverse_rotate(x - frame.center) : x);
  }
  return motion;
}

// SOFA's FreeMotionAnimationLoop projects every state's positions at the end of a step, so a
// prescribed movement on a state no solver integrates moves it there; here only a
// LinearMovementProjectiveConstraint does (above, `followed`), the others are warned.
void UnsimulatedPoints::warn_if_moved(Component& state, Component& user, bool followed) {
  for (const GraphNode* node = state.node; node; node = node->parent) {
    for (const auto& c : node->components) {
      const std::string_view type = c->type();
      if (followed && type == "LinearMovementProjectiveConstraint") continue;
      if (type.find("Movement") != std::string_view::npos || type.find("Oscillator") != std::string_view::npos) {
        data_.warn(user.where() + ": " + c->where() + " moves " + node->path + " in SOFA (its FreeMotionAnimationLoop "
                   "projects every state), but no ODE solver integrates it here: it stays put");
        return;
      }
    }
  }
}


}  // namespace fastcorot::scene_detail
