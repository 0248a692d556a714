#include "scene_data.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>

namespace fastcorot::scene_detail {

std::string Component::where() const {
  std::string text = object->location.to_string() + ": " + std::string(type());
  if (!name().empty()) text += " '" + name() + "'";
  return text;
}

std::string Component::sofa_name() const {
  if (!name().empty()) return name();
  int rank = 0;
  for (const auto& other : node->components) {
    if (other->object->type == object->type && other->name().empty()) ++rank;
    if (other.get() == this) break;
  }
  return object->type + std::to_string(rank);
}

std::vector<Component*> GraphNode::of_category(std::string_view category) const {
  std::vector<Component*> found;
  for (const auto& c : components) {
    if (c->spec && c->spec->category == category) found.push_back(c.get());
  }
  return found;
}

bool GraphNode::is_unloaded_point_set() const {
  bool placed = false;
  for (const auto& c : components) placed = placed || c->type() == "Mesh2PointTopologicalMapping";
  return placed && children.empty() && of_category("forcefield").empty() && of_category("mass").empty() &&
         of_category("constraint").empty();
}

Mat3<double> euler_rotation(const Vec3<double>& degrees) {
  const Vec3<double> radians = degrees * std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(radians.z(), Vec3<double>::UnitZ()) * Eigen::AngleAxisd(radians.y(), Vec3<double>::UnitY()) *
          Eigen::AngleAxisd(radians.x(), Vec3<double>::UnitX()))
      .toRotationMatrix();
}

// Applies scale, then rotation, then translation (SOFA's MechanicalObject and loaders).
std::vector<Vec3<double>> transformed(std::vector<Vec3<double>> points, const Vec3<double>& scale,
                                      const Vec3<double>& rotation_degrees, const Vec3<double>& translation) {
  const bool rotate = rotation_degrees != Vec3<double>::Zero();
  const Mat3<double> r = euler_rotation(rotation_degrees);
  for (auto& p : points) {
    p = p.cwiseProduct(scale);
    if (rotate) p = r * p;
    p += translation;
  }
  return points;
}

std::optional<bool> read_sofa_bool(const std::string& v) {
  if (!v.empty() && (v[0] == 't' || v[0] == 'T')) return true;
  if (!v.empty() && (v[0] == 'f' || v[0] == 'F')) return false;
  if (!v.empty() && (std::isdigit(static_cast<unsigned char>(v[0])) || v[0] == '-')) {
    char* end = nullptr;
    const long number = std::strtol(v.c_str(), &end, 10);
    if (end != v.c_str()) return number != 0;
  }
  return std::nullopt;
}

namespace {

// A node's `activated` (SOFA's Context data, true by default).
bool is_activated(const SceneNode& node) {
  const auto it = node.attributes.find("activated");
  if (it == node.attributes.end()) return true;
  if (const auto value = read_sofa_bool(it->second)) return *value;
  throw make_error(node.location.to_string(), ": Node '", node.name, "': activated = \"", it->second,
                   "\": expected true/false or 1/0");
}

}  // namespace

SceneData::SceneData(const SceneNode& root, std::vector<std::string>& info, std::vector<std::string>* warnings)
    : warnings_(warnings) {
  if (!is_activated(root)) {
    throw make_error(root.location.to_string(), ": the root node is deactivated (activated=\"",
                     root.attributes.at("activated"), "\"): SOFA runs nothing in it");
  }
  root_ = build_node(root, nullptr, info, true);
}

std::unique_ptr<GraphNode> SceneData::build_node(const SceneNode& scene, GraphNode* parent,
                                                 std::vector<std::string>& info, bool active) {
  auto node = std::make_unique<GraphNode>();
  node->scene = &scene;
  node->parent = parent;
  node->path = parent ? parent->path + "/" + scene.name : scene.name;
  // What a deactivated subtree's components would warn about is only information: SOFA never
  // initialises them (a deactivated node often holds components of a plugin not loaded).
  std::vector<std::string> deactivated_warnings;
  std::vector<std::string>* const warnings = active ? warnings_ : &deactivated_warnings;
  for (const auto& object : scene.objects) {
    auto component = std::make_unique<Component>();
    component->object = &object;
    component->node = node.get();
    try {
      component->spec = check_scene_object(object, warnings);
    } catch (const Error& error) {
      if (active) throw;
      deactivated_warnings.push_back(error.what());  // a component fastcorot lacks, where SOFA never initialises it
    }
    if (!component->spec && is_collision_component(object.type)) {
      const std::string line = object.location.to_string() + ": " + object.type +
                               " ignored: collisions and contacts are not simulated by fastcorot";
      if (!warnings) throw make_error(line);
      warnings->push_back(line);
    } else if (!component->spec && (object.type == "AddDataRepository" || object.type == "AddResourceRepository")) {
      info.push_back(object.location.to_string() + ": " + object.type + ": files are also looked for in its path");
    } else if (!component->spec && active) {
      info.push_back(object.location.to_string() + ": " + object.type + " ignored (no effect on the mechanics)");
    }
    node->components.push_back(std::move(component));
  }
  for (const auto& line : deactivated_warnings) info.push_back(line + " (in a deactivated node)");
  for (const auto& child : scene.children) {
    const bool child_active = active && is_activated(child);
    auto built = build_node(child, node.get(), info, child_active);
    if (child_active) {
      node->children.push_back(std::move(built));
    } else {
      if (active) {
        info.push_back(child.location.to_string() + ": node " + built->path +
                       " is deactivated (activated=\"" + child.attributes.at("activated") +
                       "\"): not simulated, collided or drawn, as in SOFA");
      }
      node->deactivated.push_back(std::move(built));
    }
  }
  return node;
}

Numbers SceneData::parse_numbers(const Component& c, const std::string& name, const std::string& text) const {
  Numbers numbers;
  std::string cleaned = text;
  for (char& ch : cleaned) {
    if (ch == ',' || ch == '[' || ch == ']') ch = ' ';
  }
  // Index lists take SOFA's ranges: "A-B" is A..B (either way), "A-B-S" every S-th from A to B.
  bool indices = false, real = false;
  if (c.spec) {
    for (const auto& a : c.spec->attributes) {
      indices = indices || (a.name == name && a.type == std::string_view("indices"));
      real = real || (a.name == name && a.type == std::string_view("real"));
    }
  }
  std::istringstream in(cleaned);
  std::string token;
  while (in >> token) {
    if (const auto hyphen = token.find('-', 1); indices && hyphen != std::string::npos) {
      const auto whole = [&](const std::string& part) {
        std::size_t used = 0;
        long long value = -1;
        try {
          value = std::stoll(part, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (part.empty() || used != part.size() || value < 0) {
          throw make_error(c.where(), ": ", name, ": '", token, "' is not an index range (A-B or A-B-step)");
        }
        return value;
      };
      const auto second = token.find('-', hyphen + 2);
      const long long from = whole(token.substr(0, hyphen));
      const long long to = whole(second == std::string::npos ? token.substr(hyphen + 1)
                                                             : token.substr(hyphen + 1, second - hyphen - 1));
      long long step = second == std::string::npos ? 0 : std::stoll(token.substr(second + 1));
      if (step == 0) step = from <= to ? 1 : -1;
      const long long low = std::min(from, to), high = std::max(from, to);
      if (high - low > 100000000) throw make_error(c.where(), ": ", name, ": range '", token, "' is too long");
      const long long first = step > 0 ? low : high;
      for (long long v = first; v >= low && v <= high; v += step) numbers.push_back(static_cast<double>(v));
      continue;
    }
    try {
      std::size_t used = 0;
      const double value = std::stod(token, &used);
      if (!std::isfinite(value)) throw std::invalid_argument(token);
      if (used != token.size()) {
        // SOFA reads one real as a stream does: the number that starts the text, the rest ignored.
        if (!real || !numbers.empty()) throw std::invalid_argument(token);
        warn(c.where() + ": " + name + " = \"" + text + "\": read as " + token.substr(0, used) +
             ", as SOFA reads it (the text after the number is ignored)");
        numbers.push_back(value);
        return numbers;
      }
      numbers.push_back(value);
    } catch (const std::exception&) {
      throw make_error(c.where(), ": ", name, " = \"", text.size() > 60 ? text.substr(0, 60) + "..." : text,
                       "\": '", token, "' is not a finite number");
    }
  }
  return numbers;
}

Component& SceneData::resolve_object(const GraphNode& from, const std::string& link, const Component& user,
                                     const std::string& as_written) {
  return resolve(from, link, user, as_written, false);
}

Component& SceneData::resolve_state(const GraphNode& from, const std::string& link, const Component& user) {
  Component& target = resolve(from, link, user, "", true);
  if (!target.spec || target.spec->category != "state") {
    throw make_error(user.where(), ": link '", link, "' names ", target.where(), ", not a MechanicalObject");
  }
  return target;
}

Component& SceneData::resolve(const GraphNode& from, const std::string& link, const Component& user,
                              const std::string& as_written, bool node_means_state) {
  auto fail = [&](const std::string& why) -> Component& {
    throw make_error(user.where(), ": broken link '", as_written.empty() ? link : as_written, "': ", why);
  };
  if (link.empty() || link[0] != '@') return fail("links start with @");
  std::string path = link.substr(1);
  // SOFA's "@[-k]": the component k places before the user in its node (k = 0: the user).
  if (path.size() > 2 && path.front() == '[' && path.back() == ']') {
    char* end = nullptr;
    const long offset = std::strtol(path.c_str() + 1, &end, 10);
    if (end != path.c_str() + path.size() - 1 || offset > 0) return fail("expected [-k], k >= 0: the k-th component before this one");
    const auto& components = user.node->components;
    const auto at = std::find_if(components.begin(), components.end(), [&](const auto& c) { return c.get() == &user; });
    const long index = static_cast<long>(at - components.begin()) + offset;
    if (at == components.end() || index < 0) return fail("no component " + std::to_string(-offset) + " places before this one in its node");
    return *components[static_cast<std::size_t>(index)];
  }
  const GraphNode* node = &from;
  // Only the first name of a relative path is searched upward through the ancestors (SOFA).
  bool search_up = true;
  if (!path.empty() && path[0] == '/') {
    while (node->parent) node = node->parent;
    path = path.substr(1);
    search_up = false;
    const auto slash = path.find('/');
    if (path.substr(0, slash) == node->scene->name) path = slash == std::string::npos ? "" : path.substr(slash + 1);
  }
  std::vector<std::string> parts;
  std::stringstream stream(path);
  for (std::string part; std::getline(stream, part, '/');) {
    if (!part.empty()) parts.push_back(part);
  }
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    if (part == "." || part == "..") {
      if (part == ".." && !node->parent) return fail("the root has no parent");
      if (part == "..") node = node->parent;
      search_up = false;
      continue;
    }
    const GraphNode* next = nullptr;
    for (const GraphNode* scope = node; scope && !next; scope = search_up ? scope->parent : nullptr) {
      if (last) {
        for (const auto& c : scope->components) {
          if (c->name() == part) return *c;
        }
      }
      for (const auto& child : scope->children) {
        if (child->scene->name == part) next = child.get();
      }
      for (const auto& child : scope->deactivated) {
        if (!next && child->scene->name == part) next = child.get();
      }
      if (next && last && node_means_state) {
        const auto states = next->of_category("state");
        if (states.empty()) return fail("node " + next->path + " has no MechanicalObject");
        return *states.front();
      }
      if (next && last) return fail("'" + part + "' is a node, not a component");
    }
    if (!next) {
      return fail("no " + std::string(last ? "component" : "node") + " named '" + part + "' in " + node->path +
                  (search_up ? " or above" : ""));
    }
    node = next;
    search_up = false;
  }
  // "@." or "@..": a node, which stands for its state where a state is expected.
  if (node_means_state && !parts.empty()) {
    const auto states = node->of_category("state");
    if (states.empty()) return fail("node " + node->path + " has no MechanicalObject");
    return *states.front();
  }
  return fail("it names no component");
}

std::optional<Numbers> SceneData::written(Component& c, const std::string& name) {
  const auto attribute = c.object->attributes.find(name);
  if (attribute == c.object->attributes.end()) return std::nullopt;
  const std::string& text = attribute->second;
  if (text.empty() || text[0] != '@') return parse_numbers(c, name, text);
  // "@path.data": the data name follows the last '.' after the last '/'; "@path" alone names a
  // component whose data of the same name is meant.
  const auto slash = text.rfind('/');
  const auto dot = text.rfind('.');
  const bool names_data = dot != std::string::npos && (slash == std::string::npos || dot > slash) &&
                          dot + 1 < text.size() && text[dot - 1] != '.';
  if (!names_data) return data(resolve_object(*c.node, text, c), name);
  return data(resolve_object(*c.node, text.substr(0, dot), c, text), text.substr(dot + 1));
}

const Numbers& SceneData::data(Component& c, const std::string& name) {
  if (const auto it = c.cache.find(name); it != c.cache.end()) return it->second;
  if (c.evaluating.count(name)) throw make_error(c.where(), ": '", name, "' depends on itself through links");
  c.evaluating.insert(name);
  // A MechanicalObject transforms its positions whatever their source, so it computes them itself.
  const bool transforms = c.type() == "MechanicalObject" && name == "position";
  std::optional<Numbers> value = transforms ? std::nullopt : written(c, name);
  if (!value) value = compute(c, name);
  c.evaluating.erase(name);
  return c.cache[name] = std::move(*value);
}

const MeshData& SceneData::mesh_file(Component& loader) {
  if (const auto it = mesh_files_.find(&loader); it != mesh_files_.end()) return it->second;
  const auto filename = loader.object->attributes.find("filename");
  if (filename == loader.object->attributes.end() || filename->second.empty()) {
    throw make_error(loader.where(), ": no filename given");
  }
  MeshData mesh;
  try {
    const auto path = find_data_file(loader.object->location.file, filename->second);
    mesh = loader.type() == "GIDMeshLoader" ? read_gid(path) : read_mesh_file(path);
  } catch (const Error& error) {
    throw error_at(loader.where(), error);
  }
  mesh.points = transformed(std::move(mesh.points), vec3(loader, "scale3d", {1, 1, 1}),
                            vec3(loader, "rotation", {0, 0, 0}), vec3(loader, "translation", {0, 0, 0}));
  return mesh_files_[&loader] = std::move(mesh);
}

Vec3<double> SceneData::placement(Component& c, const std::string& name) {
  // SOFA's short forms (MechanicalObject::parse, VisualModelImpl::parse): dx dy dz, rx ry rz, and
  // scale (uniform) or sx sy sz.
  const bool scale = name == "scale3d";
  const char* const* parts = name == "translation"    ? kTranslationParts
                             : name == "rotation"     ? kRotationParts
                             : name == "translation2" ? kSecondTranslationParts
                             : name == "rotation2"    ? kSecondRotationParts
                                                      : kScaleParts;
  const double fallback = scale ? 1 : 0;
  if (scale && c.has("scale")) return Vec3<double>::Constant(real(c, "scale", 1));
  if (c.has(parts[0]) || c.has(parts[1]) || c.has(parts[2])) {
    return {real(c, parts[0], fallback), real(c, parts[1], fallback), real(c, parts[2], fallback)};
  }
  return vec3(c, name, Vec3<double>::Constant(fallback));
}

RegularGrid SceneData::grid(Component& c) {
  RegularGrid grid;
  if (c.has("nx") && c.has("ny") && c.has("nz")) {
    // SOFA's GridTopology::parse: nx, ny and nz (all three) replace n.
    grid.n = {whole_number(c, "nx", 2), whole_number(c, "ny", 2), whole_number(c, "nz", 2)};
  } else {
    const Numbers& n = data(c, "n");
    if (n.size() != 3) throw make_error(c.where(), ": n needs 3 integers");
    for (int k = 0; k < 3; ++k) grid.n[k] = static_cast<Index>(n[k]);
  }
  grid.min = vec3(c, "min", {0, 0, 0});
  grid.max = vec3(c, "max", {1, 1, 1});
  // SOFA's parse reads xmin..zmax (all six, as float, times `scale`) over min and max.
  static constexpr const char* kBounds[6] = {"xmin", "ymin", "zmin", "xmax", "ymax", "zmax"};
  if (std::all_of(std::begin(kBounds), std::end(kBounds), [&](const char* b) { return c.has(b); })) {
    const double scale = static_cast<float>(real(c, "scale", 1));
    for (int a = 0; a < 3; ++a) {
      grid.min[a] = static_cast<float>(real(c, kBounds[a], 0)) * scale;
      grid.max[a] = static_cast<float>(real(c, kBounds[a + 3], 1)) * scale;
    }
  }
  if (c.has("p0")) grid.p0 = vec3(c, "p0", {0, 0, 0});
  try {
    validate(grid);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
  return grid;
}

CylinderGrid SceneData::cylinder_grid(Component& c) {
  CylinderGrid cylinder;
  cylinder.n = grid(c).n;
  cylinder.center = vec3(c, "center", {0, 0, 0});
  cylinder.axis = vec3(c, "axis", {0, 0, 1});
  cylinder.radius = real(c, "radius", 1);
  cylinder.length = real(c, "length", 1);
  try {
    cylinder_grid_points(cylinder);  // validates
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
  return cylinder;
}

Numbers SceneData::rest_positions_around(Component& c) {
  for (const GraphNode* scope = c.node; scope; scope = scope->parent) {
    const auto states = scope->of_category("state");
    if (!states.empty()) return data(*states.front(), "rest_position");
    if (scope == c.node) {
      const auto loaders = scope->of_category("loader");
      if (!loaders.empty()) return data(*loaders.front(), "position");
    }
  }
  throw make_error(c.where(), ": no position given and no MechanicalObject in its node or above");
}

Component* SceneData::triangle_container_of(const GraphNode& node) {
  for (const GraphNode* scope = &node; scope; scope = scope->parent) {
    const auto containers = scope->of_category("trianglecontainer");
    if (!containers.empty()) return containers.back();
  }
  return nullptr;
}

Component* SceneData::topology_of(Component& user) {
  return user.has("topology") ? &resolve_object(*user.node, user.object->attributes.at("topology"), user)
                              : topology_of(*user.node);
}

Component* SceneData::topology_of(const GraphNode& node) {
  for (const GraphNode* scope = &node; scope; scope = scope->parent) {
    const auto topologies = scope->of_category("topology");
    if (!topologies.empty()) return topologies.back();
  }
  return nullptr;
}

Component* SceneData::mapping_into(Component& c, std::string_view mapping_type) {
  std::vector<GraphNode*> stack = {root_.get()};
  while (!stack.empty()) {
    GraphNode* node = stack.back();
    stack.pop_back();
    for (auto& m : node->components) {
      if (m->type() != mapping_type || !m->has("output")) continue;
      if (&resolve_object(*node, m->object->attributes.at("output"), *m) == &c) return m.get();
    }
    for (auto& child : node->children) stack.push_back(child.get());
  }
  return nullptr;
}

std::vector<Tetrahedron> SceneData::tetrahedra_of(Component& topology) {
  const std::vector<Index> flat = indices(topology, "tetrahedra");
  if (flat.size() % 4 != 0) throw make_error(topology.where(), ": tetrahedra needs 4 indices per tetrahedron");
  std::vector<Tetrahedron> tetrahedra(flat.size() / 4);
  for (std::size_t t = 0; t < tetrahedra.size(); ++t) {
    for (std::size_t j = 0; j < 4; ++j) tetrahedra[t][j] = flat[4 * t + j];
  }
  return tetrahedra;
}

double SceneData::real(Component& c, const std::string& name, double fallback) {
  if (!c.has(name)) return fallback;
  const Numbers& values = data(c, name);
  if (values.size() != 1) throw make_error(c.where(), ": ", name, " needs one number, got ", values.size());
  return values[0];
}

int SceneData::whole_number(Component& c, const std::string& name, int fallback) {
  if (!c.has(name)) return fallback;
  const double value = real(c, name, fallback);
  if (!(value >= std::numeric_limits<int>::min() && value <= std::numeric_limits<int>::max()) ||
      value != std::floor(value)) {
    throw make_error(c.where(), ": ", name, " = ", value, ": expected a whole number");
  }
  return static_cast<int>(value);
}

bool SceneData::boolean(Component& c, const std::string& name, bool fallback) {
  const auto it = c.object->attributes.find(name);
  if (it == c.object->attributes.end()) return fallback;
  // SOFA warns on a value it cannot read and keeps the default; fastcorot stops there.
  if (const auto value = read_sofa_bool(it->second)) return *value;
  throw make_error(c.where(), ": ", name, " = \"", it->second, "\": expected true/false or 1/0");
}

std::string SceneData::text(Component& c, const std::string& name, const std::string& fallback) {
  const auto it = c.object->attributes.find(name);
  return it == c.object->attributes.end() ? fallback : it->second;
}

Vec3<double> SceneData::vec3(Component& c, const std::string& name, const Vec3<double>& fallback) {
  if (!c.has(name)) return fallback;
  const Numbers& values = data(c, name);
  if (values.size() != 3) throw make_error(c.where(), ": ", name, " needs 3 numbers, got ", values.size());
  return {values[0], values[1], values[2]};
}

std::vector<Vec3<double>> SceneData::points(Component& c, const std::string& name) {
  return points_from(data(c, name), c, name);
}

std::vector<Index> SceneData::indices(Component& c, const std::string& name) {
  std::vector<Index> out;
  for (double v : data(c, name)) {
    if (!(v >= 0) || v != std::floor(v) || v > 2e9) {
      throw make_error(c.where(), ": ", name, ": ", v, " is not a valid index");
    }
    out.push_back(static_cast<Index>(v));
  }
  return out;
}

std::vector<Vec3<double>> points_from(const Numbers& values, const Component& c, const std::string& name) {
  if (values.size() % 3 != 0) {
    throw make_error(c.where(), ": ", name, " needs 3 numbers per point, got ", values.size(), " numbers");
  }
  std::vector<Vec3<double>> out(values.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
  return out;
}

}  // namespace fastcorot::scene_detail
