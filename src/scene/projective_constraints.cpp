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

}  // namespace fastcorot::scene_detail
