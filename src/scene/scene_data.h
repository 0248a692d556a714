// Internal to the scene builder: the scene as a graph of component instances whose data (positions,
// tetrahedra, indices, ...) are computed on demand, following SOFA's links (`@name`, `@../a.b`,
// `src="@loader"`) and SOFA's implicit wiring (a MechanicalObject takes the node's first topology's
// points, a container is filled by the Hexa2TetraTopologicalMapping that outputs to it, BoxROI reads
// the node's rest positions, ...). Cycles and broken links are errors naming the file and line.
#pragma once

#include "fastcorot/core/error.h"

#include "fastcorot/core/types.h"
#include "fastcorot/scene/component_table.h"
#include "fastcorot/io/mesh_readers.h"
#include "fastcorot/scene/scene_graph.h"
#include "fastcorot/topology/cylinder_grid.h"
#include "fastcorot/topology/regular_grid.h"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

using Numbers = std::vector<double>;

struct GraphNode;

struct Component {
  const SceneObject* object = nullptr;
  const ComponentSpec* spec = nullptr;  // nullptr for ignored components
  GraphNode* node = nullptr;
  std::map<std::string, Numbers> cache;
  std::set<std::string> evaluating;

  std::string_view type() const { return spec ? spec->name : std::string_view(object->type); }
  std::string name() const { return object->name(); }
  // The name SOFA gives it: its `name`, else (SOFA's XML loader) its type followed by its rank
  // among the unnamed components of that type in its node ("MechanicalObject1").
  std::string sofa_name() const;
  bool has(const std::string& attribute) const { return object->attributes.count(attribute) != 0; }
  // "file:line: Type 'name'"
  std::string where() const;
};

struct GraphNode {
  const SceneNode* scene = nullptr;
  GraphNode* parent = nullptr;
  std::string path;  // names from the root joined by '/'
  std::vector<std::unique_ptr<Component>> components;
  // The active child nodes: the ones every pass of the builder walks (a node with activated="0"
  // is pruned from SOFA's visitors: not initialised, simulated, collided or drawn).
  std::vector<std::unique_ptr<GraphNode>> children;
  // The deactivated child nodes, kept only so that links into them resolve (SOFA still creates
  // their components and reads their data on demand).
  std::vector<std::unique_ptr<GraphNode>> deactivated;

  // Components of the given category, in scene order.
  std::vector<Component*> of_category(std::string_view category) const;
  // Whether its state only holds the points of a Mesh2PointTopologicalMapping (no mass, force or
  // constraint, no child node; SOFA's Mesh2PointTopologicalMapping.scn): SOFA integrates them with
  // nothing acting on them, so they stay where the mapping put them.
  bool is_unloaded_point_set() const;
};

// A text as SOFA's Data<bool> reads it: by the first character, t or T true, f or F false, a
// number (strtol: what follows it is ignored) true unless 0; nullopt for anything else.
std::optional<bool> read_sofa_bool(const std::string& text);

// Applies scale, then rotation (Euler angles in degrees, R = Rz Ry Rx), then translation, as SOFA's
// MechanicalObject, loaders and visual models place their points.
std::vector<Vec3<double>> transformed(std::vector<Vec3<double>> points, const Vec3<double>& scale,
                                      const Vec3<double>& rotation_degrees, const Vec3<double>& translation);

class SceneData {
 public:
  // Builds the graph, checking every component and attribute against the table. Ignored
  // components are reported through `info`, unknown attributes through `warnings` (null: they are
  // errors).
  SceneData(const SceneNode& root, std::vector<std::string>& info, std::vector<std::string>* warnings);

  GraphNode& root() { return *root_; }

  // A warning about what a scene says (with --strict, an error).
  void warn(const std::string& line) const {
    if (!warnings_) throw make_error(line);
    warnings_->push_back(line);
  }

  // Data `name` of component c: the attribute as written (a value, or a link to another
  // component's data), else what `src` provides, else what the component computes.
  const Numbers& data(Component& c, const std::string& name);

  // Scalar and typed reads of a component's attribute with its default from the table.
  double real(Component& c, const std::string& name, double fallback);
  // A count: throws fastcorot::Error naming the attribute unless it is a whole number that fits an int.
  int whole_number(Component& c, const std::string& name, int fallback);
  bool boolean(Component& c, const std::string& name, bool fallback);
  std::string text(Component& c, const std::string& name, const std::string& fallback);
  Vec3<double> vec3(Component& c, const std::string& name, const Vec3<double>& fallback);
  std::vector<Vec3<double>> points(Component& c, const std::string& name);
  std::vector<Index> indices(Component& c, const std::string& name);

  // The object a link ("@a/b/c") designates, searched as SOFA does from `from`.
  // `as_written` is the attribute text shown in errors when it differs from `link`.
  Component& resolve_object(const GraphNode& from, const std::string& link, const Component& user,
                            const std::string& as_written = "");
  // The MechanicalObject a link designates: the component itself, or, when the link names a node,
  // that node's state (as SOFA resolves a link to a state given a node's path).
  Component& resolve_state(const GraphNode& from, const std::string& link, const Component& user);
  // A mapping's input or output: the component a link designates, or, when it names a node ("@.",
  // "@.."), that node's state.
  Component& resolve_mapped(const GraphNode& from, const std::string& link, const Component& user) {
    return resolve(from, link, user, "", true);
  }

  // The node's topology slot (its last topology component, else the nearest ancestor's); nullptr
  // when there is none.
  Component* topology_of(const GraphNode& node);
  // The topology component `user` works on: the one its `topology` attribute links, else its node's slot.
  Component* topology_of(Component& user);
  // The nearest TriangleSetTopologyContainer at or above `node` (its last in a node); nullptr if none.
  Component* triangle_container_of(const GraphNode& node);
  // The component of type `mapping_type` whose output is c, searched over the whole scene.
  Component* mapping_into(Component& c, std::string_view mapping_type);
  // What an ROI engine selects from by default: the rest positions of the nearest MechanicalObject
  // at or above its node, else its node's loader's positions.
  Numbers rest_positions_around(Component& c);
  // Data `name` of BoxROI or PlaneROI c (its defaults and outputs: regions_of_interest.cpp).
  Numbers region_of_interest(Component& c, const std::string& name);
  // SOFA's VolumeFromVolumetricElements (also VolumeFromTetrahedrons) and VolumeFromTriangles:
  // their `volume` at init (volume_engines.cpp).
  double engine_volume(Component& c);
  // A topology's tetrahedra (4 indices each, checked).
  std::vector<Tetrahedron> tetrahedra_of(Component& topology);
  // Translation, rotation or scale3d of c, or their short forms (dx dy dz, rx ry rz, scale or sx sy
  // sz) as SOFA's MechanicalObject and visual models read them.
  Vec3<double> placement(Component& c, const std::string& name);
  static constexpr const char* kTranslationParts[3] = {"dx", "dy", "dz"};
  static constexpr const char* kSecondTranslationParts[3] = {"dx2", "dy2", "dz2"};
  static constexpr const char* kSecondRotationParts[3] = {"rx2", "ry2", "rz2"};
  static constexpr const char* kRotationParts[3] = {"rx", "ry", "rz"};
  static constexpr const char* kScaleParts[3] = {"sx", "sy", "sz"};
  // The grid a RegularGridTopology describes (validated; errors name the component). For a
  // CylinderGridTopology, its point counts (the rest of the grid is then unused).
  RegularGrid grid(Component& c);
  // The cylinder a CylinderGridTopology describes.
  CylinderGrid cylinder_grid(Component& c);

 private:
  Numbers compute(Component& c, const std::string& name);
  Numbers nearest_point_roi(Component& c, const std::string& name);
  Component& resolve(const GraphNode& from, const std::string& link, const Component& user,
                     const std::string& as_written, bool node_means_state);
  // The attribute as written: parsed numbers, or the data a link designates; nullopt when absent.
  std::optional<Numbers> written(Component& c, const std::string& name);
  Numbers parse_numbers(const Component& c, const std::string& name, const std::string& text) const;
  const MeshData& mesh_file(Component& loader);
  std::vector<std::string>* warnings_ = nullptr;
  std::unique_ptr<GraphNode> build_node(const SceneNode& scene, GraphNode* parent, std::vector<std::string>& info,
                                        bool active);

  std::unique_ptr<GraphNode> root_;
  std::map<const Component*, MeshData> mesh_files_;
};

// Whether a MechanicalObject's template names a Rigid3 state (Rigid3d, Rigid3f, Rigid3, Rigid).
inline bool is_rigid_template(std::string_view name) {
  return name == "Rigid3d" || name == "Rigid3f" || name == "Rigid3" || name == "Rigid";
}

// Groups a flat list into points; throws naming c and the data when the count is not a multiple of 3.
std::vector<Vec3<double>> points_from(const Numbers& values, const Component& c, const std::string& name);

// Rotation matrix of SOFA's Euler angles in degrees (R = Rz Ry Rx).
Mat3<double> euler_rotation(const Vec3<double>& degrees);

}  // namespace fastcorot::scene_detail
