#include "fastcorot/collision/self_collision.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <array>

namespace fastcorot {

SelfCollisionTopology self_collision_topology(Index point_count, std::span<const Edge> edges) {
  SelfCollisionTopology t;
  t.vertices_around_vertex.resize(static_cast<std::size_t>(point_count));
  t.edges_around_vertex.resize(static_cast<std::size_t>(point_count));
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Edge& edge = edges[e];
    for (const Index end : edge) {
      if (end < 0 || end >= point_count) throw make_error("self-collision: edge ", e, " has end ", end, ", outside the ", point_count, " points");
    }
    for (int side = 0; side < 2; ++side) {
      const auto v = static_cast<std::size_t>(edge[side]);
      t.edges_around_vertex[v].push_back(static_cast<Index>(e));
      t.vertices_around_vertex[v].push_back(edge[1 - side]);
    }
  }
  return t;
}

namespace {

bool contains(const std::vector<Index>& list, Index value) { return std::find(list.begin(), list.end(), value) != list.end(); }

bool shares_any(const std::vector<Index>& a, const std::vector<Index>& b) {
  return std::any_of(a.begin(), a.end(), [&](Index x) { return contains(b, x); });
}

template <class Real>
bool element_rule(std::span<const CollisionModel<Real>> models, std::size_t a, Index e1, std::size_t b, Index e2, bool delegated) {
  const CollisionModel<Real>& m = models[a];
  const CollisionModel<Real>& other = models[b];
  if (!m.self_collision || m.node != other.node) return true;
  const auto delegate = [&] { return delegated || element_rule<Real>(models, b, e2, a, e1, true); };
  const SelfCollisionTopology* t = m.self_topology.get();
  switch (m.kind) {
    case CollisionElements::triangles: {
      if (!other.node_point_model) return true;
      const Triangle& tri = m.triangles[static_cast<std::size_t>(e1)];
      return e2 != tri[0] && e2 != tri[1] && e2 != tri[2];
    }
    case CollisionElements::lines: {
      const Edge& s = m.edges[static_cast<std::size_t>(e1)];
      if (a == b) {
        const Edge& u = m.edges[static_cast<std::size_t>(e2)];
        if (s[0] == u[0] || s[0] == u[1] || s[1] == u[0] || s[1] == u[1]) return false;
        if (!t) return true;  // SOFA: no topology, an error and no pruning
        const auto& around = t->edges_around_vertex;
        for (const Index mine : {s[0], s[1]}) {
          for (const Index theirs : {u[0], u[1]}) {
            if (shares_any(around[static_cast<std::size_t>(mine)], around[static_cast<std::size_t>(theirs)])) return false;
          }
        }
        return true;
      }
      if (other.node_point_model) {
        if (e2 == s[0] || e2 == s[1]) return false;
        if (!t) return true;
        for (const Index end : {s[0], s[1]}) {
          for (const Index edge : t->edges_around_vertex[static_cast<std::size_t>(end)]) {
            const Edge& near = m.edges[static_cast<std::size_t>(edge)];
            if (e2 == near[0] || e2 == near[1]) return false;
          }
        }
        return true;
      }
      return delegate();
    }
    case CollisionElements::points: {
      if (a != b) return delegate();
      if (e1 <= e2) return false;  // each pair once: (i, j) with i > j
      if (!t) return true;
      const auto& around1 = t->vertices_around_vertex[static_cast<std::size_t>(e1)];
      const auto& around2 = t->vertices_around_vertex[static_cast<std::size_t>(e2)];
      for (const Index v1 : around1) {
        for (const Index v2 : around2) {
          if (v1 == v2 || v1 == e2 || e1 == v2) return false;
        }
      }
      return true;
    }
    case CollisionElements::spheres: return true;
  }
  return true;
}

}  // namespace

template <class Real>
bool can_collide_elements(std::span<const CollisionModel<Real>> models, std::size_t a, Index e1, std::size_t b, Index e2) {
  return element_rule<Real>(models, a, e1, b, e2, false);
}

template <class Real>
bool elements_touch(const CollisionModel<Real>& a, Index e1, const CollisionModel<Real>& b, Index e2) {
  if (a.points != b.points) return false;
  if (a.kind != CollisionElements::triangles && b.kind != CollisionElements::triangles) return false;
  // A triangle's or segment's corners (at most three), without allocating: this runs per pair.
  const auto corners = [](const CollisionModel<Real>& m, Index e, std::array<Index, 3>& out) -> int {
    if (m.kind == CollisionElements::triangles) {
      out = m.triangles[static_cast<std::size_t>(e)];
      return 3;
    }
    if (m.kind == CollisionElements::lines) {
      const Edge& s = m.edges[static_cast<std::size_t>(e)];
      out = {s[0], s[1], s[1]};
      return 2;
    }
    return 0;
  };
  std::array<Index, 3> p{}, q{};
  const int np = corners(a, e1, p), nq = corners(b, e2, q);
  for (int i = 0; i < np; ++i) {
    for (int j = 0; j < nq; ++j) {
      if (p[static_cast<std::size_t>(i)] == q[static_cast<std::size_t>(j)]) return true;
    }
  }
  return false;
}

template bool can_collide_elements(std::span<const CollisionModel<double>>, std::size_t, Index, std::size_t, Index);
template bool elements_touch(const CollisionModel<double>&, Index, const CollisionModel<double>&, Index);

}  // namespace fastcorot
