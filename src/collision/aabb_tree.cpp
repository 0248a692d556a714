#include "fastcorot/collision/aabb_tree.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/packed.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fastcorot {

namespace {

constexpr Index kLeafSize = 4;
// Leaves of at most this many elements are scanned whole; larger ones through their x order.
constexpr Index kScannedLeaf = 8;
// SOFA's CollisionPipeline depth (its default, 6): the levels of cells below the root.
constexpr int kMaxDepth = 6;

}  // namespace

template <class Real>
void AabbTree<Real>::check(std::span<const Aabb<Real>> boxes) {
  // First in one pass without branches or a chain of additions: each extent max − min lies in
  // [0, largest finite] when the box is finite and not inverted (an infinity or NaN in either puts
  // it outside; so does an extent that overflows, which the second pass then clears).
  bool fine = true;
  for (const auto& box : boxes) {
    for (int axis = 0; axis < 3; ++axis) {
      const Real extent = box.max[axis] - box.min[axis];
      fine &= (extent >= 0) & (extent <= std::numeric_limits<Real>::max());
    }
  }
  if (fine) return;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (!boxes[i].min.allFinite() || !boxes[i].max.allFinite() || (boxes[i].min.array() > boxes[i].max.array()).any()) {
      throw make_error("AabbTree: the box of element ", i, " is not finite or is inverted");
    }
  }
}

template <class Real>
void AabbTree<Real>::build(std::span<const Aabb<Real>> boxes) {
  check(boxes);
  building_ = boxes;
  boxes_.assign(boxes.begin(), boxes.end());  // order_ starts as the identity
  order_.resize(boxes_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<Index>(i);
  nodes_.clear();
  nodes_.reserve(2 * order_.size() / static_cast<std::size_t>(kLeafSize) + 2);
  nodes_.emplace_back();
  nodes_.front().count = static_cast<Index>(order_.size());
  fit(0);
  if (order_.empty()) {
    building_ = {};
    return;
  }
  // SOFA's CubeCollisionModel::computeBoundingTree: level by level from the root, each cell of the
  // level holding more than a leaf's worth split in two cells of the next level (made one after
  // the other, so siblings are adjacent); cells of the last level (kMaxDepth) are not split.
  std::size_t level_begin = 0, level_end = 1;
  for (int level = 0; level < kMaxDepth; ++level) {
    for (std::size_t n = level_begin; n < level_end; ++n) {
      if (nodes_[n].count <= kLeafSize) continue;
      split(static_cast<Index>(n));
    }
    level_begin = level_end;
    level_end = nodes_.size();
  }
  building_ = {};
  index_leaves();
}

template <class Real>
void AabbTree<Real>::index_leaves() {
  for (std::size_t r = 0; r < 6; ++r) {
    auto& row = rows_[r];
    row.assign(boxes_.size() + 3, Real(0));
    for (std::size_t k = 0; k < boxes_.size(); ++k) row[k] = r < 3 ? boxes_[k].min[static_cast<Index>(r)] : boxes_[k].max[static_cast<Index>(r) - 3];
  }
  by_x_.resize(order_.size());
  leaf_width_.assign(nodes_.size(), Real(0));
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    const Node& node = nodes_[n];
    if (node.left >= 0 || node.count <= kScannedLeaf) continue;
    const auto begin = by_x_.begin() + node.first, end = begin + node.count;
    for (Index p = node.first; p < node.first + node.count; ++p) by_x_[static_cast<std::size_t>(p)] = p;
    const auto min_x = [&](Index p) { return boxes_[static_cast<std::size_t>(p)].min.x(); };
    std::sort(begin, end, [&](Index a, Index b) { return min_x(a) < min_x(b) || (min_x(a) == min_x(b) && a < b); });
    Real width = 0;
    for (Index p = node.first; p < node.first + node.count; ++p) {
      const auto& b = boxes_[static_cast<std::size_t>(p)];
      width = std::max(width, b.max.x() - b.min.x());
    }
    leaf_width_[n] = width;
  }
}

template <class Real>
void AabbTree<Real>::leaf_overlaps(const Node& node, const Aabb<Real>& box, Real margin, std::vector<Index>& out) const {
  if (node.count <= kScannedLeaf) {
    for (Index p = node.first; p < node.first + node.count; ++p) {
      if (boxes_[static_cast<std::size_t>(p)].overlaps(box, margin)) out.push_back(p);
    }
    return;
  }
  const std::size_t begin = out.size();
  const auto first = by_x_.begin() + node.first, last = first + node.count;
  const auto n = static_cast<std::size_t>(&node - nodes_.data());
  // Boxes whose min x lies in [box.min.x − margin − widest, box.max.x + margin] may overlap.
  const Real low = box.min.x() - margin - leaf_width_[n], high = box.max.x() + margin;
  const auto min_x = [&](Index p) { return boxes_[static_cast<std::size_t>(p)].min.x(); };
  auto it = std::lower_bound(first, last, low, [&](Index p, Real value) { return min_x(p) < value; });
  for (; it != last && min_x(*it) <= high; ++it) {
    if (boxes_[static_cast<std::size_t>(*it)].overlaps(box, margin)) out.push_back(*it);
  }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end());
}

// Cell n's elements stably sorted by their box centres along its box's longest axis (SOFA's
// comparisons: x only when it beats both y and z, y when it beats z, else z), so that ties keep
// the order earlier splits left, then cut at (count + 1) / 2 into two new cells.
template <class Real>
void AabbTree<Real>::split(Index n) {
  const std::size_t node = static_cast<std::size_t>(n);
  const Vec3<Real> l = nodes_[node].box.max - nodes_[node].box.min;
  const int axis = l[0] > l[1] ? (l[0] > l[2] ? 0 : 2) : (l[1] > l[2] ? 1 : 2);
  const auto centre = [&](Index e) {
    const auto& b = building_[static_cast<std::size_t>(e)];
    return b.min[axis] + b.max[axis];
  };
  const Index first = nodes_[node].first, count = nodes_[node].count;
  std::stable_sort(order_.begin() + first, order_.begin() + first + count,
                   [&](Index a, Index b) { return centre(a) < centre(b); });
  for (Index k = first; k < first + count; ++k) {
    boxes_[static_cast<std::size_t>(k)] = building_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])];
  }
  const Index half = (count + 1) / 2;
  const auto left = static_cast<Index>(nodes_.size());
  nodes_.emplace_back();
  nodes_.back().first = first;
  nodes_.back().count = half;
  fit(left);
  nodes_.emplace_back();
  nodes_.back().first = first + half;
  nodes_.back().count = count - half;
  fit(left + 1);
  nodes_[node].left = left;
  nodes_[node].right = left + 1;
}

template <class Real>
void AabbTree<Real>::refit(std::span<const Aabb<Real>> boxes) {
  if (boxes.size() != boxes_.size() || nodes_.empty()) {
    build(boxes);
    return;
  }
  check(boxes);
  for (std::size_t k = 0; k < order_.size(); ++k) boxes_[k] = boxes[static_cast<std::size_t>(order_[k])];
  // Children come after their parent in nodes_: bottom-up is the reverse order.
  for (std::size_t n = nodes_.size(); n-- > 0;) fit(static_cast<Index>(n));
  index_leaves();
}

template <class Real>
void AabbTree<Real>::fit(Index n) {
  Node& node = nodes_[static_cast<std::size_t>(n)];
  Aabb<Real> box;
  if (node.left < 0) {
    for (Index k = node.first; k < node.first + node.count; ++k) box.extend(boxes_[static_cast<std::size_t>(k)]);
  } else {
    box.extend(nodes_[static_cast<std::size_t>(node.left)].box);
    box.extend(nodes_[static_cast<std::size_t>(node.right)].box);
  }
  node.box = box;
}

// SOFA's BVHNarrowPhase on two models' cube trees: from the pair (root's children, root's
// children), a stack of pairs of ranges (two sibling cells, or a cell's elements); a popped pair
// tests each item of the first range against each item of the second, in order, and for boxes
// that pass pushes the pair of their children (an element kept as itself against a cell's
// children), or, for two elements, reports the pair at once. The order of the element pairs is
// SOFA's order of computeIntersection calls, which decides the penalty's "first on ties".
template <class Real>
void AabbTree<Real>::pairs(const AabbTree& a, const AabbTree& b, Real margin, std::vector<Pair>& out) {
  if (a.size() == 0 || b.size() == 0) return;
  if (!a.nodes_.front().box.overlaps(b.nodes_.front().box, margin)) return;  // the broad phase's root test
  // A range: cells [first, first + count) of nodes_ (cells), or elements order_[first, first + count).
  struct Range {
    bool cells = false;
    Index first = 0, count = 0;
    Index leaf = -1;  // the leaf whose elements these are (−1: one element kept as itself)
  };
  const auto children = [](const AabbTree& t, Index n) {
    const Node& node = t.nodes_[static_cast<std::size_t>(n)];
    return node.left >= 0 ? Range{true, node.left, 2, -1} : Range{false, node.first, node.count, n};
  };
  const auto box = [](const AabbTree& t, const Range& r, Index k) -> const Aabb<Real>& {
    const auto i = static_cast<std::size_t>(r.first + k);
    return r.cells ? t.nodes_[i].box : t.boxes_[i];
  };
  std::vector<std::pair<Range, Range>> stack{{children(a, 0), children(b, 0)}};
  std::vector<Index> found;
  while (!stack.empty()) {
    const auto [ra, rb] = stack.back();
    stack.pop_back();
    if (!ra.cells && !rb.cells && rb.leaf >= 0 && rb.count > kScannedLeaf) {
      // Two element ranges: each of the first against the second's elements in order, those
      // overlapping found through the second leaf's x order (the same pairs, in the same order).
      const Node& leaf = b.nodes_[static_cast<std::size_t>(rb.leaf)];
      for (Index i = 0; i < ra.count; ++i) {
        const Index ea = a.order_[static_cast<std::size_t>(ra.first + i)];
        found.clear();
        b.leaf_overlaps(leaf, a.boxes_[static_cast<std::size_t>(ra.first + i)], margin, found);
        for (const Index p : found) out.emplace_back(ea, b.order_[static_cast<std::size_t>(p)]);
      }
      continue;
    }
    if (!ra.cells && !rb.cells) {
      // Two element ranges (small leaves, or one element against a leaf): each box of ra against
      // rb's four at a time (Aabb::overlaps' comparisons, lane by lane), without a
      // branch on the outcome, about as often true as false; each pair is written and kept when
      // its boxes overlap, in rb's order.
      using P = Packed<Real>;
      const auto first = static_cast<std::size_t>(rb.first);
      const P m = broadcast(margin);
      for (Index i = 0; i < ra.count; ++i) {
        const Aabb<Real>& box_a = a.boxes_[static_cast<std::size_t>(ra.first + i)];
        const Index ea = a.order_[static_cast<std::size_t>(ra.first + i)];
        const P a_max[3] = {broadcast(box_a.max.x()) + m, broadcast(box_a.max.y()) + m, broadcast(box_a.max.z()) + m};
        std::size_t kept = out.size();
        out.resize(kept + static_cast<std::size_t>(rb.count));
        for (Index j = 0; j < rb.count; j += 4) {
          const auto at = first + static_cast<std::size_t>(j);
          auto overlap = broadcast(box_a.min.x()) <= load_packed(b.rows_[3].data() + at) + m;
          overlap &= broadcast(box_a.min.y()) <= load_packed(b.rows_[4].data() + at) + m;
          overlap &= broadcast(box_a.min.z()) <= load_packed(b.rows_[5].data() + at) + m;
          overlap &= load_packed(b.rows_[0].data() + at) <= a_max[0];
          overlap &= load_packed(b.rows_[1].data() + at) <= a_max[1];
          overlap &= load_packed(b.rows_[2].data() + at) <= a_max[2];
          for (Index l = 0; l < 4 && j + l < rb.count; ++l) {
            out[kept] = {ea, b.order_[at + static_cast<std::size_t>(l)]};
            kept += overlap[l] ? 1 : 0;
          }
        }
        out.resize(kept);
      }
      continue;
    }
    for (Index i = 0; i < ra.count; ++i) {
      for (Index j = 0; j < rb.count; ++j) {
        if (!box(a, ra, i).overlaps(box(b, rb, j), margin)) continue;
        if (ra.cells) {
          stack.emplace_back(children(a, ra.first + i), rb.cells ? children(b, rb.first + j) : Range{false, rb.first + j, 1, -1});
        } else if (rb.cells) {
          stack.emplace_back(Range{false, ra.first + i, 1, -1}, children(b, rb.first + j));
        } else {
          out.emplace_back(a.order_[static_cast<std::size_t>(ra.first + i)], b.order_[static_cast<std::size_t>(rb.first + j)]);
        }
      }
    }
  }
}

template <class Real>
void AabbTree<Real>::self_pairs(Real margin, std::vector<Pair>& out) const {
  if (size() < 2) return;
  const std::size_t begin = out.size();
  const auto add = [&](Index ea, Index eb) { out.emplace_back(std::min(ea, eb), std::max(ea, eb)); };
  std::vector<Index> found;
  std::vector<std::pair<Index, Index>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const Node& n1 = nodes_[static_cast<std::size_t>(i)];
    const Node& n2 = nodes_[static_cast<std::size_t>(j)];
    if (i == j) {
      if (n1.left < 0) {
        for (Index p = n1.first; p < n1.first + n1.count; ++p) {
          found.clear();
          leaf_overlaps(n1, boxes_[static_cast<std::size_t>(p)], margin, found);
          for (const Index q : found) {
            if (q > p) add(order_[static_cast<std::size_t>(p)], order_[static_cast<std::size_t>(q)]);
          }
        }
      } else {
        stack.push_back({n1.left, n1.left});
        stack.push_back({n1.right, n1.right});
        stack.push_back({n1.left, n1.right});
      }
      continue;
    }
    if (!n1.box.overlaps(n2.box, margin)) continue;
    const bool leaf1 = n1.left < 0, leaf2 = n2.left < 0;
    if (leaf1 && leaf2) {
      for (Index p = n1.first; p < n1.first + n1.count; ++p) {
        found.clear();
        leaf_overlaps(n2, boxes_[static_cast<std::size_t>(p)], margin, found);
        for (const Index q : found) add(order_[static_cast<std::size_t>(p)], order_[static_cast<std::size_t>(q)]);
      }
    } else if (leaf2 || (!leaf1 && n1.count >= n2.count)) {
      stack.push_back({n1.left, j});
      stack.push_back({n1.right, j});
    } else {
      stack.push_back({i, n2.left});
      stack.push_back({i, n2.right});
    }
  }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end());
}

template class AabbTree<float>;
template class AabbTree<double>;

}  // namespace fastcorot
