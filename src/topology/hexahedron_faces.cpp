#include "fastcorot/topology/hexahedron_faces.h"

#include <algorithm>
#include <map>
#include <set>

namespace fastcorot {

namespace {

using Quad = std::array<Index, 4>;

// SOFA's createQuadSetArray visits the faces of each hexahedron in this order (outward normals).
constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

Quad starting_at_smallest(Quad v) {
  while (v[0] > v[1] || v[0] > v[2] || v[0] > v[3]) v = {v[1], v[2], v[3], v[0]};
  return v;
}

}  // namespace

std::vector<Edge> hexahedron_set_edges(std::span<const std::array<Index, 8>> hexahedra) {
  std::set<Edge> seen;
  std::vector<Edge> edges;
  for (const auto& h : hexahedra) {
    for (const auto& [a, b] : kHexahedronEdges) {
      const Edge e = {std::min(h[a], h[b]), std::max(h[a], h[b])};
      if (seen.insert(e).second) edges.push_back(e);
    }
  }
  return edges;
}

std::vector<std::array<Index, 4>> hexahedron_set_quads(std::span<const std::array<Index, 8>> hexahedra) {
  std::set<Quad> seen;  // each kept quad in both orientations
  std::vector<Quad> quads;
  for (const auto& h : hexahedra) {
    for (const auto& face : kFaces) {
      const Quad v = starting_at_smallest({h[face[0]], h[face[1]], h[face[2]], h[face[3]]});
      const Quad reversed = {v[0], v[3], v[2], v[1]};
      if (seen.count(reversed) || seen.count(v)) continue;
      seen.insert(reversed);
      seen.insert(v);
      quads.push_back(v);
    }
  }
  return quads;
}

std::vector<std::array<Index, 4>> boundary_quads(std::span<const std::array<Index, 4>> quads,
                                                 std::span<const std::array<Index, 8>> hexahedra, bool flip) {
  // How many hexahedra have each face, a face known by its sorted corners.
  const auto key = [](std::array<Index, 4> corners) {
    std::sort(corners.begin(), corners.end());
    return corners;
  };
  static constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::map<std::array<Index, 4>, int> count;
  for (const auto& h : hexahedra) {
    for (const auto& f : kFaces) ++count[key({h[f[0]], h[f[1]], h[f[2]], h[f[3]]})];
  }
  std::vector<std::array<Index, 4>> out;
  for (const auto& q : quads) {
    const auto found = count.find(key(q));
    if (found == count.end() || found->second != 1) continue;
    out.push_back(flip ? std::array<Index, 4>{q[3], q[2], q[1], q[0]} : q);
  }
  return out;
}

}  // namespace fastcorot
