// SoftRobots' constraints: their entries in the component table and how a scene's attributes make them.
#include "softrobots_builder.h"

#include "component_families.h"
#include "fastcorot/core/error.h"
#include "fastcorot/softrobots/cable_constraint.h"
#include "fastcorot/softrobots/position_constraint.h"
#include "fastcorot/softrobots/surface_pressure_constraint.h"
#include "fastcorot/softrobots/unilateral_plane_constraint.h"
#include "index_tuples.h"

#include <algorithm>
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
      {"SurfacePressureConstraint", "lagrangian",
       "SoftRobots' cavity: triangles and quads of the node's state (a mapped state on a deformable body) bounding a volume, as one "
       "Lagrangian row (the area vectors shared among their vertices) that imposes its pressure (valueType pressure, an impulse "
       "λ = pressure × dt) or its volume growth; outputs cavityVolume, volumeGrowth (as of the step's start, as SoftRobots) and "
       "pressure (λ). Under a FreeMotionAnimationLoop.",
       {{"triangles", "indices", "", "the surface's triangles (with quads empty too: the node's topology's)"},
        {"quads", "indices", "", "the surface's quads, each as two triangles for the volume"},
        {"flipNormal", "bool", "false", "the surface's normals face into the cavity"},
        {"value", "reals", "0", "the commands; value[valueIndex] is imposed"},
        {"valueIndex", "int", "0", "which command"},
        {"valueType", "string", "pressure", "pressure (an impulse, pressure × dt) or volumeGrowth; also 0 or 1"},
        {"maxPressure", "real", "", "upper bound of λ (unset: none)"},
        {"minPressure", "real", "", "lower bound of λ (unset: none)"},
        {"maxPressureVariation", "real", "", "largest change of the commanded pressure from the current one per step (unset: none)"},
        {"maxVolumeGrowth", "real", "", "largest growth (unset: none)"},
        {"minVolumeGrowth", "real", "", "smallest growth (unset: none; in pressure mode it has no effect, as in SoftRobots)"},
        {"maxVolumeGrowthVariation", "real", "", "largest change of the commanded growth per step (unset: none)"},
        {"initialCavityVolume", "real", "", "output: the volume as the scene is built"},
        {"cavityVolume", "real", "", "output: the volume at the last step's start"},
        {"volumeGrowth", "real", "", "output: cavityVolume - initialCavityVolume"},
        {"pressure", "real", "", "output: the last impulse λ (pressure × dt)"},
        {"eqPressure", "real", "0", "accepted (inverse models only)"},
        {"eqVolumeGrowth", "real", "0", "accepted (inverse models only)"},
        {"drawPressure", "bool", "false", "accepted (drawing)"},
        {"drawScale", "real", "0.1", "accepted (drawing)"},
        {"visualization", "bool", "false", "accepted (SoftRobots' older drawPressure)"},
        {"showVisuScale", "real", "0.1", "accepted (SoftRobots' older drawScale)"},
        {"endTime", "real", "-1", "accepted (-1: always active)"}}},
      {"PositionConstraint", "lagrangian",
       "SoftRobots' position actuator: points of the node's state moved along one direction from where they were at init, one "
       "Lagrangian row per point imposing the displacement (valueType displacement; SoftRobots drops its force bounds there) or "
       "the impulse λ = force × dt (valueType force); output force (λ of the first row). One direction only (SoftRobots lines "
       "up one resolution per point). Under a FreeMotionAnimationLoop.",
       {{"indices", "indices", "0", "the points moved"},
        {"directions", "vec3s", "1 0 0 0 1 0 0 0 1", "three directions (normalised)"},
        {"useDirections", "reals", "1 1 1", "which of the three directions act (1 or 0 each): exactly one"},
        {"weight", "reals", "1 1 1", "a factor on each direction's row"},
        {"value", "reals", "0", "the commands; value[valueIndex] is imposed"},
        {"valueIndex", "int", "0", "which command"},
        {"valueType", "string", "displacement", "displacement or force (the impulse); also 0 or 1"},
        {"maxForce", "real", "", "force mode: upper bound of the command (unset: none)"},
        {"minForce", "real", "", "force mode: lower bound of the command (unset: none)"},
        {"maxPositiveDisp", "real", "", "largest displacement (unset: none)"},
        {"maxNegativeDisp", "real", "", "largest displacement backwards (unset: none)"},
        {"force", "real", "", "output: λ of the first row (force × dt)"},
        {"displacement", "real", "0", "output: stays 0, as SoftRobots never sets it"},
        {"delta", "vec3s", "", "accepted (inverse models only)"}}},
      {"UnilateralPlaneConstraint", "lagrangian",
       "SoftRobots' unilateral plane: point indices[0] of the node's state kept on the side of the plane through points indices[1..3] "
       "its normal (p2 - p1) × (p3 - p1) points to, by one unilateral row; the row uses the normal as it is, the gap its unit "
       "vector (SoftRobots' formula). Under a FreeMotionAnimationLoop.",
       {{"indices", "indices", "", "four points: the one kept, then three of the plane"},
        {"flipNormal", "bool", "false", "the point is kept on the other side"}}},
  };
}

bool is_softrobots_constraint(std::string_view type) {
  return type == "CableConstraint" || type == "SurfacePressureConstraint" || type == "UnilateralPlaneConstraint" ||
         type == "PositionConstraint";
}

namespace {

std::optional<double> optional_real(SceneData& data, Component& c, const char* name) {
  if (!c.has(name)) return std::nullopt;
  return data.real(c, name, 0.0);
}

// SoftRobots' value/valueIndex: an empty value is one zero; a valueIndex beyond it is 0, warned.
void read_command(SceneData& data, Component& c, std::vector<double>& value, std::size_t& value_index) {
  const Numbers& given = data.data(c, "value");
  value.assign(given.begin(), given.end());
  if (value.empty()) value = {0.0};
  const int index = data.whole_number(c, "valueIndex", 0);
  if (index < 0) throw make_error("valueIndex = ", index, ": must be >= 0");
  value_index = static_cast<std::size_t>(index);
  if (value_index >= value.size()) {
    data.warn(c.where() + ": valueIndex " + std::to_string(index) + " is beyond value's " + std::to_string(value.size()) +
              " entries: 0 is used, as SoftRobots does");
    value_index = 0;
  }
}

// A SoftRobots valueType (SOFA's OptionsGroup of two items, given by name or index): whether it
// is the second item; an unknown one keeps the first, warned, as the OptionsGroup keeps its default.
bool second_option(SceneData& data, Component& c, const char* first, const char* second) {
  const std::string type = data.text(c, "valueType", first);
  if (type == second || type == "1") return true;
  if (type != first && type != "0") {
    data.warn(c.where() + ": valueType = \"" + type + "\" is not " + first + " or " + second + ": " + first +
              " is used, as SOFA does");
  }
  return false;
}

// valueType displacement or force and the bounds CableConstraint and PositionConstraint share.
template <class Parameters>
void read_displacement_or_force(SceneData& data, Component& c, Parameters& p) {
  using ValueType = decltype(p.value_type);
  p.value_type = second_option(data, c, "displacement", "force") ? ValueType::force : ValueType::displacement;
  p.max_force = optional_real(data, c, "maxForce");
  p.min_force = optional_real(data, c, "minForce");
  p.max_positive_displacement = optional_real(data, c, "maxPositiveDisp");
  p.max_negative_displacement = optional_real(data, c, "maxNegativeDisp");
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
  read_command(data, c, p.value, p.value_index);
  read_displacement_or_force(data, c, p);
  p.max_displacement_variation = optional_real(data, c, "maxDispVariation");
  return std::make_unique<CableConstraint<double>>(c.where(), std::move(points), initial_positions, std::move(p));
}

std::unique_ptr<LagrangianConstraint<double>> build_cavity(SceneData& data, Component& c, ConstraintPoints<double> points,
                                                           std::span<const Vec3<double>> initial_positions) {
  typename SurfacePressureConstraint<double>::Parameters p;
  p.triangles = index_tuples<3>(data, c, "triangles");
  p.quads = index_tuples<4>(data, c, "quads");
  if (p.triangles.empty() && p.quads.empty()) {
    // SoftRobots takes the context topology's triangles and quads.
    Component* topology = data.topology_of(*c.node);
    if (topology == nullptr) throw make_error("no triangles or quads given and no topology in its node or above");
    p.triangles = index_tuples<3>(data, *topology, "triangles");
    p.quads = index_tuples<4>(data, *topology, "quads");
    if (p.triangles.empty() && p.quads.empty()) {
      throw make_error("no triangles or quads given, and its topology ", topology->where(), " has none");
    }
  }
  p.flip_normal = data.boolean(c, "flipNormal", false);
  read_command(data, c, p.value, p.value_index);
  p.value_type = second_option(data, c, "pressure", "volumeGrowth") ? SurfacePressureConstraint<double>::ValueType::volume_growth
                                                                   : SurfacePressureConstraint<double>::ValueType::pressure;
  p.max_pressure = optional_real(data, c, "maxPressure");
  p.min_pressure = optional_real(data, c, "minPressure");
  p.max_pressure_variation = optional_real(data, c, "maxPressureVariation");
  p.max_volume_growth = optional_real(data, c, "maxVolumeGrowth");
  p.min_volume_growth = optional_real(data, c, "minVolumeGrowth");
  p.max_volume_growth_variation = optional_real(data, c, "maxVolumeGrowthVariation");
  return std::make_unique<SurfacePressureConstraint<double>>(c.where(), std::move(points), initial_positions, std::move(p));
}

std::unique_ptr<LagrangianConstraint<double>> build_position(SceneData& data, Component& c, ConstraintPoints<double> points,
                                                             std::span<const Vec3<double>> initial_positions) {
  typename PositionConstraint<double>::Parameters p;
  if (c.has("indices")) {
    p.indices = data.indices(c, "indices");
  } else {
    data.warn(c.where() + ": no indices: point 0 is moved, as SoftRobots does");
  }
  if (c.has("directions")) {
    const auto directions = data.points(c, "directions");
    if (directions.size() != 3) throw make_error("directions: ", directions.size(), " given; three are needed");
    std::copy(directions.begin(), directions.end(), p.directions.begin());
  }
  if (c.has("useDirections")) {
    const Numbers& use = data.data(c, "useDirections");
    if (use.size() != 3) throw make_error("useDirections: ", use.size(), " values given; three are needed (1 or 0 each)");
    for (std::size_t j = 0; j < 3; ++j) p.use_directions[j] = use[j] != 0;
  }
  if (c.has("weight")) {
    const Numbers& weight = data.data(c, "weight");
    if (weight.empty()) throw make_error("weight is empty");
    for (std::size_t j = 0; j < 3; ++j) p.weight[j] = weight.size() == 3 ? weight[j] : weight[0];  // SoftRobots' resize rule
  }
  read_command(data, c, p.value, p.value_index);
  read_displacement_or_force(data, c, p);
  return std::make_unique<PositionConstraint<double>>(c.where(), std::move(points), initial_positions, std::move(p));
}

}  // namespace

std::unique_ptr<LagrangianConstraint<double>> build_softrobots_constraint(SceneData& data, Component& c, ConstraintPoints<double> points,
                                                                          std::span<const Vec3<double>> initial_positions) {
  const std::string templ = data.text(c, "template", "Vec3d");
  if (templ.rfind("Vec2", 0) == 0) throw make_error("template = \"", templ, "\": ", c.type(), " is simulated on Vec3 states only");
  if (c.type() == "SurfacePressureConstraint") return build_cavity(data, c, std::move(points), initial_positions);
  if (c.type() == "PositionConstraint") return build_position(data, c, std::move(points), initial_positions);
  if (c.type() == "UnilateralPlaneConstraint") {
    const std::vector<Index> indices = data.indices(c, "indices");
    if (indices.size() != 4) throw make_error("indices: ", indices.size(), " given; four are needed (the point, then three of the plane)");
    typename UnilateralPlaneConstraint<double>::Parameters p;
    std::copy(indices.begin(), indices.end(), p.indices.begin());
    p.flip_normal = data.boolean(c, "flipNormal", false);
    return std::make_unique<UnilateralPlaneConstraint<double>>(c.where(), std::move(points), p);
  }
  return build_cable(data, c, std::move(points), initial_positions);
}

}  // namespace fastcorot::scene_detail
