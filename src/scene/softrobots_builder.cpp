// SoftRobots' constraints: their entries in the component table and how a scene's attributes make them.
#include "softrobots_builder.h"

#include "component_families.h"
#include "fastcorot/core/error.h"
#include "fastcorot/softrobots/cable_constraint.h"

#include <optional>

namespace fastcorot::scene_detail {

std::vector<ComponentSpec> softrobots_components() {
  return {
      {"CableConstraint", "lagrangian",
       "SoftRobots' cable: points of the node's state (a mapped state on a deformable body) joined from a pull point, as one Lagrangian "
       "row that imposes the cable's shortening (valueType displacement) or its impulse λ = force × dt (valueType force); outputs "
       "cableLength, displacement (L0 - cableLength, as of the step's start, as SoftRobots) and force (λ). Under a "
       "FreeMotionAnimationLoop.",
       {{"indices", "indices", "", "the cable's points, from the pulled one on (empty: point 0)"},
        {"pullPoint", "vec3", "0 0 0", "the fixed point the cable is pulled from"},
        {"hasPullPoint", "bool", "true", "false: the first index is the pull point, following the body"},
        {"cableInitialLength", "real", "", "L0 (default: the length at the state's rest positions)"},
        {"value", "reals", "0", "the commands; value[valueIndex] is imposed"},
        {"valueIndex", "int", "0", "which command"},
        {"valueType", "string", "displacement", "displacement (the shortening since L0) or force (the impulse); also 0 or 1"},
        {"maxForce", "real", "", "upper bound of λ (unset: none)"},
        {"minForce", "real", "", "lower bound of λ (unset: none: the cable can push)"},
        {"maxPositiveDisp", "real", "", "largest shortening (unset: none)"},
        {"maxNegativeDisp", "real", "", "largest lengthening (unset: none)"},
        {"maxDispVariation", "real", "", "largest change of the commanded displacement from the current one per step (unset: none)"},
        {"method", "string", "point", "point (the force on the cable's points); sphere and geodesic are not supported"},
        {"cableLength", "real", "", "output: the cable's length at the last step's start"},
        {"displacement", "real", "", "output: cableInitialLength - cableLength"},
        {"force", "real", "", "output: the last impulse λ (force × dt)"},
        {"eqForce", "real", "0", "accepted (inverse models only)"},
        {"eqDisp", "real", "0", "accepted (inverse models only)"},
        {"centers", "vec3s", "", "accepted with method sphere or geodesic only"},
        {"radii", "reals", "", "accepted with method sphere or geodesic only"},
        {"surfaceTopology", "link", "", "accepted with method sphere or geodesic only"},
        {"endTime", "real", "-1", "accepted (-1: always active)"},
        {"color", "string", "0.4 0.4 0.4 1", "accepted (drawing)"}}},
  };
}

bool is_softrobots_constraint(std::string_view type) { return type == "CableConstraint"; }

namespace {

std::optional<double> optional_real(SceneData& data, Component& c, const char* name) {
  if (!c.has(name)) return std::nullopt;
  return data.real(c, name, 0.0);
}

std::unique_ptr<LagrangianConstraint<double>> build_cable(SceneData& data, Component& c, ConstraintPoints<double> points,
                                                          std::span<const Vec3<double>> initial_positions) {
  const std::string method = data.text(c, "method", "point");
  if (method != "point" && method != "0") {
    throw make_error("method = \"", method, "\": only the point method is simulated (sphere and geodesic spread the force over a surface)");
  }
  typename CableConstraint<double>::Parameters p;
  p.indices = data.indices(c, "indices");
  if (p.indices.empty()) data.warn(c.where() + ": no indices: the cable acts on point 0, as SoftRobots does");
  p.pull_point = data.vec3(c, "pullPoint", Vec3<double>::Zero());
  p.has_pull_point = data.boolean(c, "hasPullPoint", true);
  p.initial_length = optional_real(data, c, "cableInitialLength");
  const Numbers& value = data.data(c, "value");
  p.value.assign(value.begin(), value.end());
  if (p.value.empty()) p.value = {0.0};
  const int index = data.whole_number(c, "valueIndex", 0);
  if (index < 0) throw make_error("valueIndex = ", index, ": must be >= 0");
  p.value_index = static_cast<std::size_t>(index);
  if (p.value_index >= p.value.size()) {
    data.warn(c.where() + ": valueIndex " + std::to_string(index) + " is beyond value's " + std::to_string(p.value.size()) +
              " entries: 0 is used, as SoftRobots does");
    p.value_index = 0;
  }
  const std::string type = data.text(c, "valueType", "displacement");
  if (type == "displacement" || type == "0") {
    p.value_type = CableConstraint<double>::ValueType::displacement;
  } else if (type == "force" || type == "1") {
    p.value_type = CableConstraint<double>::ValueType::force;
  } else {
    throw make_error("valueType = \"", type, "\": expected displacement or force");
  }
  p.max_force = optional_real(data, c, "maxForce");
  p.min_force = optional_real(data, c, "minForce");
  p.max_positive_displacement = optional_real(data, c, "maxPositiveDisp");
  p.max_negative_displacement = optional_real(data, c, "maxNegativeDisp");
  p.max_displacement_variation = optional_real(data, c, "maxDispVariation");
  return std::make_unique<CableConstraint<double>>(c.where(), std::move(points), initial_positions, std::move(p));
}

}  // namespace

std::unique_ptr<LagrangianConstraint<double>> build_softrobots_constraint(SceneData& data, Component& c, ConstraintPoints<double> points,
                                                                          std::span<const Vec3<double>> initial_positions) {
  const std::string templ = data.text(c, "template", "Vec3d");
  if (templ.rfind("Vec2", 0) == 0) throw make_error("template = \"", templ, "\": ", c.type(), " is simulated on Vec3 states only");
  return build_cable(data, c, std::move(points), initial_positions);
}

}  // namespace fastcorot::scene_detail
