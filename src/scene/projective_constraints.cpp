#include "projective_constraints.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <string>

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

// SOFA's PatchTestMovementProjectiveConstraint corners of `points`: four, or eight when the points
// do not all share one z. Each is the last point that passes SOFA's test against the corner so
// far (the tests are SOFA's as written, "or" of per-axis comparisons, corners 4 and 6 compared in
// z with corners 0 and 2, corner 7 tried only when 5 is not taken).
std::vector<Vec3<double>> patch_test_corners(const std::vector<Vec3<double>>& points) {
  if (points.empty()) return {};
  bool three_d = false;
  for (const auto& p : points) three_d = three_d || p.z() != points.front().z();
  std::vector<Vec3<double>> k(8, points.front());
  for (const auto& p : points) {
    if (p.x() < k[0].x() || p.y() < k[0].y() || p.z() < k[0].z()) k[0] = p;
    if (p.x() > k[2].x() || p.y() > k[2].y() || p.z() < k[2].z()) k[2] = p;
    if (p.y() < k[1].y() || p.x() > k[1].x() || p.z() < k[1].z()) k[1] = p;
    if (p.x() < k[3].x() || p.y() > k[3].y() || p.z() < k[3].z()) k[3] = p;
    if (three_d && (p.x() < k[4].x() || p.y() < k[4].y() || p.z() > k[0].z())) k[4] = p;
    if (three_d && (p.x() > k[6].x() || p.y() > k[6].y() || p.z() > k[2].z())) k[6] = p;
    if (three_d && (p.y() < k[5].y() || p.x() > k[5].x() || p.z() > k[5].z())) {
      k[5] = p;
    } else if (three_d && (p.x() < k[7].x() || p.y() > k[7].y() || p.z() > k[7].z())) {
      k[7] = p;
    }
  }
  if (!three_d) k.resize(4);
  return k;
}

// The movement at point p: SOFA's weights alpha, beta (and gamma) from corners 0, 1, 3 (and 4).
Vec3<double> patch_test_displacement(const std::vector<Vec3<double>>& k, const std::vector<Vec3<double>>& m,
                                     const Vec3<double>& p) {
  const double alpha = std::abs(p.x() - k[0].x()) / std::abs(k[1].x() - k[0].x());
  const double beta = std::abs(p.y() - k[0].y()) / std::abs(k[3].y() - k[0].y());
  auto face = [&](std::size_t o) {
    return Vec3<double>(m[o] * (1 - alpha) * (1 - beta) + m[o + 1] * alpha * (1 - beta) + m[o + 2] * alpha * beta +
                        m[o + 3] * (1 - alpha) * beta);
  };
  if (k.size() == 4) return face(0);
  const double gamma = std::abs(p.z() - k[0].z()) / std::abs(k[4].z() - k[0].z());
  return face(0) * (1 - gamma) + face(4) * gamma;
}

}  // namespace

LinearMovement<double> build_linear_movement(SceneData& data, Component& c, Index count, bool rigid) {
  LinearMovement<double> movement;
  for (Index i : constrained_points(data, c, count, false, {0})) {
    movement.points.push_back(rigid ? 2 * i : i);
    if (rigid) movement.rigids.push_back(i);
  }
  const Numbers& times = data.data(c, "keyTimes");
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k])) throw make_error(c.where(), ": keyTimes: time ", k, " is not finite");
    if (k > 0 && times[k] < times[k - 1]) {
      throw make_error(c.where(), ": keyTimes: ", times[k], " after ", times[k - 1], ": key times must be in order (SOFA assumes it)");
    }
  }
  movement.key_times.assign(times.begin(), times.end());
  const std::size_t width = rigid ? 6 : 3;
  // SOFA's default: one key at time 0 with no movement.
  const Numbers values = c.has("movements") || times.size() != 1 ? data.data(c, "movements") : Numbers(width, 0.0);
  if (values.size() != width * times.size()) {
    throw make_error(c.where(), ": movements has ", values.size(), " numbers: ", times.size(), " key times need ", width * times.size(),
                     " (", width, " per key", rigid ? ": the centre's movement and Euler angles" : "", ")");
  }
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) throw make_error(c.where(), ": movements: number ", k, " is not finite");
  }
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double* v = values.data() + width * k;
    movement.key_movements.emplace_back(v[0], v[1], v[2]);
    if (rigid) movement.key_angles.emplace_back(v[3], v[4], v[5]);
  }
  movement.relative = data.boolean(c, "relativeMovements", true);
  return movement;
}

bool is_partial_projective_constraint(std::string_view type) {
  return type == "PartialFixedProjectiveConstraint" || type == "FixedPlaneProjectiveConstraint" ||
         type == "PlaneProjectiveConstraint" || type == "LineProjectiveConstraint" ||
         type == "AffineMovementProjectiveConstraint" || type == "PatchTestMovementProjectiveConstraint" ||
         type == "PointProjectiveConstraint";
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
  if (type == "PointProjectiveConstraint") {
    // Increments and velocities zero, positions set to `point` after each step (SOFA's default
    // indices: point 0).
    const auto indices = constrained_points(data, c, size, data.boolean(c, "fixAll", false), {0});
    const Vec3<double> point = data.vec3(c, "point", {0, 0, 0});
    for (Index i : indices) {
      system.projections.push_back({i, Mat3<double>::Zero()});
      system.placements.push_back({i, Mat3<double>::Zero(), point, Mat3<double>::Zero()});
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
  if (type == "PatchTestMovementProjectiveConstraint") {
    // Each point goes from where it starts to start + the corners' movements interpolated at it,
    // with SOFA's corners of the constrained points and its (bi/tri)linear weights.
    const auto indices = constrained_points(data, c, size, false, {});
    const auto corners = patch_test_corners(data.points(c, "constrainedPoints"));
    // Read as SOFA reads a list of 3D vectors: whole triples, an incomplete last one dropped.
    const Numbers& numbers = data.data(c, "cornerMovements");
    std::vector<Vec3<double>> movements;
    for (std::size_t k = 0; k + 3 <= numbers.size(); k += 3) movements.emplace_back(numbers[k], numbers[k + 1], numbers[k + 2]);
    if (numbers.size() % 3 != 0) {
      data.warn(c.where() + ": cornerMovements has " + std::to_string(numbers.size()) +
                " numbers, not a multiple of 3: the incomplete last movement is dropped (as SOFA reads it)");
    }
    if (corners.empty()) {
      if (!indices.empty()) throw make_error(c.where(), ": constrainedPoints is empty: no corners to move the points by");
      return;
    }
    if (movements.size() < corners.size()) {
      // SOFA reads past its list here (undefined): the missing movements are taken as zero.
      data.warn(c.where() + ": cornerMovements has " + std::to_string(movements.size()) + " movements (3 numbers each) for " +
                std::to_string(corners.size()) + " corners: the missing ones are taken as zero");
      movements.resize(corners.size(), Vec3<double>::Zero());
    }
    const double begin = data.real(c, "beginConstraintTime", 0), end = data.real(c, "endConstraintTime", 20);
    for (Index i : indices) {
      const Vec3<double>& start = system.state.position[static_cast<std::size_t>(i)];
      system.projections.push_back({i, Mat3<double>::Zero()});
      system.motions.push_back({i, start, start + patch_test_displacement(corners, movements, start), begin, end});
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

void add_fixed_constraint(SceneData& data, Component& c, MechanicalSystem<double>& system) {
  std::vector<Index> indices;
  if (data.boolean(c, "fixAll", false)) {
    for (Index i = 0; i < system.size(); ++i) indices.push_back(i);
  } else {
    indices = c.has("indices") ? data.indices(c, "indices") : std::vector<Index>{0};  // SOFA's default
  }
  for (Index i : indices) {
    if (i >= system.size()) throw make_error(c.where(), ": index ", i, " out of range [0, ", system.size(), ")");
  }
  system.fixed.insert(system.fixed.end(), indices.begin(), indices.end());
  if (data.boolean(c, "activate_projectVelocity", false)) {
    system.zero_velocity.insert(system.zero_velocity.end(), indices.begin(), indices.end());
  }
}

}  // namespace fastcorot::scene_detail
