// TopologyChange: what one call to TetMesh::remove_tetrahedra or TetMesh::add_tetrahedra did, so
// that everything holding per-tetrahedron or per-edge data (force fields, masses, callers' own
// arrays) can follow the change at a cost proportional to the change, not to the mesh.
//
// Removal uses SOFA's swap-with-last scheme (TetrahedronSetTopologyModifier): the removed items are
// taken in decreasing index order; each time, the current last item moves into the hole and the
// array shrinks by one. Taken in that order, a removed item still sits at its original index when
// its turn comes, and the item moved is never one still to be removed. The moves are steps to
// replay in order on any per-item array (apply_moves); `from` is the last position at that step.
// Additions append: new tetrahedra and new edges take the indices after the existing ones.
#pragma once

#include "fastcorot/core/types.h"

#include <span>
#include <unordered_map>
#include <vector>

namespace fastcorot {

// One removal step: the item at `from` (the last one) moves to `to` (the hole), then the array
// drops its last entry. from == to when the removed item was the last one.
struct IndexMove {
  Index from;
  Index to;
};

struct TopologyChange {
  // Removed tetrahedra (indices before the change, decreasing) with their vertices, and the moves.
  std::vector<Index> removed_tetrahedra;
  std::vector<Tetrahedron> removed_tetrahedron_vertices;
  std::vector<IndexMove> tetrahedron_moves;
  // Edges no tetrahedron uses any more, removed the same way (indices before the change).
  std::vector<Index> removed_edges;
  std::vector<Edge> removed_edge_vertices;
  std::vector<IndexMove> edge_moves;
  // Appended items: [first_added_tetrahedron, first_added_tetrahedron + num_added_tetrahedra).
  Index first_added_tetrahedron = 0;
  Index num_added_tetrahedra = 0;
  Index first_added_edge = 0;
  Index num_added_edges = 0;
  // Points that lost their last tetrahedron (removal) or gained their first one (addition).
  std::vector<Index> isolated_points;
  std::vector<Index> reconnected_points;

  bool empty() const {
    return removed_tetrahedra.empty() && removed_edges.empty() && num_added_tetrahedra == 0 &&
           num_added_edges == 0;
  }
};

// Applies removal moves to a per-item array (v[to] = v[from], then drop the last entry).
template <class T>
void apply_moves(std::vector<T>& values, std::span<const IndexMove> moves) {
  for (const IndexMove& move : moves) {
    if (move.from != move.to) {
      values[static_cast<std::size_t>(move.to)] = std::move(values[static_cast<std::size_t>(move.from)]);
    }
    values.pop_back();
  }
}

// New index of every old one (-1 for removed items) after the moves, for callers that keep their
// own indices; costs O(old_size).
std::vector<Index> old_to_new(Index old_size, std::span<const IndexMove> moves);

// The same for a few indices, in O(moves): old index -> new index (-1 when removed).
class IndexRenumbering {
 public:
  IndexRenumbering(std::span<const Index> removed, std::span<const IndexMove> moves);
  Index operator()(Index old) const;

 private:
  std::unordered_map<Index, Index> changed_;
};

}  // namespace fastcorot
