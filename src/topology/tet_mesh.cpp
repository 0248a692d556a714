#include "fastcorot/topology/tet_mesh.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

namespace fastcorot {

namespace {

std::uint64_t edge_key(Index a, Index b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

std::unordered_map<std::uint64_t, Index> edge_lookup(std::span<const Edge> edges) {
  std::unordered_map<std::uint64_t, Index> lookup;
  lookup.reserve(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    lookup.emplace(edge_key(edges[i][0], edges[i][1]), static_cast<Index>(i));
  }
  return lookup;
}

}  // namespace

namespace {

void insert_sorted(std::vector<Index>& list, Index value) {
  list.insert(std::upper_bound(list.begin(), list.end(), value), value);
}

void erase_sorted(std::vector<Index>& list, Index value) {
  const auto it = std::lower_bound(list.begin(), list.end(), value);
  if (it != list.end() && *it == value) list.erase(it);
}

// Renames `from` to `to` in a sorted list (to < from, `to` absent).
void rename_sorted(std::vector<Index>& list, Index from, Index to) {
  erase_sorted(list, from);
  insert_sorted(list, to);
}

}  // namespace

TetMesh::TetMesh(Index num_points, std::vector<Tetrahedron> tetrahedra) : num_points_(num_points) {
  if (num_points_ < 0) throw make_error("TetMesh: negative point count ", num_points_);
  check_tetrahedra(tetrahedra, 0);
  tetrahedra_ = std::move(tetrahedra);
  // Edges in SOFA's creation order, as add_tetrahedra creates them: each tetrahedron in turn finds
  // or appends its six edges, local edges in order.
  edges_of_tetrahedron_.resize(tetrahedra_.size());
  edge_orientation_.assign(tetrahedra_.size(), 0);
  vertex_tetrahedra_.assign(static_cast<std::size_t>(num_points_), {});
  vertex_edges_.assign(static_cast<std::size_t>(num_points_), {});
  for (Index t = 0; t < num_tetrahedra(); ++t) link_tetrahedron(t);
}

TetMesh::TetMesh(Index num_points, std::vector<Tetrahedron> tetrahedra, std::vector<Edge> edges)
    : num_points_(num_points), edges_(std::move(edges)) {
  if (num_points_ < 0) throw make_error("TetMesh: negative point count ", num_points_);
  check_tetrahedra(tetrahedra, 0);
  tetrahedra_ = std::move(tetrahedra);
  std::unordered_map<std::uint64_t, Index> seen;
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const auto [a, b] = edges_[i];
    if (a < 0 || a >= num_points_ || b < 0 || b >= num_points_) {
      throw make_error("edge ", i, " (", a, ", ", b, "): vertex index out of range [0, ",
                       num_points_, ")");
    }
    if (a == b) throw make_error("edge ", i, " (", a, ", ", b, "): both ends are the same point");
    const auto [it, inserted] = seen.emplace(edge_key(a, b), static_cast<Index>(i));
    if (!inserted) {
      throw make_error("edge ", i, " (", a, ", ", b, ") repeats edge ", it->second);
    }
  }
  update_topology_information();
}

void TetMesh::check_tetrahedra(std::span<const Tetrahedron> tetrahedra, std::size_t first_index) const {
  for (std::size_t i = 0; i < tetrahedra.size(); ++i) {
    const Tetrahedron& tet = tetrahedra[i];
    const std::size_t t = first_index + i;
    for (int k = 0; k < 4; ++k) {
      if (tet[k] < 0 || tet[k] >= num_points_) {
        throw make_error("tetrahedron ", t, " (", tet[0], " ", tet[1], " ", tet[2], " ", tet[3],
                         "): vertex index ", tet[k], " out of range [0, ", num_points_, ")");
      }
      for (int j = 0; j < k; ++j) {
        if (tet[k] == tet[j]) {
          throw make_error("tetrahedron ", t, " (", tet[0], " ", tet[1], " ", tet[2], " ", tet[3],
                           "): vertex ", tet[k], " repeats");
        }
      }
    }
  }
}

void TetMesh::update_topology_information() {
  const auto lookup = edge_lookup(edges_);
  const std::size_t n = tetrahedra_.size();
  edges_of_tetrahedron_.resize(n);
  edge_orientation_.assign(n, 0);
  edge_use_.assign(edges_.size(), 0);
  for (std::size_t t = 0; t < n; ++t) {
    for (int e = 0; e < 6; ++e) {
      const Index a = tetrahedra_[t][kTetrahedronEdges[e][0]];
      const Index b = tetrahedra_[t][kTetrahedronEdges[e][1]];
      const auto it = lookup.find(edge_key(a, b));
      if (it == lookup.end()) {
        throw make_error("tetrahedron ", t, ": its edge (", a, ", ", b,
                         ") is missing from the edge list");
      }
      edges_of_tetrahedron_[t][e] = it->second;
      ++edge_use_[static_cast<std::size_t>(it->second)];
      if (edges_[static_cast<std::size_t>(it->second)][0] == a) {
        edge_orientation_[t] = static_cast<std::uint8_t>(edge_orientation_[t] | (1u << e));
      }
    }
  }
  // Adjacency lists, filled in increasing order of tetrahedron and edge.
  vertex_tetrahedra_.assign(static_cast<std::size_t>(num_points_), {});
  vertex_edges_.assign(static_cast<std::size_t>(num_points_), {});
  for (std::size_t t = 0; t < n; ++t) {
    for (Index v : tetrahedra_[t]) vertex_tetrahedra_[static_cast<std::size_t>(v)].push_back(static_cast<Index>(t));
  }
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    for (Index v : edges_[e]) vertex_edges_[static_cast<std::size_t>(v)].push_back(static_cast<Index>(e));
  }
}

std::span<const Index> TetMesh::tetrahedra_around_vertex(Index v) const {
  return vertex_tetrahedra_[static_cast<std::size_t>(v)];
}

std::span<const Index> TetMesh::edges_around_vertex(Index v) const {
  return vertex_edges_[static_cast<std::size_t>(v)];
}

Index TetMesh::edge_between(Index a, Index b) const {
  for (Index e : vertex_edges_[static_cast<std::size_t>(a)]) {
    const Edge& edge = edges_[static_cast<std::size_t>(e)];
    if (edge[0] == b || edge[1] == b) return e;
  }
  return -1;
}

std::vector<BoundaryTriangle> TetMesh::boundary_triangles() const {
  // Count each face by its sorted vertex triple; faces seen once are on the boundary.
  std::map<std::array<Index, 3>, int> count;
  auto sorted_face = [&](std::size_t t, int f) {
    std::array<Index, 3> key{};
    for (int i = 0; i < 3; ++i) key[i] = tetrahedra_[t][kTetrahedronFaces[f][i]];
    std::sort(key.begin(), key.end());
    return key;
  };
  for (std::size_t t = 0; t < tetrahedra_.size(); ++t) {
    for (int f = 0; f < 4; ++f) ++count[sorted_face(t, f)];
  }
  std::vector<BoundaryTriangle> boundary;
  for (std::size_t t = 0; t < tetrahedra_.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      if (count[sorted_face(t, f)] != 1) continue;
      Triangle tri{};
      for (int i = 0; i < 3; ++i) tri[i] = tetrahedra_[t][kTetrahedronFaces[f][i]];
      boundary.push_back({tri, static_cast<Index>(t), f});
    }
  }
  return boundary;
}

Index TetMesh::add_points(Index count) {
  if (count < 0) throw make_error("TetMesh::add_points: negative count ", count);
  const Index first = num_points_;
  num_points_ += count;
  vertex_tetrahedra_.resize(static_cast<std::size_t>(num_points_));
  vertex_edges_.resize(static_cast<std::size_t>(num_points_));
  return first;
}

Index TetMesh::append_edge(Index a, Index b) {
  const auto e = static_cast<Index>(edges_.size());
  edges_.push_back({std::min(a, b), std::max(a, b)});
  edge_use_.push_back(0);
  insert_sorted(vertex_edges_[static_cast<std::size_t>(a)], e);
  insert_sorted(vertex_edges_[static_cast<std::size_t>(b)], e);
  return e;
}

// Finds (or appends) the six edges of tetrahedron t and records it in the adjacency.
void TetMesh::link_tetrahedron(Index t) {
  const auto ti = static_cast<std::size_t>(t);
  const Tetrahedron& tet = tetrahedra_[ti];
  std::uint8_t orientation = 0;
  for (int e = 0; e < 6; ++e) {
    const Index a = tet[kTetrahedronEdges[e][0]], b = tet[kTetrahedronEdges[e][1]];
    Index edge = edge_between(a, b);
    if (edge < 0) edge = append_edge(a, b);
    edges_of_tetrahedron_[ti][e] = edge;
    ++edge_use_[static_cast<std::size_t>(edge)];
    if (edges_[static_cast<std::size_t>(edge)][0] == a) orientation = static_cast<std::uint8_t>(orientation | (1u << e));
  }
  edge_orientation_[ti] = orientation;
  for (Index v : tet) insert_sorted(vertex_tetrahedra_[static_cast<std::size_t>(v)], t);
}

TopologyChange TetMesh::add_tetrahedra(std::span<const Tetrahedron> tetrahedra) {
  check_tetrahedra(tetrahedra, tetrahedra_.size());
  TopologyChange change;
  change.first_added_tetrahedron = num_tetrahedra();
  change.num_added_tetrahedra = static_cast<Index>(tetrahedra.size());
  change.first_added_edge = num_edges();
  for (const Tetrahedron& tet : tetrahedra) {
    for (Index v : tet) {
      if (vertex_tetrahedra_[static_cast<std::size_t>(v)].empty()) change.reconnected_points.push_back(v);
    }
    tetrahedra_.push_back(tet);
    edges_of_tetrahedron_.emplace_back();
    edge_orientation_.push_back(0);
    link_tetrahedron(num_tetrahedra() - 1);
  }
  change.num_added_edges = num_edges() - change.first_added_edge;
  std::sort(change.reconnected_points.begin(), change.reconnected_points.end());  // each once: linked after
  return change;
}

TopologyChange TetMesh::remove_tetrahedra(std::span<const Index> indices) {
  std::vector<Index> sorted(indices.begin(), indices.end());
  std::sort(sorted.begin(), sorted.end(), std::greater<>());
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (sorted[i] < 0 || sorted[i] >= num_tetrahedra()) {
      throw make_error("remove_tetrahedra: tetrahedron index ", sorted[i], " out of range [0, ",
                       num_tetrahedra(), ")");
    }
    if (i > 0 && sorted[i] == sorted[i - 1]) {
      throw make_error("remove_tetrahedra: tetrahedron ", sorted[i], " listed twice");
    }
  }
  TopologyChange change;
  std::vector<Index> unused_edges;
  for (const Index hole : sorted) {
    const auto h = static_cast<std::size_t>(hole);
    change.removed_tetrahedra.push_back(hole);
    change.removed_tetrahedron_vertices.push_back(tetrahedra_[h]);
    for (Index v : tetrahedra_[h]) {
      auto& around = vertex_tetrahedra_[static_cast<std::size_t>(v)];
      erase_sorted(around, hole);
      if (around.empty()) change.isolated_points.push_back(v);
    }
    for (Index e : edges_of_tetrahedron_[h]) {
      if (--edge_use_[static_cast<std::size_t>(e)] == 0) unused_edges.push_back(e);
    }
    const Index last = num_tetrahedra() - 1;
    if (hole != last) {
      const auto l = static_cast<std::size_t>(last);
      for (Index v : tetrahedra_[l]) rename_sorted(vertex_tetrahedra_[static_cast<std::size_t>(v)], last, hole);
      tetrahedra_[h] = tetrahedra_[l];
      edges_of_tetrahedron_[h] = edges_of_tetrahedron_[l];
      edge_orientation_[h] = edge_orientation_[l];
    }
    tetrahedra_.pop_back();
    edges_of_tetrahedron_.pop_back();
    edge_orientation_.pop_back();
    change.tetrahedron_moves.push_back({last, hole});
  }
  std::sort(change.isolated_points.begin(), change.isolated_points.end());

  // Unused edges in decreasing order, each replaced by the last edge; the tetrahedra that used the
  // moved edge (around its first vertex, holding its second) follow.
  std::sort(unused_edges.begin(), unused_edges.end(), std::greater<>());
  for (const Index hole : unused_edges) {
    const auto h = static_cast<std::size_t>(hole);
    change.removed_edges.push_back(hole);
    change.removed_edge_vertices.push_back(edges_[h]);
    for (Index v : edges_[h]) erase_sorted(vertex_edges_[static_cast<std::size_t>(v)], hole);
    const Index last = num_edges() - 1;
    if (hole != last) {
      const auto l = static_cast<std::size_t>(last);
      const Index a = edges_[l][0];
      for (Index v : edges_[l]) rename_sorted(vertex_edges_[static_cast<std::size_t>(v)], last, hole);
      for (Index t : vertex_tetrahedra_[static_cast<std::size_t>(a)]) {
        for (Index& e : edges_of_tetrahedron_[static_cast<std::size_t>(t)]) {
          if (e == last) e = hole;
        }
      }
      edges_[h] = edges_[l];
      edge_use_[h] = edge_use_[l];
    }
    edges_.pop_back();
    edge_use_.pop_back();
    change.edge_moves.push_back({last, hole});
  }
  change.first_added_tetrahedron = num_tetrahedra();
  change.first_added_edge = num_edges();
  return change;
}

template <class Real>
Real signed_volume(const std::array<Vec3<Real>, 4>& p) {
  return -(p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / Real(6);
}

template <class Real>
void check_rest_volumes(std::span<const Tetrahedron> tetrahedra, std::span<const Vec3<Real>> points,
                        Index first_index) {
  const Real eps = std::numeric_limits<Real>::epsilon();
  for (std::size_t i = 0; i < tetrahedra.size(); ++i) {
    const Tetrahedron& tet = tetrahedra[i];
    for (Index v : tet) {
      if (v < 0 || static_cast<std::size_t>(v) >= points.size()) {
        throw make_error("tetrahedron ", first_index + static_cast<Index>(i), " (", tet[0], " ", tet[1], " ",
                         tet[2], " ", tet[3], "): vertex index ", v, " out of range [0, ", points.size(), ")");
      }
    }
    const auto p = tetrahedron_points(tet, points);
    Real longest = 0;
    for (const auto& [k, l] : kTetrahedronEdges) longest = std::max(longest, (p[l] - p[k]).norm());
    const Real volume = signed_volume(p);
    if (!(std::abs(volume) > 1000 * eps * longest * longest * longest)) {
      throw make_error("tetrahedron ", first_index + static_cast<Index>(i), " (", tet[0], " ", tet[1], " ", tet[2],
                       " ", tet[3], ") is degenerate: rest volume ", volume, " with longest edge ", longest);
    }
  }
}

template <class Real>
void check_rest_volumes(const TetMesh& mesh, std::span<const Vec3<Real>> points) {
  if (points.size() != static_cast<std::size_t>(mesh.num_points())) {
    throw make_error("rest positions: ", points.size(), " points given, the topology has ",
                     mesh.num_points());
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw make_error("rest position of point ", i, " is not finite (", points[i].transpose(), ")");
    }
  }
  check_rest_volumes<Real>(mesh.tetrahedra(), points, 0);
}

template float signed_volume(const std::array<Vec3<float>, 4>&);
template double signed_volume(const std::array<Vec3<double>, 4>&);
template void check_rest_volumes(const TetMesh&, std::span<const Vec3<float>>);
template void check_rest_volumes(const TetMesh&, std::span<const Vec3<double>>);
template void check_rest_volumes(std::span<const Tetrahedron>, std::span<const Vec3<float>>, Index);
template void check_rest_volumes(std::span<const Tetrahedron>, std::span<const Vec3<double>>, Index);

}  // namespace fastcorot
