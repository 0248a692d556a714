// reverse_cuthill_mckee and mean_edge_span (fastcorot/topology/point_order.h).
#include "fastcorot/topology/point_order.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

bool is_permutation_of_points(const std::vector<Index>& order) {
  std::vector<Index> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (sorted[i] != static_cast<Index>(i)) return false;
  }
  return true;
}

TEST(PointOrder, APathWithScatteredLabelsBecomesConsecutive) {
  // The path 0 - 1 - ... - 9 written with shuffled labels.
  std::vector<Index> label(10);
  std::iota(label.begin(), label.end(), Index(0));
  std::mt19937 rng(3);
  std::shuffle(label.begin(), label.end(), rng);
  std::vector<Edge> edges;
  for (std::size_t i = 0; i + 1 < label.size(); ++i) edges.push_back({label[i], label[i + 1]});
  const std::vector<Index> order = reverse_cuthill_mckee(10, edges);
  ASSERT_TRUE(is_permutation_of_points(order));
  EXPECT_EQ(mean_edge_span(edges, order), 1.0);
  EXPECT_GT(mean_edge_span(edges), 1.0);
  // It starts at an end of the path (a peripheral point).
  EXPECT_TRUE(order[static_cast<std::size_t>(label.front())] == 0 || order[static_cast<std::size_t>(label.back())] == 0);
}

TEST(PointOrder, IsolatedPointsComeLastAndPartsAreKeptTogether) {
  // Two triangles {0, 2, 4} and {1, 3, 5}, and point 6 on no edge.
  const std::vector<Edge> edges = {{0, 2}, {2, 4}, {4, 0}, {1, 3}, {3, 5}, {5, 1}};
  const std::vector<Index> order = reverse_cuthill_mckee(7, edges);
  ASSERT_TRUE(is_permutation_of_points(order));
  EXPECT_EQ(order[6], 6);
  const auto together = [&](Index a, Index b, Index c) {
    const auto [low, high] = std::minmax({order[static_cast<std::size_t>(a)], order[static_cast<std::size_t>(b)],
                                          order[static_cast<std::size_t>(c)]});
    return high - low == 2;
  };
  EXPECT_TRUE(together(0, 2, 4));
  EXPECT_TRUE(together(1, 3, 5));
  EXPECT_EQ(reverse_cuthill_mckee(7, edges), order);  // deterministic
}

TEST(PointOrder, NarrowsAShuffledGridAndKeepsEdgeCases) {
  RegularGrid grid;
  grid.n = {12, 5, 4};
  const TetMesh mesh(grid.num_points(), grid_tetrahedra(grid, true));
  std::vector<Index> shuffle(static_cast<std::size_t>(grid.num_points()));
  std::iota(shuffle.begin(), shuffle.end(), Index(0));
  std::mt19937 rng(9);
  std::shuffle(shuffle.begin(), shuffle.end(), rng);
  std::vector<Edge> edges;
  for (const Edge& e : mesh.edges()) edges.push_back({shuffle[static_cast<std::size_t>(e[0])], shuffle[static_cast<std::size_t>(e[1])]});
  const std::vector<Index> order = reverse_cuthill_mckee(grid.num_points(), edges);
  ASSERT_TRUE(is_permutation_of_points(order));
  // Far narrower than the shuffle, and within a few cross-sections (5 x 4 points) of the grid's own.
  EXPECT_LT(4 * mean_edge_span(edges, order), mean_edge_span(edges));
  EXPECT_LT(mean_edge_span(edges, order), 2 * mean_edge_span(mesh.edges()));
  EXPECT_TRUE(reverse_cuthill_mckee(0, {}).empty());
  EXPECT_EQ(mean_edge_span({}), 0.0);
  EXPECT_THROW(reverse_cuthill_mckee(3, std::vector<Edge>{{0, 3}}), Error);
  EXPECT_THROW(reverse_cuthill_mckee(-1, {}), Error);
}

}  // namespace
}  // namespace fastcorot
