#include "fastcorot/scene/component_table.h"

#include "fastcorot/core/error.h"
#include "component_families.h"

#include <algorithm>
#include <cctype>
#include <array>
#include <sstream>

namespace fastcorot {

namespace {

const std::vector<ComponentSpec>& table() {
  // Each family's entries from its own file (component_families.h), in this order.
  static const std::vector<ComponentSpec> components = [] {
    std::vector<ComponentSpec> all;
    for (auto family : {scene_detail::topology_components, scene_detail::visual_components,
                        scene_detail::mechanics_components, scene_detail::element_fem_components,
                        scene_detail::constraint_components, scene_detail::lagrangian_components, scene_detail::softrobots_components, scene_detail::engine_components, scene_detail::solver_components,
                        scene_detail::collision_components}) {
      for (auto& spec : family()) all.push_back(std::move(spec));
    }
    return all;
  }();
  return components;
}

constexpr std::array<std::string_view, 66> kIgnored = {
    "RequiredPlugin", "AddPluginRepository", "AddDataRepository", "AddResourceRepository", "VisualStyle", "DefaultAnimationLoop", "DefaultVisualManagerLoop",
    "CollisionPipeline", "DefaultPipeline", "BruteForceBroadPhase", "BVHNarrowPhase",
    "BruteForceDetection", "MinProximityIntersection", "LocalMinDistance", "NewProximityIntersection",
    "DiscreteIntersection", "CollisionResponse", "DefaultContactManager", "TriangleCollisionModel",
    "LineCollisionModel", "PointCollisionModel", "SphereCollisionModel",
    "VisualGrid", "OglGrid", "LineAxis", "OglSceneFrame", "TetrahedronSetTopologyModifier",
    "TetrahedronSetGeometryAlgorithms", "TriangleSetTopologyModifier",
    "TriangleSetGeometryAlgorithms", "InteractiveCamera", "LightManager", "DirectionalLight", "SpotLight",
    "PositionalLight", "BackgroundSetting", "Camera", "OglLabel", "ConstraintAttachButtonSetting",
    "AttachBodyButtonSetting", "Visual3DText", "OglShader", "OglShadowShader", "VisualMesh", "WriteState", "MeshExporter",
    "VisualModelOBJExporter", "CompareState", "ReadState", "EdgeSetTopologyModifier",
    "EdgeSetGeometryAlgorithms", "ValuesFromPositions", "NaturalOrderingMethod",
    "AMDOrderingMethod", "METISOrderingMethod", "RCMOrderingMethod", "TaskSchedulerSettings",
    "TetrahedronCollisionModel",
    "PointSetTopologyModifier", "PointSetGeometryAlgorithms", "QuadSetTopologyModifier", "QuadSetGeometryAlgorithms",
    "HexahedronSetTopologyModifier", "HexahedronSetGeometryAlgorithms", "TrailRenderer",
    "CCDTightInclusionIntersection"};

std::string join_names(std::span<const AttributeSpec> attributes) {
  std::string list;
  for (const auto& a : attributes) list += (list.empty() ? "" : ", ") + std::string(a.name);
  return list;
}

std::string supported_names() {
  std::string list;
  for (const auto& spec : table()) list += (list.empty() ? "" : ", ") + std::string(spec.name);
  return list;
}

constexpr std::array<std::string_view, 8> kCommon = {"name", "template", "tags", "printLog", "listening",
                                                     "bbox", "componentState", "src"};

}  // namespace

const ComponentSpec* find_component(std::string_view name) {
  for (const auto& spec : table()) {
    if (spec.name == name) return &spec;
    if (std::find(spec.aliases.begin(), spec.aliases.end(), name) != spec.aliases.end()) return &spec;
  }
  return nullptr;
}

std::span<const ComponentSpec> supported_components() { return table(); }

bool is_ignored_component(std::string_view name) {
  return std::find(kIgnored.begin(), kIgnored.end(), name) != kIgnored.end();
}

std::span<const std::string_view> ignored_components() { return kIgnored; }


bool is_collision_component(std::string_view name) {
  static constexpr std::array<std::string_view, 20> kCollision = {
      "CollisionPipeline", "DefaultPipeline", "BruteForceBroadPhase", "BVHNarrowPhase", "BruteForceDetection",
      "MinProximityIntersection", "LocalMinDistance", "NewProximityIntersection", "DiscreteIntersection",
      "CollisionResponse", "DefaultContactManager", "RuleBasedContactManager", "TriangleCollisionModel", "LineCollisionModel",
      "PointCollisionModel", "SphereCollisionModel", "TetrahedronCollisionModel",
      "CompositeCollisionPipeline", "SubCollisionPipeline",
      "CCDTightInclusionIntersection"};
  return std::find(kCollision.begin(), kCollision.end(), name) != kCollision.end();
}

bool is_common_attribute(std::string_view name) {
  return std::find(kCommon.begin(), kCommon.end(), name) != kCommon.end() || name.starts_with("draw") ||
         name.starts_with("show");
}

namespace {

// Edit distance between two names, letters compared without case (a typo, a swapped pair of
// letters or a different capital).
std::size_t name_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = previous[j - 1] + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

// " (did you mean 'X'?)" for the closest candidate within a third of the name's length (at least
// 2 edits), else "".
template <class Names>
std::string suggestion(std::string_view name, const Names& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const auto& candidate : candidates) {
    const std::size_t d = name_distance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(candidate);
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

}  // namespace

// SOFA components fastcorot knows it does not simulate, and why: a scene with one is refused in one
// line saying so (an unknown component's line would not say what is missing).
std::span<const std::pair<std::string_view, std::string_view>> refused_components() {
  static constexpr std::string_view kInverse =
      "inverse models (SoftRobots.Inverse) are not simulated: they need a QP solver over the actuators' and "
      "effectors' rows (qpOASES or ProxQP in SoftRobots.Inverse, neither packaged by Debian), which fastcorot "
      "does not have yet; the direct actuators (CableConstraint, SurfacePressureConstraint) are simulated";
  static constexpr std::string_view kArticulated =
      "articulated systems (ArticulatedSystemPlugin: Vec1 joint angles driving rigid bodies) are not simulated";
  static constexpr std::string_view kBeams =
      "the BeamAdapter plugin's beams are not simulated (tetrahedra and hexahedra only)";
  static constexpr std::pair<std::string_view, std::string_view> kRefused[] = {
      {"UnilateralLagrangianConstraint", "a UnilateralLagrangianConstraint written in a scene is not simulated yet (those a FrictionContactConstraint response makes are)"},
      {"AugmentedLagrangianConstraint", "AugmentedLagrangianConstraint is not simulated yet"},
      {"SparseGridTopology", "sparse grids (hexahedral FEM) are not simulated"},
      {"TriangularFEMForceField", "triangular FEM is not simulated (tetrahedra only)"},
      {"TriangleFEMForceField", "triangular FEM is not simulated (tetrahedra only)"},
      {"TetrahedronHyperelasticityFEMForceField", "hyperelastic FEM is not simulated (linear corotational only)"},
      {"StandardTetrahedralFEMForceField", "hyperelastic FEM is not simulated (linear corotational only)"},
      // SoftRobots.Inverse's solver and the actuators, effectors and sensors it alone resolves.
      {"QPInverseProblemSolver", kInverse},
      {"CableActuator", kInverse},
      {"CableEffector", kInverse},
      {"CableEquality", kInverse},
      {"CableSensor", kInverse},
      {"SurfacePressureActuator", kInverse},
      {"SurfacePressureEquality", kInverse},
      {"SurfacePressureSensor", kInverse},
      {"PositionEffector", kInverse},
      {"PositionEquality", kInverse},
      {"ForcePointActuator", kInverse},
      {"ForceSurfaceActuator", kInverse},
      {"JointActuator", kInverse},
      {"SlidingActuator", kInverse},
      {"YoungModulusActuator", kInverse},
      {"VolumeEffector", kInverse},
      {"BarycentricCenterEffector", kInverse},
      {"BeamRestPositionActuator", kInverse},
      // ArticulatedSystemPlugin: Vec1 joint angles mapped to rigid bodies along a kinematic chain.
      {"ArticulatedSystemMapping", kArticulated},
      {"ArticulatedHierarchyContainer", kArticulated},
      {"ArticulationCenter", kArticulated},
      {"Articulation", kArticulated},
      {"AnimationEditor", "SoftRobots' AnimationEditor (key frames edited in runSofa's window) is not supported: drive the scene from a Python controller"},
      {"DataVariationLimiter", "SoftRobots' DataVariationLimiter is not simulated yet: limit the command's change per step in a Python controller (or with CableConstraint's maxDispVariation)"},
      {"CommunicationController", "SoftRobots' CommunicationController (ZeroMQ messages between simulations) is not supported"},
      {"SerialPortBridgeGeneric", "SoftRobots' SerialPortBridgeGeneric (a serial link to the robot's hardware) is not supported"},
      {"BeamInterpolation", kBeams},
      {"AdaptiveBeamForceFieldAndMass", kBeams},
      {"AdaptiveBeamMapping", kBeams},
      {"WireRestShape", kBeams},
      {"WireBeamInterpolation", kBeams},
      {"InterventionalRadiologyController", kBeams},
      {"JointConstraint", "SoftRobots' JointConstraint is not simulated yet (CableConstraint, PositionConstraint, SurfacePressureConstraint and UnilateralPlaneConstraint are)"},
      {"PartialRigidificationConstraint", "SoftRobots' PartialRigidificationConstraint is not simulated yet (CableConstraint, PositionConstraint, SurfacePressureConstraint and UnilateralPlaneConstraint are)"},
  };
  return kRefused;
}

std::string_view refusal_reason(std::string_view type) {
  for (const auto& [name, reason] : refused_components()) {
    if (name == type) return reason;
  }
  return {};
}

bool is_known_component(std::string_view name) {
  return find_component(name) || is_ignored_component(name) || !refusal_reason(name).empty();
}

// Whether `attribute` is one of the numbered data a spec named "stem<N>" stands for: the stem then
// digits (SOFA's vectorData, e.g. MeshSplittingEngine's indices1, indices2, ...).
static bool numbered_attribute(std::string_view spec_name, std::string_view attribute) {
  if (!spec_name.ends_with("<N>")) return false;
  const std::string_view stem = spec_name.substr(0, spec_name.size() - 3);
  if (attribute.size() <= stem.size() || !attribute.starts_with(stem)) return false;
  return std::all_of(attribute.begin() + static_cast<std::ptrdiff_t>(stem.size()), attribute.end(),
                     [](char ch) { return ch >= '0' && ch <= '9'; });
}

// Whether `attribute` is one of the words of the object's declaring attribute.
static bool declared_attribute(const ComponentSpec& spec, const SceneObject& object, std::string_view attribute) {
  if (spec.declaring_attribute.empty()) return false;
  const auto declaring = object.attributes.find(std::string(spec.declaring_attribute));
  if (declaring == object.attributes.end()) return false;
  std::istringstream words(declaring->second);
  for (std::string word; words >> word;) {
    if (word == attribute) return true;
  }
  return false;
}

const ComponentSpec* check_scene_object(const SceneObject& object, std::vector<std::string>* warnings) {
  const ComponentSpec* spec = find_component(object.type);
  if (!spec) {
    if (is_ignored_component(object.type)) return nullptr;
    if (const std::string_view reason = refusal_reason(object.type); !reason.empty()) {
      throw make_error(object.location.to_string(), ": ", object.type, ": this scene needs what fastcorot does not have: ",
                       reason);
    }
    std::vector<std::string_view> names;
    for (const auto& s : table()) names.push_back(s.name);
    throw make_error(object.location.to_string(), ": unknown component '", object.type, "'",
                     suggestion(object.type, names), "; supported: ", supported_names(),
                     " (and display or collision components, which are ignored); see `fastcorot components`");
  }
  for (const auto& [attribute, value] : object.attributes) {
    if (is_common_attribute(attribute)) continue;
    bool known = false;
    for (const auto& a : spec->attributes) known = known || a.name == attribute || numbered_attribute(a.name, attribute);
    if (known || declared_attribute(*spec, object, attribute)) continue;
    std::vector<std::string_view> names;
    for (const auto& a : spec->attributes) names.push_back(a.name);
    const std::string hint = suggestion(attribute, names);
    if (!warnings) {
      throw make_error(object.location.to_string(), ": ", spec->name, ": unknown attribute '", attribute, "'",
                       hint, "; supported: ", join_names(spec->attributes));
    }
    warnings->push_back(object.location.to_string() + ": " + std::string(spec->name) + ": unknown attribute '" +
                        attribute + "' ignored" + hint + "; supported: " + join_names(spec->attributes));
  }
  return spec;
}

std::string component_documentation() {
  std::ostringstream out;
  for (const auto& spec : table()) {
    out << "### " << spec.name;
    if (!spec.aliases.empty()) {
      out << " (also";
      for (auto alias : spec.aliases) {
        if (alias != spec.name) out << " " << alias;
      }
      out << ")";
    }
    out << "\n\n" << spec.doc << "\n\n| attribute | type | default | meaning |\n|---|---|---|---|\n";
    for (const auto& a : spec.attributes) {
      out << "| `" << a.name << "` | " << a.type << " | " << (a.default_value.empty() ? "—" : a.default_value)
          << " | " << a.doc << " |\n";
    }
    out << "\n";
  }
  out << "Drawn only (no effect on the mechanics): OglModel (VisualModel) with its MeshOBJLoader or MeshSTLLoader,\n"
         "mapped by BarycentricMapping or IdentityMapping.\n\n";
  out << "Accepted without effect on the mechanics (one info line each):";
  for (auto name : kIgnored) {
    if (!is_collision_component(name)) out << " " << name;
  }
  out << ".\n\nIgnored with a warning each, as they change SOFA's mechanics (their scene's collisions and contacts "
         "are then not simulated):";
  for (auto name : kIgnored) {
    if (is_collision_component(name) && !find_component(name)) out << " " << name;
  }
  out << ".\n\nRefused, the scene with them, in one line saying what is missing:";
  for (const auto& [name, reason] : refused_components()) out << "\n- " << name << ": " << reason;
  out << "\n";
  return out.str();
}

}  // namespace fastcorot
