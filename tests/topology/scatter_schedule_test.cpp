// ScatterSchedule: every item scheduled once, in order within its group, and no two groups of one
// phase sharing a point (so they may run concurrently); run_schedule visits every group once on any
// thread count.
#include "fastcorot/topology/scatter_schedule.h"

#include "fastcorot/topology/regular_grid.h"
#include "fastcorot/topology/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <random>
#include <set>

namespace fastcorot {
namespace {

template <std::size_t K>
void check_schedule(Index num_points, std::span<const std::array<Index, K>> items, const ScatterSchedule& s) {
  // The visited positions hold a permutation of the items, each group in increasing item order;
  // the room after a group's items holds -1.
  ASSERT_EQ(s.group_begin.front(), 0);
  ASSERT_EQ(s.group_begin.back(), static_cast<Index>(s.order.size()));
  ASSERT_EQ(s.group_end.size() + 1, s.group_begin.size());
  std::vector<Index> sorted;
  for (Index g = 0; g < s.num_groups(); ++g) {
    ASSERT_LE(s.group_begin[g], s.group_end[g]);
    ASSERT_LE(s.group_end[g], s.group_begin[g + 1]);
    EXPECT_TRUE(std::is_sorted(s.order.begin() + s.group_begin[g], s.order.begin() + s.group_end[g]));
    sorted.insert(sorted.end(), s.order.begin() + s.group_begin[g], s.order.begin() + s.group_end[g]);
    for (Index i = s.group_end[g]; i < s.group_begin[g + 1]; ++i) EXPECT_EQ(s.order[i], -1) << "room " << i;
  }
  std::sort(sorted.begin(), sorted.end());
  std::vector<Index> all(items.size());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(sorted, all);
  EXPECT_EQ(s.phase_begin.front(), 0);
  EXPECT_EQ(s.phase_begin.back(), s.num_groups());
  // Groups of one phase touch disjoint points.
  for (int phase = 0; phase < ScatterSchedule::kPhases; ++phase) {
    std::vector<Index> owner(static_cast<std::size_t>(num_points), -1);
    for (Index g = s.phase_begin[phase]; g < s.phase_begin[phase + 1]; ++g) {
      for (Index i = s.group_begin[g]; i < s.group_end[g]; ++i) {
        for (Index v : items[static_cast<std::size_t>(s.order[i])]) {
          auto& o = owner[static_cast<std::size_t>(v)];
          EXPECT_TRUE(o == -1 || o == g) << "point " << v << " in groups " << o << " and " << g << " of phase " << phase;
          o = g;
        }
      }
    }
  }
}

// The 40 × 10 × 10 benchmark beam's mesh.
const TetMesh& benchmark_beam() {
  static const TetMesh mesh = [] {
    RegularGrid grid;
    grid.n = {40, 10, 10};
    return TetMesh(grid.num_points(), grid_tetrahedra(grid, true));
  }();
  return mesh;
}

// first_points / last_points: every point in one group's first range and one group's last range;
// the group whose first range holds a point runs before every other group that touches the point
// (in an earlier phase), the group whose last range holds it after every other (a later phase).
template <std::size_t K>
void check_first_and_last_points(Index num_points, std::span<const std::array<Index, K>> items,
                                 const ScatterSchedule& s) {
  ASSERT_TRUE(s.has_first_and_last_points());
  const auto phase_of = [&](Index g) { return g < s.phase_begin[1] ? 0 : g < s.phase_begin[2] ? 1 : 2; };
  std::vector<Index> first(static_cast<std::size_t>(num_points), -1), last = first;
  for (Index g = 0; g < s.num_groups(); ++g) {
    for (auto [ranges, owner] : {std::pair{s.first_points(g), &first}, std::pair{s.last_points(g), &last}}) {
      for (Index v = ranges[0]; v < ranges[1]; ++v) {
        auto& o = (*owner)[static_cast<std::size_t>(v)];
        EXPECT_EQ(o, -1) << "point " << v << " in the ranges of groups " << o << " and " << g;
        o = g;
      }
    }
  }
  for (Index v = 0; v < num_points; ++v) {
    ASSERT_NE(first[static_cast<std::size_t>(v)], -1) << "point " << v << " in no first range";
    ASSERT_NE(last[static_cast<std::size_t>(v)], -1) << "point " << v << " in no last range";
  }
  for (Index g = 0; g < s.num_groups(); ++g) {
    for (Index i = s.group_begin[g]; i < s.group_end[g]; ++i) {
      for (Index v : items[static_cast<std::size_t>(s.order[i])]) {
        const Index f = first[static_cast<std::size_t>(v)], l = last[static_cast<std::size_t>(v)];
        if (f != g) EXPECT_LT(phase_of(f), phase_of(g)) << "point " << v << ", group " << g << ", first " << f;
        if (l != g) EXPECT_GT(phase_of(l), phase_of(g)) << "point " << v << ", group " << g << ", last " << l;
      }
    }
  }
}

TEST(ScatterSchedule, FirstAndLastPointsComeBeforeAndAfterEveryOtherGroup) {
  const TetMesh& mesh = benchmark_beam();
  const auto tets = make_scatter_schedule<4>(mesh.num_points(), mesh.tetrahedra());
  EXPECT_EQ(tets.parts, 8);
  check_first_and_last_points<4>(mesh.num_points(), mesh.tetrahedra(), tets);
  const auto edges = make_scatter_schedule<2>(mesh.num_points(), mesh.edges());
  check_first_and_last_points<2>(mesh.num_points(), mesh.edges(), edges);
  // Two parts: part 1's group is the last to touch both.
  std::vector<std::array<Index, 2>> chain;
  for (Index i = 0; i + 5 < 600; ++i) chain.push_back({i, i + 5});
  const auto two = make_scatter_schedule<2>(600, std::span<const std::array<Index, 2>>(chain));
  ASSERT_EQ(two.parts, 2);
  check_first_and_last_points<2>(600, std::span<const std::array<Index, 2>>(chain), two);
  // Not for one part, nor once the serial group holds an item.
  const std::vector<std::array<Index, 2>> few = {{0, 1}, {1, 2}, {0, 2}};
  EXPECT_FALSE(make_scatter_schedule<2>(3, std::span<const std::array<Index, 2>>(few)).has_first_and_last_points());
  ScatterSchedule grown = edges;
  grown.group_end.back() += 1;
  EXPECT_FALSE(grown.has_first_and_last_points());
}

TEST(ScatterSchedule, GridTetrahedraAndEdges) {
  RegularGrid grid;
  grid.n = {10, 6, 40};  // z slowest
  const TetMesh mesh(grid.num_points(), grid_tetrahedra(grid, true));
  const auto tets = make_scatter_schedule<4>(mesh.num_points(), mesh.tetrahedra());
  EXPECT_GE(tets.parts, 3);
  check_schedule<4>(mesh.num_points(), mesh.tetrahedra(), tets);
  const auto edges = make_scatter_schedule<2>(mesh.num_points(), mesh.edges());
  check_schedule<2>(mesh.num_points(), mesh.edges(), edges);
}

TEST(ScatterSchedule, PartsAreLongerThanTheBandwidthAndComeInFours) {
  // 4,000 points, items of index span 441 (the 40 x 10 x 10 benchmark beam's): at most 9 parts of
  // 442 points, so 8; each phase then has four groups of about the same size.
  const TetMesh& mesh = benchmark_beam();
  const auto tets = make_scatter_schedule<4>(mesh.num_points(), mesh.tetrahedra());
  ASSERT_EQ(tets.parts, 8);
  EXPECT_EQ(tets.phase_begin[1] - tets.phase_begin[0], 4);
  EXPECT_EQ(tets.phase_begin[2] - tets.phase_begin[1], 4);
  ASSERT_EQ(tets.part_begin.size(), 9u);
  EXPECT_EQ(tets.part_begin.front(), 0);
  EXPECT_EQ(tets.part_begin.back(), mesh.num_points());
  for (std::size_t p = 0; p < 8; ++p) EXPECT_GE(tets.part_begin[p + 1] - tets.part_begin[p], 442) << "part " << p;
  const double mean = mesh.num_tetrahedra() / 8.0;
  for (Index g = 0; g < 8; ++g) {
    EXPECT_NEAR(tets.group_end[g] - tets.group_begin[g], mean, 0.1 * mean) << "group " << g;
  }
  check_schedule<4>(mesh.num_points(), mesh.tetrahedra(), tets);
}

TEST(ScatterSchedule, PartsAreCutFromTheBandwidth) {
  // Random tetrahedra over many points span nearly everything: one part, and still a valid schedule.
  std::mt19937 rng(3);
  std::uniform_int_distribution<Index> pick(0, 1999);
  std::vector<std::array<Index, 4>> items;
  for (int i = 0; i < 500; ++i) items.push_back({pick(rng), pick(rng), pick(rng), pick(rng)});
  const auto wide = make_scatter_schedule<4>(2000, std::span<const std::array<Index, 4>>(items), 16);
  EXPECT_EQ(wide.parts, 1);
  check_schedule<4>(2000, std::span<const std::array<Index, 4>>(items), wide);
  // Narrow items (span 9) over 2000 points with parts of at least 16 points: capped at 64 parts.
  items.clear();
  for (Index i = 0; i + 9 < 2000; i += 3) items.push_back({i, i + 9, i + 4, i + 1});
  const auto narrow = make_scatter_schedule<4>(2000, std::span<const std::array<Index, 4>>(items), 16);
  EXPECT_EQ(narrow.parts, 64);
  check_schedule<4>(2000, std::span<const std::array<Index, 4>>(items), narrow);
}

TEST(ScatterSchedule, GroupsStartAtMultiplesOfTheAlignment) {
  const TetMesh& mesh = benchmark_beam();
  const auto plain = make_scatter_schedule<4>(mesh.num_points(), mesh.tetrahedra());
  const auto aligned = make_scatter_schedule<4>(mesh.num_points(), mesh.tetrahedra(), kDefaultMinPart, 8);
  check_schedule<4>(mesh.num_points(), mesh.tetrahedra(), aligned);
  ASSERT_EQ(aligned.num_groups(), plain.num_groups());
  Index room = 0;
  for (Index g = 0; g < aligned.num_groups(); ++g) {
    EXPECT_EQ(aligned.group_begin[g] % 8, 0) << "group " << g;
    // The same items in the same order as without alignment; less than one batch of room.
    EXPECT_TRUE(std::equal(aligned.order.begin() + aligned.group_begin[g], aligned.order.begin() + aligned.group_end[g],
                           plain.order.begin() + plain.group_begin[g], plain.order.begin() + plain.group_end[g]))
        << "group " << g;
    EXPECT_LT(aligned.group_begin[g + 1] - aligned.group_end[g], 8) << "group " << g;
    room += aligned.group_begin[g + 1] - aligned.group_end[g];
  }
  EXPECT_GT(room, 0);  // the grid's groups are not all multiples of 8 long
}

TEST(ScatterSchedule, SmallMeshIsOnePart) {
  const std::vector<std::array<Index, 2>> items = {{0, 1}, {1, 2}, {0, 2}};
  const auto s = make_scatter_schedule<2>(3, std::span<const std::array<Index, 2>>(items));
  EXPECT_EQ(s.parts, 1);
  check_schedule<2>(3, std::span<const std::array<Index, 2>>(items), s);
}

TEST(ScatterSchedule, RunScheduleVisitsEveryGroupOnceOnAnyThreadCount) {
  RegularGrid grid;
  grid.n = {8, 5, 16};
  const TetMesh mesh(grid.num_points(), grid_tetrahedra(grid, true));
  const auto s = make_scatter_schedule<4>(mesh.num_points(), mesh.tetrahedra());
  for (int threads : {1, 2, 4}) {
    std::vector<std::atomic<int>> visits(static_cast<std::size_t>(mesh.num_tetrahedra()));
    run_schedule(s, threads, [&](Index begin, Index end) {
      for (Index i = begin; i < end; ++i) visits[static_cast<std::size_t>(s.order[i])]++;
    });
    for (const auto& v : visits) EXPECT_EQ(v.load(), 1) << threads << " threads";
  }
}

}  // namespace
}  // namespace fastcorot
