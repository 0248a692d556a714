// SOFA's MeshSplittingEngine (Sofa.Component.Engine.Select, MeshSplittingEngine.inl, master
// 2a278d891f): shares a mesh's points among nbInputs sub-meshes and a last one for the rest. Sub-mesh
// i (1-based) takes the points listed in indices<i> and the points of the elements listed in
// edgeIndices<i>, triangleIndices<i>, quadIndices<i>, tetrahedronIndices<i>, hexahedronIndices<i>;
// a point claimed by several takes the first. Outputs: position<i> (i = 1..nbInputs + 1), each
// sub-mesh's points in input order, and indexPairs (sub-mesh, index in it) per input point, as
// SubsetMultiMapping reads them (sub-meshes numbered from 0 there).
#include "engine_data.h"

#include <cmath>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

// The k of "position<k>" (k >= 1), or 0 when `name` is not such a name.
std::size_t numbered(const std::string& name, const std::string& stem) {
  if (name.size() <= stem.size() || name.compare(0, stem.size(), stem) != 0) return 0;
  std::size_t k = 0;
  for (std::size_t i = stem.size(); i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9' || k > 100000) return 0;
    k = 10 * k + static_cast<std::size_t>(name[i] - '0');
  }
  return k;
}

struct ElementList {
  const char* elements;  // the input data, e.g. "tetrahedra"
  const char* indices;   // the per-sub-mesh list stem, e.g. "tetrahedronIndices"
  std::size_t corners;
};
constexpr ElementList kElementLists[] = {{"edges", "edgeIndices", 2},           {"triangles", "triangleIndices", 3},
                                         {"quads", "quadIndices", 4},           {"tetrahedra", "tetrahedronIndices", 4},
                                         {"hexahedra", "hexahedronIndices", 8}};

}  // namespace

Numbers mesh_splitting_engine(SceneData& scene, Component& c, const std::string& name) {
  for (const auto& list : kElementLists) {
    if (name == list.elements) return from_src(scene, c, name).value_or(Numbers{});
  }
  if (name == "position") return from_src(scene, c, name).value_or(Numbers{});
  const std::size_t output = numbered(name, "position");
  if (name != "indexPairs" && output == 0) return {};
  const int nb_inputs = scene.whole_number(c, "nbInputs", 0);
  if (nb_inputs < 0) throw make_error(c.where(), ": nbInputs = ", nb_inputs, ": expected a count >= 0");
  const auto nb = static_cast<std::size_t>(nb_inputs);
  if (output > nb + 1) {
    throw make_error(c.where(), ": no output ", name, ": nbInputs = ", nb, " gives position1 to position", nb + 1);
  }
  const auto points = points_from(scene.data(c, "position"), c, "position");
  const std::size_t n = points.size();

  // Each point's sub-mesh: the rest by default, then the lists from the last sub-mesh to the first.
  std::vector<std::size_t> part(n, nb);
  const auto claim = [&](const std::string& list, double v, std::size_t i) {
    if (!(v >= 0) || v >= static_cast<double>(n) || v != std::floor(v)) {
      throw make_error(c.where(), ": ", list, " reaches point ", v, ", not an index below the ", n, " points");
    }
    part[static_cast<std::size_t>(v)] = i;
  };
  for (std::size_t i = nb; i-- > 0;) {
    const std::string suffix = std::to_string(i + 1);
    if (c.has("indices" + suffix)) {
      for (Index v : scene.indices(c, "indices" + suffix)) claim("indices" + suffix, v, i);
    }
    for (const auto& list : kElementLists) {
      const std::string list_name = list.indices + suffix;
      if (!c.has(list_name)) continue;
      const Numbers& elements = scene.data(c, list.elements);
      if (elements.size() % list.corners != 0) {
        throw make_error(c.where(), ": ", list.elements, " needs ", list.corners, " point indices per element");
      }
      const std::size_t count = elements.size() / list.corners;
      for (Index e : scene.indices(c, list_name)) {
        if (static_cast<std::size_t>(e) >= count) {
          throw make_error(c.where(), ": ", list_name, " has element ", e, " of ", count, " ", list.elements);
        }
        for (std::size_t k = 0; k < list.corners; ++k) {
          claim(list_name, elements[static_cast<std::size_t>(e) * list.corners + k], i);
        }
      }
    }
  }

  Numbers pairs(2 * n);
  std::vector<Numbers> positions(nb + 1);
  for (std::size_t v = 0; v < n; ++v) {
    Numbers& target = positions[part[v]];
    pairs[2 * v] = static_cast<double>(part[v]);
    pairs[2 * v + 1] = static_cast<double>(target.size() / 3);
    target.insert(target.end(), {points[v][0], points[v][1], points[v][2]});
  }
  // Every output at once (unless written in the scene).
  if (!c.has("indexPairs")) c.cache.emplace("indexPairs", pairs);
  for (std::size_t i = 0; i <= nb; ++i) {
    const std::string position = "position" + std::to_string(i + 1);
    if (!c.has(position)) c.cache.emplace(position, positions[i]);
  }
  return output == 0 ? pairs : positions[output - 1];
}

}  // namespace fastcorot::scene_detail
