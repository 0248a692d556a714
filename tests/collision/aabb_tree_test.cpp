// AabbTree's candidate pairs against the all-pairs box test on random boxes: two trees and one
// tree with itself, before and after refits that move the boxes (the structure kept), after a
// rebuild for a new element count, at several margins; SOFA's traversal order on a small case;
// bad boxes refused.
#include "fastcorot/collision/aabb_tree.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace fastcorot {
namespace {

using Box = Aabb<double>;
using Pairs = std::vector<std::pair<Index, Index>>;

std::vector<Box> random_boxes(std::mt19937& rng, int n, double spread, double size) {
  std::uniform_real_distribution<double> where(-spread, spread), extent(0, size);
  std::vector<Box> boxes(static_cast<std::size_t>(n));
  for (auto& b : boxes) {
    const Vec3<double> c(where(rng), where(rng), where(rng));
    b.extend(c);
    b.extend(Vec3<double>(c + Vec3<double>(extent(rng), extent(rng), extent(rng))));
  }
  return boxes;
}

Pairs all_pairs(const std::vector<Box>& a, const std::vector<Box>& b, double margin) {
  Pairs out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      bool apart = false;
      for (int k = 0; k < 3; ++k) apart = apart || a[i].min[k] > b[j].max[k] + margin || b[j].min[k] > a[i].max[k] + margin;
      if (!apart) out.emplace_back(static_cast<Index>(i), static_cast<Index>(j));
    }
  }
  return out;
}

Pairs all_self_pairs(const std::vector<Box>& a, double margin) {
  Pairs out;
  for (const auto& [i, j] : all_pairs(a, a, margin)) {
    if (i < j) out.emplace_back(i, j);
  }
  return out;
}

TEST(AabbTree, PairsOfTwoTreesAreTheOverlappingElementPairs) {
  std::mt19937 rng(7);
  for (const int n : {1, 3, 5, 40, 300}) {
    const auto a = random_boxes(rng, n, 10, 1.5), b = random_boxes(rng, n + 7, 10, 1.0);
    AabbTree<double> ta, tb;
    ta.build(a);
    tb.build(b);
    for (const double margin : {0.0, 0.3, 2.0}) {
      Pairs found;
      AabbTree<double>::pairs(ta, tb, margin, found);
      std::sort(found.begin(), found.end());  // found in SOFA's traversal order
      EXPECT_EQ(found, all_pairs(a, b, margin)) << n << " boxes, margin " << margin;
    }
  }
}

// SOFA's order (CubeCollisionModel's splits, BVHNarrowPhase's stack): a cell's two halves pushed
// in order and popped last first, each half's elements in their sorted order.
TEST(AabbTree, PairsComeInSofasTraversalOrder) {
  const auto unit_box = [](double x, double y) {
    Box b;
    b.extend(Vec3<double>(x, y, 0));
    b.extend(Vec3<double>(x + 1, y + 1, 1));
    return b;
  };
  Box big;
  big.extend(Vec3<double>(-10, -10, -10));
  big.extend(Vec3<double>(10, 10, 10));
  AabbTree<double> other;
  other.build(std::vector<Box>{big});
  // The root box as long in x as in y: SOFA splits along y (x only when strictly longest), where
  // the elements come in the reverse order.
  std::vector<Box> diagonal;
  for (int k = 0; k < 6; ++k) diagonal.push_back(unit_box(k, 5 - k));
  AabbTree<double> tree;
  tree.build(diagonal);
  Pairs found;
  AabbTree<double>::pairs(tree, other, 0.0, found);
  EXPECT_EQ(found, (Pairs{{2, 0}, {1, 0}, {0, 0}, {5, 0}, {4, 0}, {3, 0}}));
  // Equal centres keep their order (a stable sort); equal extents split along z.
  tree.build(std::vector<Box>(5, unit_box(0, 0)));
  found.clear();
  AabbTree<double>::pairs(tree, other, 0.0, found);
  EXPECT_EQ(found, (Pairs{{3, 0}, {4, 0}, {0, 0}, {1, 0}, {2, 0}}));
  // Against the first tree's order: its pairs as the outer loop of each popped pair.
  found.clear();
  AabbTree<double>::pairs(other, tree, 0.0, found);
  EXPECT_EQ(found, (Pairs{{0, 3}, {0, 4}, {0, 0}, {0, 1}, {0, 2}}));
}

TEST(AabbTree, SelfPairsAndRefitsFollowTheBoxes) {
  std::mt19937 rng(8);
  auto boxes = random_boxes(rng, 500, 8, 1.0);
  AabbTree<double> tree;
  tree.build(boxes);
  Pairs found;
  tree.self_pairs(0.2, found);
  EXPECT_EQ(found, all_self_pairs(boxes, 0.2));
  EXPECT_GT(found.size(), 50u);  // the test sees pairs (78 with this seed)
  std::normal_distribution<double> move(0, 2);
  for (int round = 0; round < 3; ++round) {
    for (auto& b : boxes) {
      const Vec3<double> d(move(rng), move(rng), move(rng));
      b.min += d;
      b.max += d;
    }
    tree.refit(boxes);
    found.clear();
    tree.self_pairs(0.2, found);
    EXPECT_EQ(found, all_self_pairs(boxes, 0.2)) << "after refit " << round;
  }
  // Another element count: rebuilt.
  boxes.resize(123);
  tree.refit(boxes);
  EXPECT_EQ(tree.size(), 123u);
  found.clear();
  tree.self_pairs(0.0, found);
  EXPECT_EQ(found, all_self_pairs(boxes, 0.0));
}

TEST(AabbTree, TouchingBoxesCountAndBadBoxesAreRefused) {
  Box a, b;
  a.extend(Vec3<double>(0, 0, 0));
  a.extend(Vec3<double>(1, 1, 1));
  b.extend(Vec3<double>(1, 0, 0));  // shares a face
  b.extend(Vec3<double>(2, 1, 1));
  EXPECT_TRUE(a.overlaps(b, 0));
  Box c;
  c.extend(Vec3<double>(1.5, 0, 0));
  c.extend(Vec3<double>(2, 1, 1));
  EXPECT_FALSE(a.overlaps(c, 0.49));
  EXPECT_TRUE(a.overlaps(c, 0.5));
  AabbTree<double> tree;
  Box bad;  // empty: min above max
  EXPECT_THROW(tree.build(std::vector<Box>{a, bad}), Error);
  Box nan = a;
  nan.max[1] = std::nan("");
  EXPECT_THROW(tree.build(std::vector<Box>{nan}), Error);
  tree.build(std::vector<Box>{});
  Pairs none;
  tree.self_pairs(1.0, none);
  EXPECT_TRUE(none.empty());
}

}  // namespace
}  // namespace fastcorot
