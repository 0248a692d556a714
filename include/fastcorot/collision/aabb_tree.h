// AabbTree<Real>: a bounding-volume hierarchy of axis-aligned boxes over a collision model's
// elements (one box per triangle, segment, point or sphere), for the narrow phase: which element
// pairs of two models (or of one model with itself) have boxes that overlap within a margin.
// Built once as SOFA's CubeCollisionModel (median splits along the longest axis of each cell's
// box, cells of more than four elements split, six levels below the root at most), then refitted
// each step (cell boxes recomputed bottom-up from the new element boxes, the structure kept),
// rebuilt when the element count changes (docs/collision.md, §2.3 and §7). The tree decides
// neither which pairs are found (exactly the element pairs whose boxes overlap) nor, for two
// models, anything but their order, which is SOFA's (BVHNarrowPhase's traversal): a response
// that keeps the first of equal outputs depends on it.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace fastcorot {

template <class Real>
struct Aabb {
  Vec3<Real> min = Vec3<Real>::Constant(std::numeric_limits<Real>::max());
  Vec3<Real> max = Vec3<Real>::Constant(std::numeric_limits<Real>::lowest());

  void extend(const Vec3<Real>& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  // Whether the gap between the two boxes is at most `margin` along every axis (boundaries
  // included): one box widened by `margin` on every side meets the other.
  bool overlaps(const Aabb& b, Real margin) const {
    return (min.array() <= b.max.array() + margin).all() && (b.min.array() <= max.array() + margin).all();
  }
};

template <class Real>
class AabbTree {
 public:
  using Pair = std::pair<Index, Index>;

  // Builds the tree over `boxes` (element i's box is boxes[i]). Throws fastcorot::Error for a box
  // that is not finite or whose min exceeds its max.
  void build(std::span<const Aabb<Real>> boxes);
  // The same elements' new boxes; rebuilds when their number changed. Throws as build.
  void refit(std::span<const Aabb<Real>> boxes);
  std::size_t size() const { return order_.size(); }
  const Aabb<Real>& bounds() const { return nodes_.front().box; }

  // Element pairs (i in a, j in b) whose boxes overlap within `margin`, appended to `out` in the
  // order SOFA's BVHNarrowPhase visits them.
  static void pairs(const AabbTree& a, const AabbTree& b, Real margin, std::vector<Pair>& out);
  // Pairs (i, j), i < j, of this tree's elements whose boxes overlap within `margin`, sorted.
  void self_pairs(Real margin, std::vector<Pair>& out) const;

 private:
  struct Node {
    Aabb<Real> box;
    Index first = 0, count = 0;  // a leaf: elements order_[first, first + count)
    Index left = -1, right = -1;  // an inner node: its children
  };
  void split(Index node);
  void fit(Index node);
  static void check(std::span<const Aabb<Real>> boxes);
  // Beyond SOFA's cost (not its results): each leaf's positions sorted by their boxes' min x, and
  // its widest box along x, so that a leaf's elements overlapping a box are found without testing
  // all of them (SOFA's depth limit leaves about n / 64 elements in a leaf). Leaves of eight
  // elements or fewer are scanned whole instead, and not indexed. Also fills rows_.
  void index_leaves();
  // Positions p in leaf `node` (order_[p]) whose boxes overlap `box` within `margin`, appended to
  // `out` in increasing p.
  void leaf_overlaps(const Node& node, const Aabb<Real>& box, Real margin, std::vector<Index>& out) const;

  std::vector<Node> nodes_;
  std::vector<Index> order_;
  std::vector<Aabb<Real>> boxes_;  // by position: boxes_[k] is element order_[k]'s, so that leaves read consecutive boxes
  std::span<const Aabb<Real>> building_;  // during build only: the boxes by element
  std::vector<Index> by_x_;      // per leaf segment [first, first + count): positions sorted by min x
  std::vector<Real> leaf_width_;  // per node: its leaf's widest box along x (0 for inner nodes)
  // boxes_ again as six rows (min x, y, z, max x, y, z; three spare values at the end of each), so
  // that two scanned leaves are checked four boxes at a time.
  std::array<std::vector<Real>, 6> rows_;
};

}  // namespace fastcorot
