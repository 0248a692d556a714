// SOFA's PointsFromIndices (Sofa.Component.Engine.Select, PointsFromIndices.inl, master
// 2a278d891f), Vec3 only: indices_position lists position[i] for each i of `indices`, in that order,
// leaving out a point equal to one already listed (SOFA's Vec3 ==: every coordinate less than 1e-6
// away). Without a position it reads the position of the mechanical state of its node or the
// nearest above, as SOFA links it at init; an empty position gives an empty output.
#include "engine_data.h"

#include <cmath>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {
namespace {

constexpr double kVectorThreshold = 1e-6;  // SOFA's EQUALITY_THRESHOLD (type::Vec ==)

bool same_point(const Vec3<double>& a, const Vec3<double>& b) {
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(a[i] - b[i]) < kVectorThreshold)) return false;
  }
  return true;
}

bool is_vec3_state(SceneData& scene, Component& state) {
  const std::string tmpl = scene.text(state, "template", "Vec3d");
  return tmpl == "Vec3d" || tmpl == "Vec3f" || tmpl == "Vec3";
}

}  // namespace

Numbers points_from_indices(SceneData& scene, Component& c, const std::string& name) {
  const std::string tmpl = scene.text(c, "template", "Vec3d");
  if (tmpl != "Vec3d" && tmpl != "Vec3f" && tmpl != "Vec3") {
    throw make_error(c.where(), ": template \"", tmpl, "\" is not supported (Vec3 only, as in SOFA)");
  }
  if (name == "position") {
    for (const GraphNode* scope = c.node; scope; scope = scope->parent) {
      for (Component* state : scope->of_category("state")) {
        if (is_vec3_state(scene, *state)) return scene.data(*state, "position");
      }
    }
    return {};
  }
  if (name != "indices_position") return {};
  const auto positions = points_from(scene.data(c, "position"), c, "position");
  if (positions.empty()) return {};
  const std::vector<Index> indices = c.has("indices") ? scene.indices(c, "indices") : std::vector<Index>{};
  std::vector<Vec3<double>> selected;
  for (const Index i : indices) {
    if (static_cast<std::size_t>(i) >= positions.size()) {
      throw make_error(c.where(), ": indices: ", i, " is out of range (position has ", positions.size(), " points)");
    }
    const Vec3<double>& p = positions[static_cast<std::size_t>(i)];
    bool listed = false;
    for (const auto& q : selected) listed = listed || same_point(q, p);
    if (!listed) selected.push_back(p);
  }
  Numbers out;
  out.reserve(3 * selected.size());
  for (const auto& p : selected) out.insert(out.end(), {p.x(), p.y(), p.z()});
  return out;
}

}  // namespace fastcorot::scene_detail
