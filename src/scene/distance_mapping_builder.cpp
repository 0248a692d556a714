#include "distance_mapping_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/mapping/distance_mapping.h"

#include <memory>

namespace fastcorot::scene_detail {

namespace {

GeometricStiffnessMethod geometric_stiffness(SceneData& data, Component& mapping) {
  const std::string text = data.text(mapping, "geometricStiffness", "Stabilized");
  if (text == "None" || text == "0") return GeometricStiffnessMethod::none;
  if (text == "Exact" || text == "1") return GeometricStiffnessMethod::exact;
  if (text == "Stabilized" || text == "2") return GeometricStiffnessMethod::stabilized;
  throw make_error("geometricStiffness = \"", text, "\": not None, Exact or Stabilized (0, 1, 2)");
}

}  // namespace

void build_distance_mapped_state(SceneData& data, GraphNode& node, Component& state, Component& mapping,
                                 SimulatedObject<double>& object, MappedState& mapped) {
  const std::string tmpl = data.text(state, "template", "Vec3d");
  if (!is_vec1_template(tmpl)) {
    throw make_error("the output of DistanceMapping ", mapping.where(), " is a ", tmpl, " state: SOFA's DistanceMapping outputs Vec1 (template=\"Vec1\")");
  }
  if (object.system.rigids) {
    throw make_error("DistanceMapping ", mapping.where(), ": its input is a Rigid3 state (only DistanceMapping<Vec3, Vec1> is supported)");
  }
  if (!mapping.has("topology")) {
    data.warn(mapping.where() + ": no topology link: the nearest topology is used (set topology=\"@...\"), as SOFA warns");
  }
  Component* topology = data.topology_of(mapping);
  if (!topology) throw make_error("DistanceMapping ", mapping.where(), ": no topology in node ", node.path, " or above");
  const std::vector<Index> flat = data.indices(*topology, "edges");
  if (flat.size() % 2 != 0) throw make_error(topology->where(), ": edges needs 2 indices per edge");
  if (flat.empty()) throw make_error("DistanceMapping ", mapping.where(), ": its topology ", topology->where(), " has no edges");
  std::vector<Edge> edges;
  for (std::size_t e = 0; e + 1 < flat.size(); e += 2) edges.push_back({flat[e], flat[e + 1]});
  std::vector<double> rest_lengths;
  if (mapping.has("restLengths")) {
    const Numbers& written = data.data(mapping, "restLengths");
    rest_lengths.assign(written.begin(), written.end());
  }
  // SOFA's init: lengths measured where the points are, or 0 with computeDistance; written rest
  // lengths only when there is one per edge.
  if (rest_lengths.size() != edges.size()) {
    rest_lengths.clear();
    if (data.boolean(mapping, "computeDistance", false)) rest_lengths.assign(edges.size(), 0.0);
  }
  const auto& x = object.system.state.position;
  auto distance = std::make_shared<DistanceMapping<double>>(edges, x, rest_lengths);
  mapped.mapping = "DistanceMapping";
  mapped.map = PointMapping<double>::identity(distance->size());
  mapped.coordinates = 1;
  mapped.constraint_force = std::make_shared<std::vector<Vec3<double>>>(distance->size(), Vec3<double>::Zero());
  mapped.through = distance;
  mapped.apply_rest_position = data.boolean(mapping, "applyRestPosition", false);
  const GeometricStiffnessMethod method = geometric_stiffness(data, mapping);
  if (method == GeometricStiffnessMethod::none) return;
  const auto points = std::make_shared<const TetMesh>(object.system.size(), std::vector<Tetrahedron>{});
  object.system.force_fields.push_back(
      std::make_shared<DistanceGeometricStiffness<double>>(points, std::move(edges), mapped.constraint_force, method));
  object.force_field_drawing.push_back({});
}

}  // namespace fastcorot::scene_detail
