#include "subset_multi_mapping_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/mapping/subset_multi_mapping.h"

#include <sstream>

namespace fastcorot::scene_detail {

bool is_subset_multi_mapping(std::string_view type) { return type == "SubsetMultiMapping"; }

std::optional<PointMapping<double>> SubsetMultiMappingInputs::linear() const {
  PointMapping<double> picked;
  for (const auto& [k, j] : pairs) {
    const Input& input = inputs[k];
    if (input.rigid) return std::nullopt;
    picked.vertices.push_back(input.map.vertices[static_cast<std::size_t>(j)]);
    picked.weights.push_back(input.map.weights[static_cast<std::size_t>(j)]);
  }
  return picked;
}

std::optional<RigidPoints<double>> SubsetMultiMappingInputs::carried() const {
  RigidPoints<double> picked;
  for (const auto& [k, j] : pairs) {
    const Input& input = inputs[k];
    if (!input.rigid || (picked.frames && picked.frames != input.rigid->frames)) return std::nullopt;
    picked.frames = input.rigid->frames;
    picked.local.push_back(input.rigid->local[static_cast<std::size_t>(j)]);
    picked.rigid.push_back(input.rigid->rigid[static_cast<std::size_t>(j)]);
  }
  if (!picked.frames) return std::nullopt;
  return picked;
}

std::unique_ptr<MechanicalMapping<double>> SubsetMultiMappingInputs::mapping() const {
  std::vector<std::unique_ptr<MechanicalMapping<double>>> parts;
  for (const Input& input : inputs) parts.push_back(mechanical_mapping(input.map, input.rigid));
  return std::make_unique<SubsetMultiMapping<double>>(std::move(parts), pairs);
}

SubsetMultiMappingInputs read_subset_multi_mapping(SceneData& data, const GraphNode& node, Component& c,
                                                   const std::vector<Component*>& states, const std::vector<Index>& offsets,
                                                   const std::vector<Index>& sizes, const SimulatedObject<double>& object) {
  try {
    const std::string kind = data.text(c, "template", "Vec3,Vec3");
    if (kind.find("Rigid") != std::string::npos) {
      throw make_error("template=\"", kind, "\": only Vec3 inputs are supported (SubsetMultiMapping<Vec3, Vec3>)");
    }
    const Component& own = *node.of_category("state").front();
    if (const auto output = c.object->attributes.find("output"); output != c.object->attributes.end()) {
      if (&data.resolve_mapped(node, output->second, c) != &own) {
        throw make_error("output=\"", output->second, "\": only the MechanicalObject of its own node is supported");
      }
    }
    const auto input = c.object->attributes.find("input");
    std::vector<std::string> links;
    if (input != c.object->attributes.end()) {
      std::istringstream words(input->second);
      for (std::string link; words >> link;) links.push_back(link);
    }
    if (links.empty()) throw make_error("input: no input states (SOFA's input=\"@state1 @state2 ...\")");
    SubsetMultiMappingInputs read;
    for (const std::string& link : links) {
      Component& state = data.resolve_mapped(node, link, c);
      SubsetMultiMappingInputs::Input in;
      bool found = false;
      for (std::size_t k = 0; k < states.size() && !found; ++k) {
        if (states[k] != &state) continue;
        if (is_rigid_template(data.text(state, "template", "Vec3d"))) {
          throw make_error("input ", link, " is a Rigid3 state: only Vec3 inputs are supported (SubsetMultiMapping<Vec3, Vec3>)");
        }
        std::vector<Index> own_points;
        for (Index i = 0; i < sizes[k]; ++i) own_points.push_back(offsets[k] + i);
        in.map = PointMapping<double>::subset(own_points);
        found = true;
      }
      for (std::size_t m = 0; m < object.mapped_states.size() && !found; ++m) {
        const MappedState& mapped = object.mapped_states[m];
        if (mapped.node != state.node->path || mapped.name != state.sofa_name()) continue;
        if (mapped.coordinates == 1) throw make_error("input ", link, " is a Vec1 state (a DistanceMapping's output): not a Vec3 input");
        if (mapped.through) {
          throw make_error("input ", link, " is itself below a SubsetMultiMapping or follows several rigid bodies: not supported");
        }
        in.map = mapped.map;
        in.rigid = mapped.rigid;
        found = true;
      }
      if (!found) {
        throw make_error("input ", link, " (", state.where(), ") is not a state this node's ODE solver integrates, ",
                         "nor one mapped from such a state");
      }
      read.inputs.push_back(std::move(in));
    }
    const std::vector<Index> pairs = data.indices(c, "indexPairs");
    if (pairs.size() % 2 != 0) throw make_error("indexPairs has ", pairs.size(), " numbers: pairs (input, index) are needed");
    for (std::size_t i = 0; i < pairs.size(); i += 2) {
      if (pairs[i] < 0 || static_cast<std::size_t>(pairs[i]) >= read.inputs.size()) {
        throw make_error("indexPairs: point ", i / 2, " takes input ", pairs[i], ", there are ", read.inputs.size(), " inputs");
      }
      const std::size_t k = static_cast<std::size_t>(pairs[i]);
      const std::size_t available = read.inputs[k].rigid ? read.inputs[k].rigid->size() : read.inputs[k].map.size();
      if (pairs[i + 1] < 0 || static_cast<std::size_t>(pairs[i + 1]) >= available) {
        throw make_error("indexPairs: point ", i / 2, " takes point ", pairs[i + 1], " of input ", k, " (", links[k], "), which has ",
                         available, " points");
      }
      read.pairs.emplace_back(k, pairs[i + 1]);
    }
    if (read.pairs.empty()) throw make_error("indexPairs is empty: the mapped state would have no points");
    return read;
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

}  // namespace fastcorot::scene_detail
