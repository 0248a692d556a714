#include "projective_constraints.h"

#include "fastcorot/core/error.h"

namespace fastcorot::scene_detail {

namespace {

// The constraint's indices, each checked against the state size; `fix_all` (FixedProjective-
// Constraint's data, inherited by PartialFixedProjectiveConstraint) selects every point.
std::vector<Index> constrained_points(SceneData& data, Component& c, Index size, bool fix_all,
                                      const std::vector<Index>& fallback) {
  std::vector<Index> indices;
  if (fix_all) {
    for (Index i = 0; i < size; ++i) indices.push_back(i);
    return indices;
  }
  indices = c.has("indices") ? data.indices(c, "indices") : fallback;
  for (Index i : indices) {
    if (i < 0 || i >= size) throw make_error(c.where(), ": index ", i, " out of range [0, ", size, ")");
  }
  return indices;
}

Vec3<double> unit_or(const Vec3<double>& v, const Vec3<double>& fallback) {
  const double norm = v.norm();
  return norm == 0 ? fallback : Vec3<double>(v / norm);
}

}  // namespace

bool is_partial_projective_constraint(std::string_view type) {
  return type == "PartialFixedProjectiveConstraint" || type == "FixedPlaneProjectiveConstraint" ||
         type == "PlaneProjectiveConstraint" || type == "LineProjectiveConstraint" ||
         type == "AffineMovementProjectiveConstraint";
}

void add_projective_constraint(SceneData& data, Component& c, MechanicalSystem<double>& system) {
  const std::string_view type = c.type();
  const Index size = system.size();
  if (type == "PartialFixedProjectiveConstraint") {
    // The held axes' components of every increment are zeroed; with projectVelocity, those of
    // the velocity after each step too.
    const auto indices = constrained_points(data, c, size, data.boolean(c, "fixAll", false), {0});
    const Numbers& axes = data.data(c, "fixedDirections");
    if (axes.size() != 3) throw make_error(c.where(), ": fixedDirections needs 3 values (0 or 1)");
    Mat3<double> free = Mat3<double>::Identity();
    for (int a = 0; a < 3; ++a) {
      if (axes[static_cast<std::size_t>(a)] != 0) free(a, a) = 0;
    }
    const bool velocity = data.boolean(c, "projectVelocity", false);
    for (Index i : indices) {
      system.projections.push_back({i, free});
      if (velocity) system.placements.push_back({i, Mat3<double>::Identity(), Vec3<double>::Zero(), free});
    }
    return;
  }
  if (type == "FixedPlaneProjectiveConstraint") {
    // dx <- dx - d (d . dx) with the direction as given; SOFA leaves positions and velocities alone.
    const Vec3<double> d = data.vec3(c, "direction", {0, 0, 0});
    auto indices = constrained_points(data, c, size, false, {});
    const double dmin = data.real(c, "dmin", 0), dmax = data.real(c, "dmax", 0);
    if (dmin != dmax) {
      for (Index i = 0; i < size; ++i) {
        const double along = system.state.position[static_cast<std::size_t>(i)].dot(d);
        if (along > dmin && along < dmax) indices.push_back(i);
      }
    }
    const Mat3<double> projector = Mat3<double>::Identity() - d * d.transpose();
    for (Index i : indices) system.projections.push_back({i, projector});
    return;
  }
  if (type == "AffineMovementProjectiveConstraint") {
    // The points go from where they start to rotation x + translation between the two times;
    // SOFA's rotation has no default (a zero matrix) and its times default to 0 and 20.
    const auto indices = constrained_points(data, c, size, false, {});
    const Numbers& r = data.data(c, "rotation");
    if (!r.empty() && r.size() != 9) throw make_error(c.where(), ": rotation needs 9 numbers (a 3x3 matrix, row by row)");
    Mat3<double> rotation = Mat3<double>::Zero();
    for (std::size_t k = 0; k < r.size(); ++k) rotation(static_cast<Index>(k / 3), static_cast<Index>(k % 3)) = r[k];
    const Vec3<double> translation = data.vec3(c, "translation", {0, 0, 0});
    const double begin = data.real(c, "beginConstraintTime", 0), end = data.real(c, "endConstraintTime", 20);
    for (Index i : indices) {
      const Vec3<double>& start = system.state.position[static_cast<std::size_t>(i)];
      system.projections.push_back({i, Mat3<double>::Zero()});
      system.motions.push_back({i, start, rotation * start + translation, begin, end});
    }
    return;
  }
  // Plane and line: increments and velocities projected, positions projected after each step.
  const bool plane = type == "PlaneProjectiveConstraint";
  const auto indices = constrained_points(data, c, size, false, {});
  const Vec3<double> origin = data.vec3(c, "origin", {0, 0, 0});
  Mat3<double> projector;
  if (plane) {
    const Vec3<double> n = unit_or(data.vec3(c, "normal", {0, 0, 0}), Vec3<double>::Zero());
    projector = Mat3<double>::Identity() - n * n.transpose();
  } else {
    const Vec3<double> d = unit_or(data.vec3(c, "direction", {0, 0, 0}), Vec3<double>::UnitX());
    projector = d * d.transpose();
  }
  for (Index i : indices) {
    system.projections.push_back({i, projector});
    system.placements.push_back({i, projector, origin, projector});
  }
}

void add_attach_constraint(SceneData& data, Component& c, const std::vector<Component*>& states,
                           const std::vector<Index>& offsets, const std::vector<Index>& sizes,
                           MechanicalSystem<double>& system) {
  // Which of `states` a link designates; without the link, the nearest state at or above c (SOFA's
  // context state).
  auto object = [&](const char* name) -> std::size_t {
    const Component* state = nullptr;
    if (c.has(name)) {
      state = &data.resolve_state(*c.node, c.object->attributes.at(name), c);
    } else {
      for (const GraphNode* scope = c.node; scope && !state; scope = scope->parent) {
        for (const Component* s : states) {
          if (s->node == scope) state = s;
        }
      }
      if (!state) throw make_error(c.where(), ": ", name, " is not given and no MechanicalObject is at or above node ", c.node->path);
    }
    for (std::size_t k = 0; k < states.size(); ++k) {
      if (states[k] == state) return k;
    }
    throw make_error(c.where(), ": ", name, " ", state->where(), " is not integrated by the ODE solver of this constraint's objects");
  };
  const std::size_t first = object("object1"), second = object("object2");
  const auto indices1 = data.indices(c, "indices1"), indices2 = data.indices(c, "indices2");
  if (indices1.size() != indices2.size()) {
    throw make_error(c.where(), ": indices1 has ", indices1.size(), " points, indices2 ", indices2.size(), " (one per pair)");
  }
  const Numbers& factors = data.data(c, "constraintFactor");
  if (!factors.empty() && factors.size() != indices2.size()) {
    throw make_error(c.where(), ": constraintFactor has ", factors.size(), " values for ", indices2.size(), " pairs");
  }
  if (data.real(c, "minDistance", -1) != -1) {
    throw make_error(c.where(), ": minDistance (releasing pairs that drift apart) is not supported; only -1");
  }
  if (c.has("lastDir") && data.vec3(c, "lastDir", {0, 0, 0}).norm() > 1e-10) {
    throw make_error(c.where(), ": lastDir and lastPos (releasing points past a plane) are not supported");
  }
  const bool two_way = data.boolean(c, "twoWay", false);
  const double position = data.real(c, "positionFactor", 1), velocity = data.real(c, "velocityFactor", 1),
               response = data.real(c, "responseFactor", 1);
  auto point = [&](std::size_t object_index, Index i, const char* list) {
    if (i < 0 || i >= sizes[object_index]) {
      throw make_error(c.where(), ": ", list, " index ", i, " out of range [0, ", sizes[object_index], ")");
    }
    return offsets[object_index] + i;
  };
  for (std::size_t k = 0; k < indices1.size(); ++k) {
    const double factor = factors.empty() ? 1.0 : factors[k];
    system.couplings.push_back({point(first, indices1[k], "indices1"), point(second, indices2[k], "indices2"), two_way,
                                0.5 * response * factor, 0.5 * position * factor, 0.5 * velocity * factor});
  }
}

}  // namespace fastcorot::scene_detail
