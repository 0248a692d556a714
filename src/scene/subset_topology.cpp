// SOFA's SubsetTopology (Sofa.Component.Engine.Select, SubsetTopology.inl, master 2a278d891f):
// the points and elements of a mesh inside axis-aligned boxes (bounds included, reversed bounds
// swapped) or, when `centers` is given, spheres (distance <= radius). An element is inside when all
// its points are inside one same region. With localIndices the outputs are renumbered for the two
// sub-meshes: the points on the border (inside the first region, in a tetrahedron, else a triangle,
// that has points outside it) come first in both point lists, then the other points inside (or
// outside), each element's indices replaced by those local numbers. With tetrahedraInput the
// tetrahedra listed there are inside whatever the regions, and the point lists are rebuilt from
// the tetrahedra's points (indices keeping, as SOFA's does, the points found by the regions).
#include "engine_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

using Point = Vec3<double>;

struct Regions {
  std::vector<std::array<double, 6>> boxes;
  std::vector<Point> centres;
  std::vector<double> radii;
  bool spheres = false;

  std::size_t count() const { return spheres ? centres.size() : boxes.size(); }
  bool contains(const Point& p, std::size_t r) const {
    if (!spheres) {
      const auto& b = boxes[r];
      return p[0] >= b[0] && p[0] <= b[3] && p[1] >= b[1] && p[1] <= b[4] && p[2] >= b[2] && p[2] <= b[5];
    }
    const Point d = p - centres[r];
    return !(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) > radii[r]);
  }
};

void push_point(Numbers& out, const Point& p) { out.insert(out.end(), {p[0], p[1], p[2]}); }

template <std::size_t N>
void push_cell(Numbers& out, const std::array<Index, N>& cell) {
  for (Index v : cell) out.push_back(static_cast<double>(v));
}

// The element kinds, their input data and outputs, in the order SOFA selects them.
struct Kind {
  const char* elements;
  const char* indices;
  const char* in_roi;
  const char* out_roi;
};
constexpr Kind kEdges{"edges", "edgeIndices", "edgesInROI", "edgesOutROI"};
constexpr Kind kTriangles{"triangles", "triangleIndices", "trianglesInROI", "trianglesOutROI"};
constexpr Kind kQuads{"quads", "quadIndices", "quadsInROI", "quadsOutROI"};
constexpr Kind kTetrahedra{"tetrahedra", "tetrahedronIndices", "tetrahedraInROI", "tetrahedraOutROI"};
constexpr Kind kHexahedra{"hexahedra", "hexahedronIndices", "hexahedraInROI", "hexahedraOutROI"};

class Subset {
 public:
  Subset(SceneData& scene, Component& c) : scene_(scene), c_(c) {}

  std::map<std::string, Numbers> select() {
    read_regions();
    points_ = points_from(scene_.data(c_, "rest_position"), c_, "rest_position");
    const auto edges = cells<2>(kEdges);
    const auto triangles = cells<3>(kTriangles);
    const auto quads = cells<4>(kQuads);
    const auto tetrahedra = cells<4>(kTetrahedra);
    const auto hexahedra = cells<8>(kHexahedra);
    const bool local = scene_.boolean(c_, "localIndices", false);
    local_.assign(points_.size(), 0);

    for (const Kind& kind : {kEdges, kTriangles, kQuads, kTetrahedra, kHexahedra}) {
      for (const char* output : {kind.indices, kind.in_roi, kind.out_roi}) out_[output] = {};
    }
    Numbers& indices = out_["indices"];
    Numbers& in = out_["pointsInROI"];
    Numbers& out = out_["pointsOutROI"];

    // Border points (first region only, as SOFA tests them): in tetrahedra, else in triangles.
    std::vector<bool> border(points_.size(), false);
    std::size_t border_count = 0;
    if (local && regions_.count() > 0) {
      const auto mark = [&](const auto& elements) {
        for (const auto& cell : elements) {
          bool found_in = false, found_out = false;
          for (Index v : cell) (regions_.contains(point(v), 0) ? found_in : found_out) = true;
          if (!found_in || !found_out) continue;
          for (Index v : cell) {
            if (regions_.contains(point(v), 0)) border[static_cast<std::size_t>(v)] = true;
          }
        }
      };
      if (tetrahedra.empty()) {
        mark(triangles);
      } else {
        mark(tetrahedra);
      }
      border_count = static_cast<std::size_t>(std::count(border.begin(), border.end(), true));
    }
    out_["nbrborder"] = {static_cast<double>(border_count)};

    // Points: border points first in both lists, then the others in or out.
    Numbers border_points;
    Numbers inside_indices, inside_points, outside_points;
    Index in_count = static_cast<Index>(border_count), out_count = in_count, border_rank = 0;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      if (border[i]) {
        local_[i] = border_rank++;
        indices.push_back(static_cast<double>(i));
        push_point(border_points, points_[i]);
        continue;
      }
      bool inside = false;
      for (std::size_t r = 0; r < regions_.count() && !inside; ++r) inside = regions_.contains(points_[i], r);
      if (inside) {
        inside_indices.push_back(static_cast<double>(i));
        push_point(inside_points, points_[i]);
        if (local) local_[i] = in_count++;
      } else {
        push_point(outside_points, points_[i]);
        if (local) local_[i] = out_count++;
      }
    }
    indices.insert(indices.end(), inside_indices.begin(), inside_indices.end());
    in = border_points;
    in.insert(in.end(), inside_points.begin(), inside_points.end());
    out = border_points;
    out.insert(out.end(), outside_points.begin(), outside_points.end());

    select_cells(kEdges, edges, local);
    select_cells(kTriangles, triangles, local);
    select_cells(kQuads, quads, local);
    if (c_.has("tetrahedraInput")) {
      select_listed_tetrahedra(tetrahedra, local);
    } else {
      select_cells(kTetrahedra, tetrahedra, local);
    }
    select_cells(kHexahedra, hexahedra, local);
    return std::move(out_);
  }

 private:
  const Point& point(Index v) const { return points_[static_cast<std::size_t>(v)]; }

  void read_regions() {
    const Numbers& box = scene_.data(c_, "box");
    if (box.size() % 6 != 0) {
      throw make_error(c_.where(), ": box needs 6 numbers per box (xmin ymin zmin xmax ymax zmax), got ", box.size());
    }
    for (std::size_t b = 0; b < box.size(); b += 6) {
      std::array<double, 6> v;
      std::copy(box.begin() + static_cast<std::ptrdiff_t>(b), box.begin() + static_cast<std::ptrdiff_t>(b + 6), v.begin());
      for (std::size_t k = 0; k < 3; ++k) {
        if (v[k] > v[k + 3]) std::swap(v[k], v[k + 3]);
      }
      regions_.boxes.push_back(v);
    }
    regions_.spheres = c_.has("centers");
    if (!regions_.spheres) return;
    regions_.centres = points_from(scene_.data(c_, "centers"), c_, "centers");
    regions_.radii = scene_.data(c_, "radii");
    // SOFA leaves its outputs as they were (with a warning when the counts differ).
    if (regions_.centres.empty()) throw make_error(c_.where(), ": centers is given but empty");
    if (regions_.centres.size() != regions_.radii.size()) {
      throw make_error(c_.where(), ": ", regions_.centres.size(), " centers but ", regions_.radii.size(),
                       " radii: one radius per sphere");
    }
  }

  template <std::size_t N>
  std::vector<std::array<Index, N>> cells(const Kind& kind) {
    return cells_from<N>(scene_.data(c_, kind.elements), c_, kind.elements, points_.size());
  }

  template <std::size_t N>
  std::array<Index, N> renumbered(std::array<Index, N> cell, bool local) const {
    if (local) {
      for (Index& v : cell) v = local_[static_cast<std::size_t>(v)];
    }
    return cell;
  }

  template <std::size_t N>
  void select_cells(const Kind& kind, const std::vector<std::array<Index, N>>& elements, bool local) {
    for (std::size_t e = 0; e < elements.size(); ++e) {
      bool inside = false;
      for (std::size_t r = 0; r < regions_.count() && !inside; ++r) {
        inside = std::all_of(elements[e].begin(), elements[e].end(),
                             [&](Index v) { return regions_.contains(point(v), r); });
      }
      if (inside) {
        out_[kind.indices].push_back(static_cast<double>(e));
        push_cell(out_[kind.in_roi], renumbered(elements[e], local));
      } else {
        push_cell(out_[kind.out_roi], renumbered(elements[e], local));
      }
    }
  }

  // tetrahedraInput: the listed tetrahedra are inside; each sub-mesh's points are its tetrahedra's,
  // numbered in the order met.
  void select_listed_tetrahedra(const std::vector<std::array<Index, 4>>& tetrahedra, bool local) {
    const std::vector<Index> listed = scene_.indices(c_, "tetrahedraInput");
    std::vector<bool> seen_in(points_.size(), false), seen_out(points_.size(), false);
    std::vector<Index> local_out(points_.size(), 0);
    Numbers& in = out_["pointsInROI"];
    Numbers& out = out_["pointsOutROI"];
    in.clear();
    out.clear();
    Index in_count = 0, out_count = 0;
    for (std::size_t i = 0; i < tetrahedra.size(); ++i) {
      auto t = tetrahedra[i];
      const bool inside = std::find(listed.begin(), listed.end(), static_cast<Index>(i)) != listed.end();
      for (Index& v : t) {
        const auto p = static_cast<std::size_t>(v);
        if (inside && !seen_in[p]) {
          seen_in[p] = true;
          out_["indices"].push_back(static_cast<double>(v));
          push_point(in, points_[p]);
          if (local) local_[p] = in_count++;
        } else if (!inside && !seen_out[p]) {
          seen_out[p] = true;
          push_point(out, points_[p]);
          if (local) local_out[p] = out_count++;
        }
        if (local) v = inside ? local_[p] : local_out[p];
      }
      if (inside) out_["tetrahedronIndices"].push_back(static_cast<double>(i));
      push_cell(out_[inside ? "tetrahedraInROI" : "tetrahedraOutROI"], t);
    }
  }

  SceneData& scene_;
  Component& c_;
  Regions regions_;
  std::vector<Point> points_;
  std::vector<Index> local_;  // each point's index in its sub-mesh
  std::map<std::string, Numbers> out_;
};

// The nearest MechanicalObject at or above the node (SOFA links rest_position to its position).
Component* state_around(const GraphNode& node) {
  for (const GraphNode* scope = &node; scope; scope = scope->parent) {
    const auto states = scope->of_category("state");
    if (!states.empty()) return states.front();
  }
  return nullptr;
}

}  // namespace

std::optional<Numbers> from_src(SceneData& scene, Component& c, const std::string& name) {
  const auto src = c.object->attributes.find("src");
  if (src == c.object->attributes.end()) return std::nullopt;
  return scene.data(scene.resolve_object(*c.node, src->second, c), name);
}

Numbers subset_topology(SceneData& scene, Component& c, const std::string& name) {
  if (const std::string t = scene.text(c, "template", "Vec3"); t.rfind("Rigid", 0) == 0) {
    throw make_error(c.where(), ": template ", t, " (rigid frames) is not supported, Vec3 only");
  }
  if (name == "box") return {0, 0, 0, 1, 1, 1};
  if (name == "rest_position") {
    // SOFA: the context's MechanicalObject's position; a loader has no rest_position to give.
    if (Component* state = state_around(*c.node)) return scene.data(*state, "position");
    return {};
  }
  if (name == "edges" || name == "triangles" || name == "quads" || name == "tetrahedra" || name == "hexahedra") {
    if (auto given = from_src(scene, c, name)) return *given;
    // SOFA links edges, triangles and tetrahedra (not quads or hexahedra) to the context's topology.
    if (name == "quads" || name == "hexahedra") return {};
    Component* topology = scene.topology_of(*c.node);
    return topology ? scene.data(*topology, name) : Numbers{};
  }
  static const std::vector<std::string> kOutputs = {
      "indices", "pointsInROI", "pointsOutROI", "nbrborder", "edgeIndices", "edgesInROI", "edgesOutROI",
      "triangleIndices", "trianglesInROI", "trianglesOutROI", "quadIndices", "quadsInROI", "quadsOutROI",
      "tetrahedronIndices", "tetrahedraInROI", "tetrahedraOutROI", "hexahedronIndices", "hexahedraInROI",
      "hexahedraOutROI"};
  if (std::find(kOutputs.begin(), kOutputs.end(), name) == kOutputs.end()) return {};
  auto outputs = Subset(scene, c).select();
  // Every output at once: the others are kept for later reads (unless written in the scene).
  for (auto& [output, value] : outputs) {
    if (output != name && !c.has(output)) c.cache.emplace(output, value);
  }
  return outputs[name];
}

}  // namespace fastcorot::scene_detail
