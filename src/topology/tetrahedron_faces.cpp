#include "fastcorot/topology/tetrahedron_faces.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

namespace fastcorot {

namespace {

// SOFA's trianglesOrientationInTetrahedronArray: face j is opposite vertex j.
constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {1, 3, 0}, {0, 2, 1}};

Triangle starting_at_smallest(Triangle v) {
  while (v[0] > v[1] || v[0] > v[2]) v = {v[1], v[2], v[0]};
  return v;
}

// The triangle array and, for each of its triangles, the number of tetrahedra it bounds.
std::vector<Triangle> faces(std::span<const Tetrahedron> tetrahedra, std::vector<int>* counts) {
  std::map<Triangle, std::size_t> seen;
  std::vector<Triangle> triangles;
  for (const Tetrahedron& t : tetrahedra) {
    for (const auto& face : kFaces) {
      const Triangle v = starting_at_smallest({t[face[0]], t[face[1]], t[face[2]]});
      auto found = seen.find({v[0], v[2], v[1]});
      if (found == seen.end()) found = seen.find(v);
      if (found == seen.end()) {
        found = seen.emplace(v, triangles.size()).first;
        triangles.push_back(v);
        if (counts) counts->push_back(0);
      }
      if (counts) ++(*counts)[found->second];
    }
  }
  return triangles;
}

}  // namespace

std::vector<Triangle> tetrahedron_set_triangles(std::span<const Tetrahedron> tetrahedra) { return faces(tetrahedra, nullptr); }

std::vector<Edge> tetrahedron_set_edges(std::span<const Tetrahedron> tetrahedra) {
  // SOFA's edgesInTetrahedronArray.
  constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  std::set<std::pair<Index, Index>> seen;
  std::vector<Edge> edges;
  for (const Tetrahedron& t : tetrahedra) {
    for (const auto& e : kEdges) {
      const Index a = std::min(t[e[0]], t[e[1]]), b = std::max(t[e[0]], t[e[1]]);
      if (seen.insert({a, b}).second) edges.push_back({a, b});
    }
  }
  return edges;
}

std::vector<Triangle> boundary_triangles(std::span<const Tetrahedron> tetrahedra, bool flip_normals) {
  std::vector<int> counts;
  const std::vector<Triangle> all = faces(tetrahedra, &counts);
  std::vector<Triangle> boundary;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (counts[i] != 1) continue;
    boundary.push_back(flip_normals ? Triangle{all[i][0], all[i][2], all[i][1]} : all[i]);
  }
  return boundary;
}

}  // namespace fastcorot
