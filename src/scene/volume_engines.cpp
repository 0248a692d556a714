// SOFA's volume engines (Sofa.Component.Engine.Generate; SoftRobots had them before): the volume of
// a mesh's elements, or inside a closed surface, from the positions as the scene is built.
//   VolumeFromVolumetricElements (VolumeFromTetrahedrons): Σ |det(p1 - p0, p2 - p0, p3 - p0)| / 6 over
//     the tetrahedra, and each hexahedron as SOFA's six tetrahedra (n0 n5 n1 n6, n0 n1 n3 n6,
//     n1 n3 n6 n2, n6 n3 n0 n7, n6 n7 n0 n5, n7 n5 n4 n0); the sum's absolute value.
//   VolumeFromTriangles: the divergence theorem on x, per triangle ((p1 - p0) × (p2 - p0))_x ·
//     (x0 + x1 + x2) / 6, each quad as (0 1 2) and (0 2 3); the sum's absolute value (meaningful
//     for a closed surface only, as SOFA says).
// Positions default to the nearest MechanicalObject's at or above the engine, elements to its
// node's topology's. SOFA's `update` recomputes at each step; here the volume is that of init.
#include "scene_data.h"

#include <cmath>

namespace fastcorot::scene_detail {

namespace {

double tetrahedron_volume(const Vec3<double>& a, const Vec3<double>& b, const Vec3<double>& c, const Vec3<double>& d) {
  return std::abs((b - a).cross(c - a).dot(d - a) / 6);
}

double triangle_term(const Vec3<double>& p0, const Vec3<double>& p1, const Vec3<double>& p2) {
  return ((p1[1] - p0[1]) * (p2[2] - p0[2]) - (p2[1] - p0[1]) * (p1[2] - p0[2])) * (p0[0] + p1[0] + p2[0]) / 6;
}

}  // namespace

double SceneData::engine_volume(Component& c) {
  std::vector<Vec3<double>> x;
  if (c.has("position")) {
    x = points(c, "position");
  } else {
    for (const GraphNode* node = c.node; node && x.empty(); node = node->parent) {
      const auto states = node->of_category("state");
      if (!states.empty()) x = points(*states.front(), "position");
    }
  }
  if (x.empty()) throw make_error(c.where(), ": no position given and no MechanicalObject at or above its node");
  Component* topology = topology_of(*c.node);
  const auto elements = [&](const char* own, const char* of_topology, std::size_t corners) {
    Numbers values;
    if (c.has(own)) {
      values = data(c, own);
    } else if (topology) {
      values = data(*topology, of_topology);
    }
    if (values.size() % corners != 0) throw make_error(c.where(), ": ", own, " needs ", corners, " point indices each");
    std::vector<std::size_t> out;
    for (const double v : values) {
      if (v < 0 || v >= static_cast<double>(x.size())) {
        throw make_error(c.where(), ": ", own, " names point ", v, " of ", x.size());
      }
      out.push_back(static_cast<std::size_t>(v));
    }
    return out;
  };
  double volume = 0;
  if (c.type() == "VolumeFromTriangles") {  // else VolumeFromVolumetricElements (VolumeFromTetrahedrons)
    const auto triangles = elements("triangles", "triangles", 3);
    const auto quads = elements("quads", "quads", 4);
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
      volume += triangle_term(x[triangles[t]], x[triangles[t + 1]], x[triangles[t + 2]]);
    }
    for (std::size_t q = 0; q < quads.size(); q += 4) {
      volume += triangle_term(x[quads[q]], x[quads[q + 1]], x[quads[q + 2]]);
      volume += triangle_term(x[quads[q]], x[quads[q + 2]], x[quads[q + 3]]);
    }
  } else {
    const auto tetrahedra = elements("tetras", "tetrahedra", 4);
    const auto hexahedra = elements("hexas", "hexahedra", 8);
    for (std::size_t t = 0; t < tetrahedra.size(); t += 4) {
      volume += tetrahedron_volume(x[tetrahedra[t]], x[tetrahedra[t + 1]], x[tetrahedra[t + 2]], x[tetrahedra[t + 3]]);
    }
    for (std::size_t h = 0; h < hexahedra.size(); h += 8) {
      const auto n = [&](std::size_t k) -> const Vec3<double>& { return x[hexahedra[h + k]]; };
      volume += tetrahedron_volume(n(0), n(5), n(1), n(6)) + tetrahedron_volume(n(0), n(1), n(3), n(6)) +
                tetrahedron_volume(n(1), n(3), n(6), n(2)) + tetrahedron_volume(n(6), n(3), n(0), n(7)) +
                tetrahedron_volume(n(6), n(7), n(0), n(5)) + tetrahedron_volume(n(7), n(5), n(4), n(0));
    }
  }
  if (c.has("update") && boolean(c, "update", false)) {
    warn(c.where() + ": update: the volume is the one of init here (SOFA recomputes it at each step)");
  }
  return std::abs(volume);
}

}  // namespace fastcorot::scene_detail
