// SOFA's TransformEngine (Sofa.Component.Engine.Transform, TransformEngine.inl, master 2a278d891f):
// output_position = input_position moved by, in this order, a scale, a rotation given as Euler
// angles in degrees, a rotation given as a quaternion and a translation. Each step is applied only
// when it differs from the identity by SOFA's comparisons (a vector differs when one component is
// at least 1e-6 away; a quaternion when one component is more than 1e-6 away). With `inverse` the
// steps run in the opposite order, each inverted (1/scale, the conjugate of the normalised
// quaternion, -translation). The Euler angles become a quaternion as SOFA's
// Quat::createQuaterFromEuler does in its default order (R = Rz Ry Rx), and points are turned by
// SOFA's quaternion rotation formula, so that the numbers are SOFA's to the last bit.
//
// Templates: Vec1, Vec2, Vec3 (coordinates padded with zeros to 3, moved, cut back, as SOFA's
// DataTypes::get/set do) and Rigid3 (x y z qx qy qz qw: the centre moves, and a rotation q turns the
// orientation to q * orientation); Rigid2 is refused.
#include "engine_data.h"

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

using Triple = std::array<double, 3>;

struct Quaternion {
  double x = 0, y = 0, z = 0, w = 1;
};

constexpr double kVectorThreshold = 1e-6;      // SOFA's EQUALITY_THRESHOLD (type::Vec ==)
constexpr double kQuaternionThreshold = 1e-6;  // SOFA's quaternionEqualityThreshold (type::Quat ==)

bool differs(const Triple& a, const Triple& b) {
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(a[i] - b[i]) < kVectorThreshold)) return true;
  }
  return false;
}

bool differs_from_identity(const Quaternion& q) {
  return std::abs(q.x) > kQuaternionThreshold || std::abs(q.y) > kQuaternionThreshold ||
         std::abs(q.z) > kQuaternionThreshold || std::abs(q.w - 1) > kQuaternionThreshold;
}

// SOFA's createQuaterFromEuler, order ZYX (its default): the rotation Rz(c) Ry(b) Rx(a) of the
// angles (a, b, c) in radians.
Quaternion from_euler(const Triple& radians) {
  const double c1 = std::cos(radians[0] / 2), c2 = std::cos(radians[1] / 2), c3 = std::cos(radians[2] / 2);
  const double s1 = std::sin(radians[0] / 2), s2 = std::sin(radians[1] / 2), s3 = std::sin(radians[2] / 2);
  return {s1 * c2 * c3 - c1 * s2 * s3, c1 * s2 * c3 + s1 * c2 * s3, c1 * c2 * s3 - s1 * s2 * c3,
          c1 * c2 * c3 + s1 * s2 * s3};
}

// SOFA's Quat::inverse: the conjugate divided by the norm (all zero for a zero quaternion).
Quaternion inverted(const Quaternion& q) {
  double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (norm == 0) return {0, 0, 0, 0};
  norm = 1 / norm;
  return {-q.x * norm, -q.y * norm, -q.z * norm, q.w * norm};
}

Triple cross(const Triple& a, const Triple& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// SOFA's Quat::rotate: v + w t + q × t with t = 2 (q × v) (the quaternion is not normalised).
Triple rotate(const Quaternion& q, const Triple& v) {
  const Triple axis = {q.x, q.y, q.z};
  Triple t = cross(axis, v);
  for (double& e : t) e *= 2;
  const Triple u = cross(axis, t);
  return {v[0] + q.w * t[0] + u[0], v[1] + q.w * t[1] + u[1], v[2] + q.w * t[2] + u[2]};
}

// SOFA's Quat product a * b (b's rotation first).
Quaternion product(const Quaternion& a, const Quaternion& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y + a.y * b.w + a.z * b.x - a.x * b.z,
          a.w * b.z + a.z * b.w + a.x * b.y - a.y * b.x, a.w * b.w - (a.x * b.x + a.y * b.y + a.z * b.z)};
}

// One step of the transformation, as SOFA's TransformOperation.
struct Step {
  enum class Kind { scale, rotation, translation } kind;
  Triple vector{};  // the scale factors or the translation
  Quaternion turn{};
};

// The coordinates of one item: its position (padded to 3) and, for Rigid3, its orientation.
struct Item {
  Triple position{};
  Quaternion orientation{};
};

void apply(const Step& step, Item& item, bool rigid) {
  switch (step.kind) {
    case Step::Kind::scale:
      for (int i = 0; i < 3; ++i) item.position[i] *= step.vector[i];
      break;
    case Step::Kind::translation:
      for (int i = 0; i < 3; ++i) item.position[i] += step.vector[i];
      break;
    case Step::Kind::rotation:
      item.position = rotate(step.turn, item.position);
      if (rigid) item.orientation = product(step.turn, item.orientation);
      break;
  }
}

Triple triple(const Vec3<double>& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

Numbers transform_engine(SceneData& scene, Component& c, const std::string& name) {
  if (name != "output_position") return {};
  // The coordinates per item: SOFA's DataTypes of the template (Vec3 by default).
  const std::string tmpl = scene.text(c, "template", "Vec3d");
  std::size_t dimension = 3;
  bool rigid = false;
  if (tmpl == "Vec1d" || tmpl == "Vec1f" || tmpl == "Vec1") dimension = 1;
  else if (tmpl == "Vec2d" || tmpl == "Vec2f" || tmpl == "Vec2") dimension = 2;
  else if (is_rigid_template(tmpl)) rigid = true;
  else if (tmpl != "Vec3d" && tmpl != "Vec3f" && tmpl != "Vec3") {
    throw make_error(c.where(), ": template \"", tmpl, "\" is not supported (Vec1, Vec2, Vec3 or Rigid3)");
  }
  const std::size_t width = rigid ? 7 : dimension;

  const bool inverse = scene.boolean(c, "inverse", false);
  const Triple scale = triple(scene.vec3(c, "scale", {1, 1, 1}));
  const Triple rotation = triple(scene.vec3(c, "rotation", {0, 0, 0}));
  const Triple translation = triple(scene.vec3(c, "translation", {0, 0, 0}));
  Quaternion quaternion;
  if (c.has("quaternion")) {
    const Numbers& q = scene.data(c, "quaternion");
    if (q.size() != 4) throw make_error(c.where(), ": quaternion needs 4 numbers (qx qy qz qw), got ", q.size());
    quaternion = {q[0], q[1], q[2], q[3]};
  }

  // The steps in SOFA's order; with inverse each is inverted and put first (SOFA's push_front).
  std::vector<Step> steps;
  const auto add = [&](Step step) {
    if (inverse) steps.insert(steps.begin(), step);
    else steps.push_back(step);
  };
  if (differs(scale, {1, 1, 1})) {
    Step step{Step::Kind::scale, scale, {}};
    if (inverse) {
      for (double& s : step.vector) {
        if (s == 0) throw make_error(c.where(), ": inverse with a zero scale factor (scale = ", scale[0], " ", scale[1], " ", scale[2], ")");
        s = 1.0 / s;
      }
    }
    add(step);
  }
  if (differs(rotation, {0, 0, 0})) {
    const double to_radians = std::numbers::pi / 180.0;
    const Quaternion q = from_euler({rotation[0] * to_radians, rotation[1] * to_radians, rotation[2] * to_radians});
    add({Step::Kind::rotation, {}, inverse ? inverted(q) : q});
  }
  if (differs_from_identity(quaternion)) add({Step::Kind::rotation, {}, inverse ? inverted(quaternion) : quaternion});
  if (differs(translation, {0, 0, 0})) {
    add({Step::Kind::translation,
         inverse ? Triple{-translation[0], -translation[1], -translation[2]} : translation, {}});
  }

  const Numbers& input = scene.data(c, "input_position");
  if (input.size() % width != 0) {
    throw make_error(c.where(), ": input_position of a ", tmpl, " engine needs ", width, " numbers per ",
                     rigid ? "rigid (x y z qx qy qz qw)" : "point", ", got ", input.size(), " numbers");
  }
  Numbers output = input;
  for (std::size_t k = 0; k < output.size(); k += width) {
    Item item;
    const std::size_t coordinates = rigid ? 3 : dimension;
    for (std::size_t i = 0; i < coordinates; ++i) item.position[i] = output[k + i];
    if (rigid) item.orientation = {output[k + 3], output[k + 4], output[k + 5], output[k + 6]};
    for (const Step& step : steps) apply(step, item, rigid);
    for (std::size_t i = 0; i < coordinates; ++i) output[k + i] = item.position[i];
    if (rigid) {
      output[k + 3] = item.orientation.x, output[k + 4] = item.orientation.y;
      output[k + 5] = item.orientation.z, output[k + 6] = item.orientation.w;
    }
  }
  return output;
}

}  // namespace fastcorot::scene_detail
