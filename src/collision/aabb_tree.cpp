#include "fastcorot/collision/aabb_tree.h"

#include "fastcorot/core/error.h"

#include <algorithm>

namespace fastcorot {

namespace {

constexpr Index kLeafSize = 4;

}  // namespace

template <class Real>
void AabbTree<Real>::check(std::span<const Aabb<Real>> boxes) {
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (!boxes[i].min.allFinite() || !boxes[i].max.allFinite() || (boxes[i].min.array() > boxes[i].max.array()).any()) {
      throw make_error("AabbTree: the box of element ", i, " is not finite or is inverted");
    }
  }
}

template <class Real>
void AabbTree<Real>::build(std::span<const Aabb<Real>> boxes) {
  check(boxes);
  boxes_.assign(boxes.begin(), boxes.end());
  order_.resize(boxes_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<Index>(i);
  nodes_.clear();
  nodes_.reserve(2 * order_.size() / static_cast<std::size_t>(kLeafSize) + 2);
  nodes_.emplace_back();
  if (!order_.empty()) split(0, static_cast<Index>(order_.size()));
}

// Node 'nodes_.back()' (just added) over order_[first, first + count): its box, then its children
// when it holds more than a leaf's worth, the elements sorted by their box centres along the
// longest axis (index order on ties) and cut at (count + 1) / 2, as SOFA's tree.
template <class Real>
Index AabbTree<Real>::split(Index first, Index count) {
  const auto node = static_cast<Index>(nodes_.size() - 1);
  Aabb<Real> box;
  for (Index k = first; k < first + count; ++k) box.extend(boxes_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])]);
  nodes_[static_cast<std::size_t>(node)].box = box;
  nodes_[static_cast<std::size_t>(node)].first = first;
  nodes_[static_cast<std::size_t>(node)].count = count;
  if (count <= kLeafSize) return node;
  int axis = 0;
  (box.max - box.min).maxCoeff(&axis);
  const auto centre = [&](Index e) {
    const auto& b = boxes_[static_cast<std::size_t>(e)];
    return b.min[axis] + b.max[axis];
  };
  std::sort(order_.begin() + first, order_.begin() + first + count, [&](Index a, Index b) {
    const Real ca = centre(a), cb = centre(b);
    return ca < cb || (ca == cb && a < b);
  });
  const Index half = (count + 1) / 2;
  nodes_.emplace_back();
  const Index left = split(first, half);
  nodes_.emplace_back();
  const Index right = split(first + half, count - half);
  nodes_[static_cast<std::size_t>(node)].left = left;
  nodes_[static_cast<std::size_t>(node)].right = right;
  return node;
}

template <class Real>
void AabbTree<Real>::refit(std::span<const Aabb<Real>> boxes) {
  if (boxes.size() != boxes_.size() || nodes_.empty()) {
    build(boxes);
    return;
  }
  check(boxes);
  boxes_.assign(boxes.begin(), boxes.end());
  // Children come after their parent in nodes_: bottom-up is the reverse order.
  for (std::size_t n = nodes_.size(); n-- > 0;) fit(static_cast<Index>(n));
}

template <class Real>
void AabbTree<Real>::fit(Index n) {
  Node& node = nodes_[static_cast<std::size_t>(n)];
  Aabb<Real> box;
  if (node.left < 0) {
    for (Index k = node.first; k < node.first + node.count; ++k) box.extend(boxes_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])]);
  } else {
    box.extend(nodes_[static_cast<std::size_t>(node.left)].box);
    box.extend(nodes_[static_cast<std::size_t>(node.right)].box);
  }
  node.box = box;
}

template <class Real>
void AabbTree<Real>::pairs(const AabbTree& a, const AabbTree& b, Real margin, std::vector<Pair>& out) {
  if (a.size() == 0 || b.size() == 0) return;
  const std::size_t begin = out.size();
  std::vector<std::pair<Index, Index>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const Node& na = a.nodes_[static_cast<std::size_t>(i)];
    const Node& nb = b.nodes_[static_cast<std::size_t>(j)];
    if (!na.box.overlaps(nb.box, margin)) continue;
    const bool leaf_a = na.left < 0, leaf_b = nb.left < 0;
    if (leaf_a && leaf_b) {
      for (Index p = na.first; p < na.first + na.count; ++p) {
        const Index ea = a.order_[static_cast<std::size_t>(p)];
        for (Index q = nb.first; q < nb.first + nb.count; ++q) {
          const Index eb = b.order_[static_cast<std::size_t>(q)];
          if (a.boxes_[static_cast<std::size_t>(ea)].overlaps(b.boxes_[static_cast<std::size_t>(eb)], margin)) out.emplace_back(ea, eb);
        }
      }
    } else if (leaf_b || (!leaf_a && na.count >= nb.count)) {
      stack.push_back({na.left, j});
      stack.push_back({na.right, j});
    } else {
      stack.push_back({i, nb.left});
      stack.push_back({i, nb.right});
    }
  }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end());
}

template <class Real>
void AabbTree<Real>::self_pairs(Real margin, std::vector<Pair>& out) const {
  if (size() < 2) return;
  const std::size_t begin = out.size();
  const auto test = [&](Index ea, Index eb) {
    if (boxes_[static_cast<std::size_t>(ea)].overlaps(boxes_[static_cast<std::size_t>(eb)], margin)) out.emplace_back(std::min(ea, eb), std::max(ea, eb));
  };
  std::vector<std::pair<Index, Index>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const Node& n1 = nodes_[static_cast<std::size_t>(i)];
    const Node& n2 = nodes_[static_cast<std::size_t>(j)];
    if (i == j) {
      if (n1.left < 0) {
        for (Index p = n1.first; p < n1.first + n1.count; ++p) {
          for (Index q = p + 1; q < n1.first + n1.count; ++q) test(order_[static_cast<std::size_t>(p)], order_[static_cast<std::size_t>(q)]);
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
        for (Index q = n2.first; q < n2.first + n2.count; ++q) test(order_[static_cast<std::size_t>(p)], order_[static_cast<std::size_t>(q)]);
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
