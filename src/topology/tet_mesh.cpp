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

TetMesh::TetMesh(Index num_points, std::vector<Tetrahedron> tetrahedra)
    : num_points_(num_points), tetrahedra_(std::move(tetrahedra)) {
  if (num_points_ < 0) throw make_error("TetMesh: negative point count ", num_points_);
  check_tetrahedra(0);
  append_missing_edges(0);
  update_topology_information();
}

TetMesh::TetMesh(Index num_points, std::vector<Tetrahedron> tetrahedra, std::vector<Edge> edges)
    : num_points_(num_points), tetrahedra_(std::move(tetrahedra)), edges_(std::move(edges)) {
  if (num_points_ < 0) throw make_error("TetMesh: negative point count ", num_points_);
  check_tetrahedra(0);
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

void TetMesh::check_tetrahedra(std::size_t first) const {
  for (std::size_t t = first; t < tetrahedra_.size(); ++t) {
    const Tetrahedron& tet = tetrahedra_[t];
    for (int i = 0; i < 4; ++i) {
      if (tet[i] < 0 || tet[i] >= num_points_) {
        throw make_error("tetrahedron ", t, " (", tet[0], " ", tet[1], " ", tet[2], " ", tet[3],
                         "): vertex index ", tet[i], " out of range [0, ", num_points_, ")");
      }
      for (int j = 0; j < i; ++j) {
        if (tet[i] == tet[j]) {
          throw make_error("tetrahedron ", t, " (", tet[0], " ", tet[1], " ", tet[2], " ", tet[3],
                           "): vertex ", tet[i], " repeats");
        }
      }
    }
  }
}

void TetMesh::append_missing_edges(std::size_t first_tetrahedron) {
  auto lookup = edge_lookup(edges_);
  for (std::size_t t = first_tetrahedron; t < tetrahedra_.size(); ++t) {
    for (const auto& [k, l] : kTetrahedronEdges) {
      const Index a = tetrahedra_[t][k];
      const Index b = tetrahedra_[t][l];
      if (lookup.emplace(edge_key(a, b), static_cast<Index>(edges_.size())).second) {
        edges_.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  }
}

void TetMesh::update_topology_information() {
  const auto lookup = edge_lookup(edges_);
  const std::size_t n = tetrahedra_.size();
  edges_of_tetrahedron_.resize(n);
  edge_orientation_.assign(n, 0);
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
      if (edges_[static_cast<std::size_t>(it->second)][0] == a) {
        edge_orientation_[t] = static_cast<std::uint8_t>(edge_orientation_[t] | (1u << e));
      }
    }
  }
  // Vertex → tetrahedron adjacency as compressed rows.
  vertex_tetrahedra_offsets_.assign(static_cast<std::size_t>(num_points_) + 1, 0);
  for (const Tetrahedron& tet : tetrahedra_) {
    for (Index v : tet) ++vertex_tetrahedra_offsets_[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t v = 0; v < static_cast<std::size_t>(num_points_); ++v) {
    vertex_tetrahedra_offsets_[v + 1] += vertex_tetrahedra_offsets_[v];
  }
  vertex_tetrahedra_.resize(4 * n);
  std::vector<Index> cursor(vertex_tetrahedra_offsets_.begin(), vertex_tetrahedra_offsets_.end() - 1);
  for (std::size_t t = 0; t < n; ++t) {
    for (Index v : tetrahedra_[t]) {
      vertex_tetrahedra_[static_cast<std::size_t>(cursor[static_cast<std::size_t>(v)]++)] =
          static_cast<Index>(t);
    }
  }
}

std::span<const Index> TetMesh::tetrahedra_around_vertex(Index v) const {
  const auto begin = static_cast<std::size_t>(vertex_tetrahedra_offsets_[static_cast<std::size_t>(v)]);
  const auto end = static_cast<std::size_t>(vertex_tetrahedra_offsets_[static_cast<std::size_t>(v) + 1]);
  return std::span<const Index>(vertex_tetrahedra_).subspan(begin, end - begin);
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
  vertex_tetrahedra_offsets_.resize(static_cast<std::size_t>(num_points_) + 1,
                                    vertex_tetrahedra_offsets_.empty() ? 0 : vertex_tetrahedra_offsets_.back());
  return first;
}

void TetMesh::add_tetrahedra(std::span<const Tetrahedron> tetrahedra) {
  const std::size_t first = tetrahedra_.size();
  tetrahedra_.insert(tetrahedra_.end(), tetrahedra.begin(), tetrahedra.end());
  try {
    check_tetrahedra(first);
  } catch (...) {
    tetrahedra_.resize(first);
    throw;
  }
  append_missing_edges(first);
  update_topology_information();
}

void TetMesh::remove_tetrahedra(std::span<const Index> indices) {
  std::vector<bool> remove(tetrahedra_.size(), false);
  for (Index t : indices) {
    if (t < 0 || t >= num_tetrahedra()) {
      throw make_error("remove_tetrahedra: tetrahedron index ", t, " out of range [0, ",
                       num_tetrahedra(), ")");
    }
    if (remove[static_cast<std::size_t>(t)]) {
      throw make_error("remove_tetrahedra: tetrahedron ", t, " listed twice");
    }
    remove[static_cast<std::size_t>(t)] = true;
  }
  std::vector<bool> edge_used(edges_.size(), false);
  std::vector<Tetrahedron> kept;
  kept.reserve(tetrahedra_.size() - indices.size());
  for (std::size_t t = 0; t < tetrahedra_.size(); ++t) {
    if (remove[t]) continue;
    kept.push_back(tetrahedra_[t]);
    for (Index e : edges_of_tetrahedron_[t]) edge_used[static_cast<std::size_t>(e)] = true;
  }
  // Edges that no tetrahedron used before the removal stay, as SOFA keeps them.
  std::vector<bool> edge_used_before(edges_.size(), false);
  for (const auto& tet_edges : edges_of_tetrahedron_) {
    for (Index e : tet_edges) edge_used_before[static_cast<std::size_t>(e)] = true;
  }
  std::vector<Edge> kept_edges;
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    if (edge_used[e] || !edge_used_before[e]) kept_edges.push_back(edges_[e]);
  }
  tetrahedra_ = std::move(kept);
  edges_ = std::move(kept_edges);
  update_topology_information();
}

template <class Real>
Real signed_volume(const std::array<Vec3<Real>, 4>& p) {
  return -(p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / Real(6);
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
  const Real eps = std::numeric_limits<Real>::epsilon();
  for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
    const Tetrahedron& tet = mesh.tetrahedron(t);
    const auto p = tetrahedron_points(tet, points);
    Real longest = 0;
    for (const auto& [k, l] : kTetrahedronEdges) longest = std::max(longest, (p[l] - p[k]).norm());
    const Real volume = signed_volume(p);
    if (!(std::abs(volume) > 1000 * eps * longest * longest * longest)) {
      throw make_error("tetrahedron ", t, " (", tet[0], " ", tet[1], " ", tet[2], " ", tet[3],
                       ") is degenerate: rest volume ", volume, " with longest edge ", longest);
    }
  }
}

template float signed_volume(const std::array<Vec3<float>, 4>&);
template double signed_volume(const std::array<Vec3<double>, 4>&);
template void check_rest_volumes(const TetMesh&, std::span<const Vec3<float>>);
template void check_rest_volumes(const TetMesh&, std::span<const Vec3<double>>);

}  // namespace fastcorot
