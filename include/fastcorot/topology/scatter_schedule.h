// ScatterSchedule: the order in which a loop over items (tetrahedra or edges) visits them when each
// item adds into arrays indexed by its vertices (or by its edges, which join its vertices), so that
// the loop can run on several threads without races and with results that do not depend on the
// thread count.
//
// The points are cut into `parts` contiguous index ranges, each longer than the mesh's bandwidth
// (the largest index span of one item), so that an item lies in one part or in two neighbouring
// ones; the cut depends on the mesh only, never on the threads. Part p's group holds the items
// whose lowest point lies in part p and whose highest lies in part p or p + 1: groups of even parts
// run in phase 0, those of odd parts in phase 1, and any other item (only ever one added later)
// goes to the single group of phase 2. Two groups of one phase never share a point (part p's group
// touches parts p and p + 1 only), so they may run concurrently; phases run one after the other,
// and each group runs its items in the given order. Every array entry therefore receives its
// contributions in one fixed order. The part count is a multiple of four where the mesh allows, and
// the cuts give every group about as many items, so that both phases split evenly over two threads.
//
// Groups may keep room for more items (topological changes): group g owns the positions
// [group_begin[g], group_begin[g + 1]) and visits [group_begin[g], group_end[g]). An item added
// later goes to the group its points say (group_for) when that group has room, else to the single
// group of phase 2, which is the last one and so can always grow at the end.
#pragma once

#include "fastcorot/core/types.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace fastcorot {

struct ScatterSchedule {
  static constexpr int kPhases = 3;

  Index parts = 1;
  std::vector<Index> part_begin;  // part p holds the points [part_begin[p], part_begin[p + 1])
  std::vector<Index> order;        // item indices in visiting order
  std::vector<Index> group_begin;  // group g owns order[group_begin[g], group_begin[g + 1])
  std::vector<Index> group_end;    // and visits order[group_begin[g], group_end[g])
  std::array<Index, kPhases + 1> phase_begin{};  // phase p runs groups [phase_begin[p], phase_begin[p + 1])

  Index num_groups() const { return static_cast<Index>(group_begin.size()) - 1; }
  // The group that owns position `position` of `order`.
  Index group_at(Index position) const;
  // The group an item over these points belongs to.
  template <std::size_t K>
  Index group_for(const std::array<Index, K>& item) const;

  // With an even number of parts and nothing in the serial group, a loop over the schedule can do
  // work per point just before a point's first item and just after its last: the group of even
  // part p runs before any other group touches parts p and p + 1 (first_points), and the group of
  // odd part p after every other group that touches parts p and p + 1, and part 0 for p = 1
  // (last_points). Each point is in one group's first_points and one group's last_points; the
  // ranges [begin, end) of points are empty for the other groups.
  bool has_first_and_last_points() const;
  std::array<Index, 2> first_points(Index group) const;
  std::array<Index, 2> last_points(Index group) const;
};

// The least number of points of a part, unless asked otherwise.
inline constexpr Index kDefaultMinPart = 256;

// Schedules `items` (point indices in [0, num_points)) keeping their relative order within each
// group. Parts hold more points than the bandwidth and at least `min_part`; at most 64 parts. Every
// group starts at a multiple of `align` (a SIMD batch of items then begins on a batch of data kept
// by position), the positions up to the next group being its room (order -1).
template <std::size_t K>
ScatterSchedule make_scatter_schedule(Index num_points, std::span<const std::array<Index, K>> items,
                                      Index min_part = kDefaultMinPart, Index align = 1);

// Calls body(begin, end) for every group, [begin, end) being its range of positions in
// schedule.order: phases in order, the groups of a phase on up to `threads` threads.
template <class Body>
void run_schedule(const ScatterSchedule& schedule, int threads, const Body& body);

// The same with body(group) for every group.
template <class Body>
void run_schedule_groups(const ScatterSchedule& schedule, int threads, const Body& body);

}  // namespace fastcorot

#include "fastcorot/core/parallel.h"

namespace fastcorot {

template <std::size_t K>
Index ScatterSchedule::group_for(const std::array<Index, K>& item) const {
  const auto [low, high] = std::minmax_element(item.begin(), item.end());
  const auto part_of = [&](Index v) {
    return static_cast<Index>(std::upper_bound(part_begin.begin() + 1, part_begin.end() - 1, v) - part_begin.begin()) - 1;
  };
  const Index p = part_of(*low), q = part_of(*high);
  // Groups are numbered phase-major: the even parts' groups, the odd parts', then the serial one.
  if (q == p || q == p + 1) return (p % 2 == 0) ? p / 2 : (parts + 1) / 2 + p / 2;
  return num_groups() - 1;
}

template <class Body>
void run_schedule_groups(const ScatterSchedule& schedule, int threads, const Body& body) {
  for (int phase = 0; phase < ScatterSchedule::kPhases; ++phase) {
    const Index first = schedule.phase_begin[static_cast<std::size_t>(phase)];
    const Index last = schedule.phase_begin[static_cast<std::size_t>(phase) + 1];
    run_tasks(threads, static_cast<int>(last - first), [&](int task) { body(first + task); });
  }
}

template <class Body>
void run_schedule(const ScatterSchedule& schedule, int threads, const Body& body) {
  run_schedule_groups(schedule, threads, [&](Index group) {
    const auto g = static_cast<std::size_t>(group);
    body(schedule.group_begin[g], schedule.group_end[g]);
  });
}

}  // namespace fastcorot
