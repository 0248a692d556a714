// Self-collision as SOFA prunes it: models of one node meet only when both have selfCollision (a
// model with itself when it has), and each element pair of such models passes SOFA's
// canCollideWithElement (Sofa/Component/Collision/Geometry: PointCollisionModel.inl,
// LineCollisionModel.inl, TriangleCollisionModel.inl) before its rule runs:
// - a triangle against the node's point model: not its own three vertices;
// - a segment against its own model: no shared end, and no edge around one of its ends that is also
//   around one of the other's; against the node's point model: not its ends, nor the ends of the edges
//   around its ends;
// - a point against its own model: only (i, j) with i > j, and not when one of i's neighbours is one
//   of j's, is j, or i is one of j's (SOFA's loops: a point without neighbours is never pruned).
//   SOFA's iterator first keeps (i, j) of one model only when i < j (CollisionElement.h), so a point
//   model never meets itself: reproduced (the pipeline hands a model's own pairs over as i < j);
// - otherwise the other model's rule, with the elements swapped (once: SOFA would loop forever
//   between a segment model and a second point model of one node); spheres are never pruned.
// Design: docs/collision.md (§2.1, "Self-collision").
#pragma once

#include "fastcorot/collision/collision_model.h"

#include <span>
#include <vector>

namespace fastcorot {

// The neighbourhoods SOFA's rules read from a model's topology: each point's neighbours along the
// edges (VerticesAroundVertex) and each point's edges (EdgesAroundVertex, indices into `edges`).
struct SelfCollisionTopology {
  std::vector<std::vector<Index>> vertices_around_vertex;
  std::vector<std::vector<Index>> edges_around_vertex;
};

// Throws fastcorot::Error for an edge with an end outside [0, point_count).
SelfCollisionTopology self_collision_topology(Index point_count, std::span<const Edge> edges);

// Whether element e1 of models[a] may be tested against element e2 of models[b] (SOFA's
// CollisionElementIterator::canCollideWith); always true for models of different nodes.
template <class Real>
bool can_collide_elements(std::span<const CollisionModel<Real>> models, std::size_t a, Index e1, std::size_t b, Index e2);

// Beyond SOFA: whether a triangle and a triangle or segment on the same points share a corner. SOFA
// passes such pairs of one node to NewProximityIntersection's rules, which find them at distance
// zero and divide by it (a NaN normal); they are skipped here.
template <class Real>
bool elements_touch(const CollisionModel<Real>& a, Index e1, const CollisionModel<Real>& b, Index e2);

}  // namespace fastcorot
