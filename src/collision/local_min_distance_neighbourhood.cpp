// LocalMinDistance's neighbourhood: the shells its cone filters read from a model's topology, and
// the cones at given positions (collision/local_min_distance.h).
#include "fastcorot/collision/local_min_distance.h"

#include "fastcorot/core/error.h"
#include "sofa_vec.h"

#include <algorithm>
#include <map>

namespace fastcorot {

using sofa_vec::sofa_normalized;
using sofa_vec::unit_triangle_normal;

LocalMinDistanceTopology local_min_distance_topology(Index point_count,
                                                     std::span<const Triangle> triangles,
                                                     std::span<const Edge> edges) {
  if (point_count < 0) throw make_error("LocalMinDistance: negative point count ", point_count);
  const auto check = [&](Index v, const char* what, std::size_t i) {
    if (v < 0 || v >= point_count)
      throw make_error("LocalMinDistance: ", what, " ", i, " names point ", v, " of ", point_count);
  };
  LocalMinDistanceTopology t;
  t.point_count = point_count;
  t.triangles.assign(triangles.begin(), triangles.end());
  t.edges.assign(edges.begin(), edges.end());
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (Index v : triangles[i]) check(v, "triangle", i);
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (Index v : edges[i]) check(v, "edge", i);

  // Shells by counting sort: each list in ascending element order, as SOFA's topologies build them.
  const auto build = [&](auto&& each_corner, std::size_t count, std::vector<Index>& offsets,
                         std::vector<Index>& items, auto&& item) {
    offsets.assign(point_count + 1, 0);
    for (std::size_t i = 0; i < count; ++i)
      each_corner(i, [&](Index v, std::size_t) { ++offsets[v + 1]; });
    for (Index v = 0; v < point_count; ++v) offsets[v + 1] += offsets[v];
    items.resize(offsets[point_count]);
    std::vector<Index> next(offsets.begin(), offsets.end() - 1);
    for (std::size_t i = 0; i < count; ++i)
      each_corner(i, [&](Index v, std::size_t k) { items[next[v]++] = item(i, k); });
  };
  build(
      [&](std::size_t i, auto&& f) {
        for (std::size_t k = 0; k < 3; ++k) f(triangles[i][k], k);
      },
      triangles.size(), t.vertex_triangle_offsets, t.vertex_triangles,
      [](std::size_t i, std::size_t) { return Index(i); });
  build(
      [&](std::size_t i, auto&& f) {
        for (std::size_t k = 0; k < 2; ++k) f(edges[i][k], k);
      },
      edges.size(), t.vertex_edge_offsets, t.vertex_edge_other,
      [&](std::size_t i, std::size_t k) { return edges[i][1 - k]; });

  // Triangles around each edge in SOFA's order (MeshTopology and TriangleSetTopologyContainer
  // createTrianglesAroundEdgeArray): triangle i's edge j is (t[j+1], t[j+2]); a triangle listing it
  // in the edge's stored direction goes in front, any other at the back.
  std::map<std::pair<Index, Index>, Index> edge_of;
  const auto key = [](Index u, Index v) { return std::make_pair(std::min(u, v), std::max(u, v)); };
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto [it, fresh] = edge_of.emplace(key(edges[i][0], edges[i][1]), Index(i));
    if (!fresh)
      throw make_error("LocalMinDistance: edge ", i, " (", edges[i][0], ", ", edges[i][1],
                       ") repeats edge ", it->second);
  }
  std::vector<std::vector<Index>> around(edges.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      const Index from = triangles[i][(j + 1) % 3], to = triangles[i][(j + 2) % 3];
      const auto it = edge_of.find(key(from, to));
      if (it == edge_of.end())
        continue;  // an edge the list lacks (SOFA's topologies derive them all)
      auto& list = around[it->second];
      if (edges[it->second][0] == from)
        list.insert(list.begin(), Index(i));
      else
        list.push_back(Index(i));
    }
  }
  // LocalMinDistance's left: the list's first triangle when it lists the edge as stored, else the
  // second (unchecked); right: the other.
  t.edge_right_left.assign(edges.size(), {-1, -1});
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (around[i].size() != 2) continue;
    const Triangle& first = triangles[around[i][0]];
    const Edge& e = edges[i];
    const bool first_is_left = (e[0] == first[0] && e[1] == first[1]) ||
                               (e[0] == first[1] && e[1] == first[2]) ||
                               (e[0] == first[2] && e[1] == first[0]);
    t.edge_right_left[i] = first_is_left ? std::array<Index, 2>{around[i][1], around[i][0]}
                                         : std::array<Index, 2>{around[i][0], around[i][1]};
  }
  return t;
}

template <class Real>
LocalMinDistancePointCone<Real> LocalMinDistanceNeighbourhood<Real>::point_cone(
    Index vertex, bool both_side) const {
  LocalMinDistancePointCone<Real> cone;
  cone.normal_sum = normal_sum.at(vertex);
  cone.edge_directions =
      std::span<const Vec3<Real>>(edge_directions)
          .subspan(edge_offsets[vertex], edge_offsets[vertex + 1] - edge_offsets[vertex]);
  cone.both_side = both_side;
  return cone;
}

template <class Real>
LocalMinDistanceLineCone<Real> LocalMinDistanceNeighbourhood<Real>::line_cone(
    Index edge, bool both_side) const {
  LocalMinDistanceLineCone<Real> cone = line_cones.at(edge);
  cone.both_side = both_side;
  return cone;
}

template <class Real>
void compute_local_min_distance_neighbourhood(const LocalMinDistanceTopology& topology,
                                              std::span<const Vec3<Real>> x,
                                              LocalMinDistanceNeighbourhood<Real>& out) {
  if (x.size() != std::size_t(topology.point_count)) {
    throw make_error("LocalMinDistance: ", x.size(), " positions for a topology of ",
                     topology.point_count, " points");
  }
  const auto normal = [&](Index t) {
    const Triangle& tri = topology.triangles[t];
    return unit_triangle_normal(x[tri[0]], x[tri[1]], x[tri[2]]);
  };
  const Index n = topology.point_count;
  out.normal_sum.assign(n, Vec3<Real>::Zero());
  out.edge_offsets = topology.vertex_edge_offsets;
  out.edge_directions.resize(topology.vertex_edge_other.size());
  for (Index v = 0; v < n; ++v) {
    const Index e0 = topology.vertex_edge_offsets[v], e1 = topology.vertex_edge_offsets[v + 1];
    for (Index k = e0; k < e1; ++k)
      out.edge_directions[k] = sofa_normalized(Vec3<Real>(x[v] - x[topology.vertex_edge_other[k]]));
    Vec3<Real>& sum = out.normal_sum[v];
    const Index t0 = topology.vertex_triangle_offsets[v],
                t1 = topology.vertex_triangle_offsets[v + 1];
    for (Index k = t0; k < t1; ++k) sum += normal(topology.vertex_triangles[k]);
    if (t0 == t1) {
      for (Index k = e0; k < e1; ++k) sum += out.edge_directions[k];
    }
  }
  out.line_cones.assign(topology.edges.size(), LocalMinDistanceLineCone<Real>{});
  for (std::size_t i = 0; i < topology.edges.size(); ++i) {
    const auto [right, left] = topology.edge_right_left[i];
    if (right < 0) continue;
    out.line_cones[i].two_triangles = true;
    out.line_cones[i].right_normal = normal(right);
    out.line_cones[i].left_normal = normal(left);
  }
}

#define FASTCOROT_LOCAL_MIN_DISTANCE_NEIGHBOURHOOD(Real)                                  \
  template struct LocalMinDistanceNeighbourhood<Real>;                                    \
  template void compute_local_min_distance_neighbourhood(const LocalMinDistanceTopology&, \
                                                         std::span<const Vec3<Real>>,     \
                                                         LocalMinDistanceNeighbourhood<Real>&);
FASTCOROT_LOCAL_MIN_DISTANCE_NEIGHBOURHOOD(float)
FASTCOROT_LOCAL_MIN_DISTANCE_NEIGHBOURHOOD(double)
#undef FASTCOROT_LOCAL_MIN_DISTANCE_NEIGHBOURHOOD

}  // namespace fastcorot
