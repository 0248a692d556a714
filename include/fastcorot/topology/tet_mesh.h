// TetMesh: the topology of a tetrahedral mesh with SOFA's TetrahedronSetTopologyContainer semantics.
// It holds the point count, the tetrahedra, the derived edge list (each mesh edge once), the six
// mesh edges of every tetrahedron in SOFA's local edge order together with their orientation, the
// vertex → tetrahedron adjacency and the boundary triangles. Positions are not part of the topology
// (they belong to the mechanical state); `check_rest_volumes` validates a mesh against positions.
//
// Derived edges are created as SOFA creates them: tetrahedra in order, local edges in order, each
// new edge stored as (min vertex, max vertex). A mesh may also be built from an explicit edge list in
// any order and orientation (as a scene file may give it); everything computed on a TetMesh must
// give the same results either way, which is why each tetrahedron records how its local edges run
// relative to the mesh edges.
//
// Topological changes (cutting) are incremental: removal follows SOFA's swap-with-last scheme and
// addition appends (topology_change.h); each costs time proportional to the elements changed and
// their neighbourhoods, never to the mesh, and returns a TopologyChange for whoever holds data per
// tetrahedron or per edge.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/topology/topology_change.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace fastcorot {

// Local edges of a tetrahedron (v0, v1, v2, v3), in SOFA's order: e = (k, l) joins local vertices k < l.
inline constexpr std::array<std::array<int, 2>, 6> kTetrahedronEdges = {
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

// Local faces of a tetrahedron; face i is opposite local vertex i and is ordered so that its normal
// (b - a) × (c - a) points away from vertex i when the tetrahedron is positively oriented
// (dot(p1 - p0, (p2 - p0) × (p3 - p0)) > 0).
inline constexpr std::array<std::array<int, 3>, 4> kTetrahedronFaces = {
    {{1, 2, 3}, {0, 3, 2}, {1, 3, 0}, {0, 2, 1}}};

// A triangle on the boundary (a face that belongs to exactly one tetrahedron).
struct BoundaryTriangle {
  Triangle vertices;  // in the order of kTetrahedronFaces[face]
  Index tetrahedron;  // the tetrahedron it bounds
  int face;           // local face index in that tetrahedron (the opposite local vertex)
};

class TetMesh {
 public:
  TetMesh() = default;

  // Derives the edges from the tetrahedra. Throws fastcorot::Error naming the tetrahedron when an
  // index is out of [0, num_points) or a vertex repeats.
  TetMesh(Index num_points, std::vector<Tetrahedron> tetrahedra);

  // Uses the given edges (kept in this order and orientation). Throws when an edge is out of range,
  // degenerate or repeated, or when an edge of a tetrahedron is missing from the list. Edges not
  // used by any tetrahedron are kept (SOFA keeps them too) and get no stiffness.
  TetMesh(Index num_points, std::vector<Tetrahedron> tetrahedra, std::vector<Edge> edges);

  Index num_points() const { return num_points_; }
  Index num_tetrahedra() const { return static_cast<Index>(tetrahedra_.size()); }
  Index num_edges() const { return static_cast<Index>(edges_.size()); }

  std::span<const Tetrahedron> tetrahedra() const { return tetrahedra_; }
  const Tetrahedron& tetrahedron(Index t) const { return tetrahedra_[static_cast<std::size_t>(t)]; }
  std::span<const Edge> edges() const { return edges_; }

  // Mesh edge index of each local edge of tetrahedron t (order of kTetrahedronEdges).
  const std::array<Index, 6>& edges_of_tetrahedron(Index t) const {
    return edges_of_tetrahedron_[static_cast<std::size_t>(t)];
  }

  // True when local edge e = (k, l) of tetrahedron t starts at its mesh edge's first vertex
  // (tetrahedron(t)[k] == edges()[edges_of_tetrahedron(t)[e]][0]).
  bool edge_follows_mesh_edge(Index t, int e) const {
    return (edge_orientation_[static_cast<std::size_t>(t)] >> e) & 1u;
  }

  // Tetrahedra that contain vertex v, in increasing order.
  std::span<const Index> tetrahedra_around_vertex(Index v) const;
  // Edges that end at vertex v, in increasing order.
  std::span<const Index> edges_around_vertex(Index v) const;
  // Number of tetrahedra that have edge e.
  Index tetrahedra_around_edge_count(Index e) const { return edge_use_[static_cast<std::size_t>(e)]; }
  // Index of the edge joining a and b (either orientation), or -1.
  Index edge_between(Index a, Index b) const;

  // Faces that belong to exactly one tetrahedron, in order of (tetrahedron, local face).
  std::vector<BoundaryTriangle> boundary_triangles() const;

  // Appends points (they start unused) and returns the index of the first new one.
  Index add_points(Index count);

  // Appends tetrahedra over existing points; edges they introduce are appended in SOFA's creation
  // order. Throws fastcorot::Error naming the tetrahedron for a bad vertex index (mesh unchanged).
  TopologyChange add_tetrahedra(std::span<const Tetrahedron> tetrahedra);

  // Removes the listed tetrahedra (any order; an index out of range or listed twice is an error and
  // nothing changes) by swap-with-last, then the edges no tetrahedron uses any more (edges that no
  // tetrahedron used before stay, as SOFA keeps them). Points stay: they belong to the state.
  TopologyChange remove_tetrahedra(std::span<const Index> indices);

  // Recomputes the edges of each tetrahedron, their orientations and the adjacency from the
  // tetrahedra and the current edge list (SOFA's updateTopologyInformation).
  void update_topology_information();

 private:
  void check_tetrahedra(std::span<const Tetrahedron> tetrahedra, std::size_t first_index) const;
  Index append_edge(Index a, Index b);
  void link_tetrahedron(Index t);

  Index num_points_ = 0;
  std::vector<Tetrahedron> tetrahedra_;
  std::vector<Edge> edges_;
  std::vector<std::array<Index, 6>> edges_of_tetrahedron_;
  std::vector<std::uint8_t> edge_orientation_;  // bit e set: local edge e follows its mesh edge
  std::vector<Index> edge_use_;                    // tetrahedra per edge
  std::vector<std::vector<Index>> vertex_tetrahedra_;  // sorted, per point
  std::vector<std::vector<Index>> vertex_edges_;       // sorted, per point
};

// Signed volume as SOFA defines it: -dot(p1 - p0, (p2 - p0) × (p3 - p0)) / 6 (note the sign).
template <class Real>
Real signed_volume(const std::array<Vec3<Real>, 4>& p);

// The four positions of tetrahedron t.
template <class Real>
std::array<Vec3<Real>, 4> tetrahedron_points(const Tetrahedron& t, std::span<const Vec3<Real>> x) {
  return {x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
          x[static_cast<std::size_t>(t[2])], x[static_cast<std::size_t>(t[3])]};
}

// Throws fastcorot::Error when `points` does not hold num_points() entries, a coordinate is not
// finite, or a tetrahedron has (near) zero volume: |V| <= 1000 eps L^3 with L its longest edge.
// The message names the tetrahedron, its vertices and its volume.
template <class Real>
void check_rest_volumes(const TetMesh& mesh, std::span<const Vec3<Real>> points);
// The same for some tetrahedra (numbered from first_index in messages), also checking that their
// vertices index `points`.
template <class Real>
void check_rest_volumes(std::span<const Tetrahedron> tetrahedra, std::span<const Vec3<Real>> points,
                        Index first_index);

}  // namespace fastcorot
