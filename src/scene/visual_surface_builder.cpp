#include "visual_surface_builder.h"
#include "distance_mapping_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/surface_readers.h"
#include "fastcorot/mapping/barycentric_mapping.h"
#include "fastcorot/topology/regular_grid.h"
#include "rigid_builder.h"

#include <cmath>
#include <map>
#include <sstream>

namespace fastcorot::scene_detail {

Rgba parse_color(const std::string& attribute, const std::string& text) {
  auto fail = [&](const char* why) {
    return make_error(attribute, " = \"", text, "\": ", why,
                      " (expected \"r g b [a]\" in [0, 1], #rrggbb[aa], #rgb[a] or a colour name)");
  };
  static const std::map<std::string, Rgba> names = {
      {"white", {1, 1, 1, 1}}, {"black", {0, 0, 0, 1}},  {"red", {1, 0, 0, 1}},     {"green", {0, 1, 0, 1}},
      {"blue", {0, 0, 1, 1}},  {"cyan", {0, 1, 1, 1}},   {"magenta", {1, 0, 1, 1}}, {"yellow", {1, 1, 0, 1}},
      {"gray", {0.5f, 0.5f, 0.5f, 1}}};
  std::istringstream in(text);
  std::string first;
  in >> first;
  if (first.empty()) throw fail("empty");
  Rgba color{0, 0, 0, 1};
  if (first[0] == '#') {
    const std::string hex = first.substr(1);
    const bool digits = hex.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
    if (!digits || (hex.size() != 3 && hex.size() != 4 && hex.size() != 6 && hex.size() != 8)) throw fail("bad hex colour");
    const std::size_t width = hex.size() <= 4 ? 1 : 2;
    for (std::size_t k = 0; k * width < hex.size(); ++k) {
      const int value = std::stoi(hex.substr(k * width, width), nullptr, 16);
      color[k] = static_cast<float>(width == 1 ? value * 17 : value) / 255.0f;
    }
  } else if (const auto named = names.find(first); named != names.end()) {
    color = named->second;
  } else {
    std::istringstream numbers(text);
    std::vector<double> values;
    for (double v; numbers >> v;) values.push_back(v);
    if (!numbers.eof() || (values.size() != 3 && values.size() != 4)) throw fail("not a colour");
    for (std::size_t k = 0; k < values.size(); ++k) {
      if (!(values[k] >= 0 && values[k] <= 1)) throw fail("a component is outside [0, 1]");
      color[k] = static_cast<float>(values[k]);
    }
    return color;
  }
  if (std::string rest; in >> rest) throw fail("unexpected text after the colour");
  return color;
}

namespace {

class VisualSurfaceBuilder {
 public:
  VisualSurfaceBuilder(SceneData& data, std::vector<std::string>& info) : data_(data), info_(info) {}

  // The visual models of a mapped child node, with their mapping onto the object.
  void add_visual_surfaces(GraphNode& node, SimulatedObject<double>& object) {
    const auto mappings = node.of_category("visualmapping");
    for (Component* model : node.of_category("visual")) {
      Component* mapping = nullptr;
      for (Component* m : mappings) {
        const auto output = m->object->attributes.find("output");
        if (output == m->object->attributes.end() || &data_.resolve_mapped(node, output->second, *m) == model) {
          mapping = m;
          break;
        }
      }
      if (!model->has("src") && !model->has("filename") && !model->has("fileMesh") && !has_own_geometry(*model)) {
        info_.push_back(model->where() + ": " + std::string(model->type()) + " of mapped node " + node.path +
                        " has no src (a surface loader), filename or position and triangles: nothing to draw");
        continue;
      }
      if (!mapping) {
        info_.push_back(model->where() + ": " + std::string(model->type()) + " of mapped node " + node.path +
                        " is not mapped (its mapping is none fastcorot draws): not drawn");
        continue;
      }
      Component* grid = first_topology(node);
      if (mapping->type() == "BarycentricMapping" && !object.mesh && !(grid && grid->type() == "RegularGridTopology")) {
        // SOFA maps onto a surface's triangles too (its MeshMapper): not made here for drawing.
        data_.warn(model->where() + ": " + std::string(model->type()) + " is not drawn: its BarycentricMapping " + mapping->where() +
                   " maps onto an object without tetrahedra (a surface), which fastcorot does not follow");
        continue;
      }
      try {
        object.visual_surfaces.push_back(build_surface(node, *model, *mapping, object));
      } catch (const Error& error) {
        throw error_at(model->where(), error);
      }
    }
  }

  static bool has_own_geometry(Component& model) {
    return (model.has("position") || model.has("vertices")) && model.has("triangles");
  }

  static std::vector<Triangle> triangles_of(const std::vector<Index>& flat) {
    if (flat.size() % 3 != 0) throw make_error("triangles: ", flat.size(), " indices, not a multiple of 3");
    std::vector<Triangle> triangles;
    for (std::size_t i = 0; i + 2 < flat.size(); i += 3) triangles.push_back({flat[i], flat[i + 1], flat[i + 2]});
    return triangles;
  }

  VisualSurface build_surface(GraphNode& node, Component& model, Component& mapping, SimulatedObject<double>& object) {
    VisualSurface surface;
    surface.path = node.path + "/" + (model.object->name().empty() ? std::string(model.type()) : model.object->name());
    SurfaceData data;
    if (const auto src = model.object->attributes.find("src"); src != model.object->attributes.end()) {
      Component& loader = data_.resolve_object(node, src->second, model);
      if (loader.spec == nullptr || loader.spec->category != "surfaceloader") {
        throw make_error("src ", src->second, " is a ", loader.type(), ", not a surface loader (MeshOBJLoader, MeshSTLLoader)");
      }
      data = load_surface(loader, "filename");
    } else if (model.has("filename") || model.has("fileMesh")) {
      data = load_surface(model, model.has("filename") ? "filename" : "fileMesh");
    } else if (has_own_geometry(model)) {
      // SOFA's OglModel data written in the scene or linked (position="@topology.position").
      data.points = data_.points(model, model.has("position") ? "position" : "vertices");
      data.triangles = triangles_of(data_.indices(model, "triangles"));
      const std::vector<Index> quads = model.has("quads") ? data_.indices(model, "quads") : std::vector<Index>{};
      for (std::size_t i = 0; i + 3 < quads.size(); i += 4) data.quads.push_back({quads[i], quads[i + 1], quads[i + 2], quads[i + 3]});
      for (const Triangle& t : data.all_triangles()) {
        for (Index v : t) {
          if (v < 0 || v >= static_cast<Index>(data.points.size())) {
            throw make_error("triangle vertex ", v, " is outside its ", data.points.size(), " positions");
          }
        }
      }
    } else {
      throw make_error("no src (a surface loader), filename or position and triangles: fastcorot cannot tell what to draw");
    }
    // The model's own placement (SOFA's VisualModelImpl: scale, then rotation, then translation).
    data.points = transformed(std::move(data.points), data_.placement(model, "scale3d"),
                              data_.placement(model, "rotation"), data_.placement(model, "translation"));
    surface.rest_points = data.points;
    surface.triangles = data.all_triangles();
    surface.color = visual_color(model);
    if (mapping.type() == "RigidMapping") {
      surface.rigid = RigidPoints<double>::from(object.system.rigids,
                                                build_rigid_mapping(data_, mapping, object, surface.rest_points, surface.rest_points));
      surface.mapping = "RigidMapping";
      return surface;
    }
    surface.map = map_points(node, mapping, surface.rest_points, object, "the visual model", surface.mapping);
    return surface;
  }

  // Each MechanicalObject of mapped node `node` that one of its mappings outputs to, with that
  // mapping (outputs only: sim/mapped_state.h).
  void add_mapped_states(GraphNode& node, SimulatedObject<double>& object) {
    const auto mappings = node.of_category("visualmapping");
    for (Component* state : node.of_category("state")) {
      Component* mapping = nullptr;
      for (Component* m : mappings) {
        const auto output = m->object->attributes.find("output");
        if (output == m->object->attributes.end() ? node.of_category("state").front() == state
                                                  : &data_.resolve_mapped(node, output->second, *m) == state) {
          mapping = m;
          break;
        }
      }
      if (!mapping) {
        info_.push_back(state->where() + ": the state of mapped node " + node.path +
                        " has no mapping fastcorot follows (BarycentricMapping, IdentityMapping, SubsetMapping, RigidMapping, DistanceMapping): not in outputs");
        continue;
      }
      try {
        MappedState mapped;
        mapped.node = node.path;
        mapped.name = state->sofa_name();
        if (mapping->type() == "DistanceMapping") {
          build_distance_mapped_state(data_, node, *state, *mapping, object, mapped);
          object.mapped_states.push_back(std::move(mapped));
          continue;
        }
        if (mapping->type() == "RigidMapping") {
          mapped.rigid = RigidPoints<double>::from(
              object.system.rigids, build_rigid_mapping(data_, *mapping, object, data_.points(*state, "position"),
                                                        data_.points(*state, "rest_position")));
          mapped.mapping = "RigidMapping";
          object.mapped_states.push_back(std::move(mapped));
          continue;
        }
        // SOFA's IdentityMapping and SubsetMapping size their output themselves.
        std::vector<Vec3<double>> points;
        // (A SubsetMapping with indices or a range resizes its output; without, it matches the state's points.)
        const bool listed = mapping->has("indices") || mapping->has("first");
        if (mapping->type() == "BarycentricMapping" || (mapping->type() == "SubsetMapping" && !listed)) {
          points = data_.points(*state, "position");
        }
        mapped.map = map_points(node, *mapping, points, object, "the state", mapped.mapping);
        object.mapped_states.push_back(std::move(mapped));
      } catch (const Error& error) {
        throw error_at(state->where(), error);
      }
    }
  }

  // The mapping of `points` (the mapped model's, as placed) onto the object's points; `what` names
  // the model in messages, `description` receives the mapping's kind. An empty `points` with
  // IdentityMapping or SubsetMapping takes the mapping's own size, as SOFA's do for states.
  PointMapping<double> map_points(GraphNode& node, Component& mapping, const std::vector<Vec3<double>>& points,
                                  const SimulatedObject<double>& object, const char* what, std::string& description) {
    const auto& system = object.system;
    if (mapping.type() == "IdentityMapping") {
      // From Rigid3 bodies (SOFA's IdentityMapping<Rigid3, Vec3>): one point per body, its centre.
      const std::size_t size = system.rigids ? system.rigids->size() : system.state.position.size();
      if (!points.empty() && points.size() != size) {
        throw make_error("IdentityMapping ", mapping.where(), ": ", what, " has ", points.size(), " points, the object ", size,
                         system.rigids ? " rigid bodies" : "");
      }
      description = "IdentityMapping";
      return system.rigids ? PointMapping<double>::subset(system.rigids->block) : PointMapping<double>::identity(size);
    }
    if (mapping.type() == "SubsetMapping") {
      description = "SubsetMapping";
      return PointMapping<double>::subset(subset_indices(mapping, points, system.state.position));
    }
    // SOFA's BarycentricMapping takes the first topology of the object's node: a grid gives the
    // trilinear mapper, tetrahedra the tetrahedral one.
    const bool rest = data_.boolean(mapping, "useRestPosition", false);
    const auto& x = rest ? system.state.rest_position : system.state.position;
    Component* topology = first_topology(node);
    if (topology && topology->type() == "RegularGridTopology") {
      description = "BarycentricMapping (trilinear, RegularGridTopology)";
      return PointMapping<double>::trilinear(data_.grid(*topology), points);
    }
    if (!object.mesh) throw make_error("BarycentricMapping ", mapping.where(), ": the object has no tetrahedra to map onto");
    // A MeshTopology gets SOFA's MeshMapper, which tries every tetrahedron; a dynamic container its
    // TetrahedronSetMapper, which searches a grid.
    const bool mesh_topology = topology && topology->object->type == "MeshTopology";
    description = mesh_topology ? "BarycentricMapping (tetrahedra, every one tried)" : "BarycentricMapping (tetrahedra)";
    return PointMapping<double>::from_barycentric(
        *object.mesh, map_onto_tetrahedra<double>(*object.mesh, x, points,
                                                  mesh_topology ? TetrahedronSearch::exhaustive : TetrahedronSearch::grid));
  }

  // SOFA's SubsetMapping::init: `indices`, else first..last (clamped into the input), else for each
  // output point the input point within `radius` found last while the distance decreases.
  std::vector<Index> subset_indices(Component& mapping, const std::vector<Vec3<double>>& out,
                                    const std::vector<Vec3<double>>& in) {
    const Index size = static_cast<Index>(in.size());
    std::vector<Index> indices = data_.indices(mapping, "indices");
    if (indices.empty() && mapping.has("first")) {
      Index first = data_.whole_number(mapping, "first", 0), last = mapping.has("last") ? data_.whole_number(mapping, "last", 0) : size - 1;
      if (first < 0 || first >= size) first = 0;
      if (last < 0 || last >= size) last = size - 1;
      for (Index i = first; i <= last; ++i) indices.push_back(i);
    } else if (indices.empty()) {
      const double radius = data_.real(mapping, "radius", 1e-5);
      for (std::size_t i = 0; i < out.size(); ++i) {
        double best = radius;
        Index found = -1;
        for (Index j = 0; j < size; ++j) {
          const double r = (out[i] - in[static_cast<std::size_t>(j)]).norm();
          if (r < best) {
            best = r;
            found = j;
          }
        }
        if (found < 0) {
          throw make_error("SubsetMapping ", mapping.where(), ": point ", i, " of the visual model has no point of the object within radius ",
                           radius);
        }
        indices.push_back(found);
      }
    }
    for (Index i : indices) {
      if (i < 0 || i >= size) throw make_error("SubsetMapping ", mapping.where(), ": index ", i, " out of range [0, ", size, ")");
    }
    if (!out.empty() && indices.size() != out.size()) {
      throw make_error("SubsetMapping ", mapping.where(), ": ", indices.size(), " indices for a visual model of ", out.size(), " points");
    }
    return indices;
  }

  // The first topology object of the node above a mapped node (the object's node), as SOFA's
  // BarycentricMapping finds its input topology.
  static Component* first_topology(const GraphNode& mapped) {
    for (const GraphNode* scope = mapped.parent; scope; scope = scope->parent) {
      const auto topologies = scope->of_category("topology");
      if (!topologies.empty()) return topologies.front();
    }
    return nullptr;
  }

  SurfaceData load_surface(Component& c, const std::string& attribute) {
    const std::string name = data_.text(c, attribute, "");
    if (name.empty()) throw make_error(c.where(), ": no ", attribute, " given");
    SurfaceData surface;
    try {
      surface = read_surface_file(find_data_file(c.object->location.file, name));
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
    if (c.spec && c.spec->category == "surfaceloader") {
      Vec3<double> scale = data_.vec3(c, "scale3d", {1, 1, 1});
      if (c.has("scale")) scale *= data_.real(c, "scale", 1);
      surface.points = transformed(std::move(surface.points), scale, data_.vec3(c, "rotation", {0, 0, 0}),
                                   data_.vec3(c, "translation", {0, 0, 0}));
    }
    return surface;
  }

  // The model's colour: `color` (a name or r g b [a]), else the Diffuse colour of `material`, else
  // SOFA's default white.
  Rgba visual_color(Component& model) {
    if (model.has("color")) return parse_color("color", data_.text(model, "color", ""));
    if (model.has("material")) {
      std::istringstream in(data_.text(model, "material", ""));
      std::string word;
      while (in >> word) {
        if (word == "Diffuse") {
          int enabled = 0;
          Rgba rgba{1, 1, 1, 1};
          if (in >> enabled >> rgba[0] >> rgba[1] >> rgba[2] >> rgba[3]) return rgba;
          break;
        }
      }
    }
    return {1, 1, 1, 1};
  }
 private:
  SceneData& data_;
  std::vector<std::string>& info_;
};

}  // namespace

void add_visual_surfaces(SceneData& data, std::vector<std::string>& info, GraphNode& node,
                         SimulatedObject<double>& object) {
  VisualSurfaceBuilder(data, info).add_visual_surfaces(node, object);
}

void add_mapped_states(SceneData& data, std::vector<std::string>& info, GraphNode& node, SimulatedObject<double>& object) {
  VisualSurfaceBuilder(data, info).add_mapped_states(node, object);
}

}  // namespace fastcorot::scene_detail
