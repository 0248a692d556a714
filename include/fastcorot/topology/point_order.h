// Point orders for locality: which order to keep a mesh's points in so that the points of an
// element or edge sit close together in memory. Meshes from SOFA's grids and most mesh generators
// are numbered locally already; meshes whose numbering is scattered (shuffled, or written out in
// an arbitrary order) are renumbered inside the force field (docs/performance.md).
#pragma once

#include "fastcorot/core/types.h"

#include <span>
#include <vector>

namespace fastcorot {

// The reverse Cuthill–McKee order of the graph whose vertices are the points and whose edges are
// `edges`: new index of each point. Each connected part starts from a point of least degree
// (refined once towards the far end of its breadth-first levels), neighbours are taken by
// increasing degree, then point index, so the order is deterministic. Points on no edge come last,
// in their order.
std::vector<Index> reverse_cuthill_mckee(Index num_points, std::span<const Edge> edges);

// The mean of |order[a] - order[b]| over the edges (a, b): how far apart an edge's points are
// kept. With an empty `order`, the points' own indices.
double mean_edge_span(std::span<const Edge> edges, std::span<const Index> order = {});

}  // namespace fastcorot
