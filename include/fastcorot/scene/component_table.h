// The SOFA components fastcorot understands, as a declarative table: for each component its
// attributes (name, type, default, meaning). The scene builder checks every attribute against this
// table (unknown names are errors with file:line), and `fastcorot components` prints it, so the
// documentation of supported components comes from the same source. Components listed as ignored
// are accepted with one info line: they only draw, configure plugins or handle collisions.
#pragma once

#include "fastcorot/scene/scene_graph.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fastcorot {

struct AttributeSpec {
  std::string_view name;
  std::string_view type;           // "real", "vec3", "reals", "vec3s", "indices", "int", "int3", "bool", "string", "link", "file"
  std::string_view default_value;  // as a scene would write it; "" when none
  std::string_view doc;
};

struct ComponentSpec {
  std::string_view name;
  std::string_view category;  // "state", "topology", "loader", "mapping", "forcefield", "mass", "constraint", "engine", "odesolver", "linearsolver", "preconditioner", "linearsystem"
  std::string_view doc;
  std::vector<AttributeSpec> attributes;
  std::vector<std::string_view> aliases = {};  // other component names SOFA accepts for it
  // An attribute whose words name further attributes the component accepts (RuleBasedContactManager's
  // `variables`, each then given a value in the scene); empty for none.
  std::string_view declaring_attribute = {};
};

// Supported components; nullptr when `name` is neither a component nor one of its aliases.
const ComponentSpec* find_component(std::string_view name);
std::span<const ComponentSpec> supported_components();

// Components accepted without effect on the mechanics (visual, plugin, collision, helpers).
bool is_ignored_component(std::string_view name);
std::span<const std::string_view> ignored_components();
// Ignored components that change SOFA's mechanics (collision detection and contact response): the
// scene loads, with a warning that contacts are not simulated.
bool is_collision_component(std::string_view name);
// Whether a component of this name is one fastcorot reads as SOFA's object factory would create it:
// supported, ignored or refused with a reason. A scene element of any other type is replaced, as
// SOFA's loader replaces it, by the file Objects/<type>.xml on the data path when there is one
// (scene_graph.h); otherwise it is an unknown component.
bool is_known_component(std::string_view name);

// Attributes every component accepts (name, template, tags, printLog, ...) and the rule that
// attributes beginning with "draw" or "show" are display options with no effect on mechanics.
bool is_common_attribute(std::string_view name);

// Checks one scene object against the table as the scene builder does: returns its spec, or nullptr
// for an ignored component; throws fastcorot::Error naming the object's file and line for an unknown
// component, with the closest supported name when one is close and the supported names. An unknown
// attribute of a known component is, as in SOFA, not fatal: with `warnings` it adds a line there
// (the attribute, its file and line, the closest known attribute) and the attribute is ignored;
// without (strict checking) it is the same error. (Front ends that assemble scenes in memory, like
// the Python module, call it to report mistakes where they are made.)
const ComponentSpec* check_scene_object(const SceneObject& object, std::vector<std::string>* warnings = nullptr);

// A Markdown table of the supported components (used by `fastcorot components` and the README).
std::string component_documentation();

}  // namespace fastcorot
