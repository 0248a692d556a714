// ScatterSchedule: the order in which a loop over items (tetrahedra or edges) visits them when each
// item adds into arrays indexed by its vertices (or by its edges, which join its vertices), so that
// the loop can run on several threads without races and with results that do not depend on the
// thread count.
//
// The points are cut into `parts` contiguous index ranges; the cut depends on the mesh only (its
// point count and its bandwidth, the largest index span of one item), never on the threads. An item
// whose points all lie in part p goes to group p of phase 0; an item spanning parts p and p + 1 goes
// to group p of phase 1 (p even) or phase 2 (p odd); any other item to the single group of phase 3.
// Two items in different groups of one phase never share a point, so the groups of a phase may run
// concurrently; phases run one after the other, and each group runs its items in the given order.
// Every array entry therefore receives its contributions in one fixed order.
#pragma once

#include "fastcorot/core/types.h"

#include <array>
#include <span>
#include <vector>

namespace fastcorot {

struct ScatterSchedule {
  static constexpr int kPhases = 4;

  Index parts = 1;
  std::vector<Index> order;        // item indices in visiting order
  std::vector<Index> group_begin;  // group g visits order[group_begin[g], group_begin[g + 1])
  std::array<Index, kPhases + 1> phase_begin{};  // phase p runs groups [phase_begin[p], phase_begin[p + 1])

  Index num_groups() const { return static_cast<Index>(group_begin.size()) - 1; }
};

// Schedules `items` (point indices in [0, num_points)) keeping their relative order within each
// group. Parts hold at least twice the bandwidth (and at least `min_part` points), at most 64.
template <std::size_t K>
ScatterSchedule make_scatter_schedule(Index num_points, std::span<const std::array<Index, K>> items,
                                      Index min_part = 256);

// Calls body(begin, end) for every group, [begin, end) being its range of positions in
// schedule.order: phases in order, the groups of a phase on up to `threads` threads.
template <class Body>
void run_schedule(const ScatterSchedule& schedule, int threads, const Body& body);

}  // namespace fastcorot

#include "fastcorot/core/parallel.h"

namespace fastcorot {

template <class Body>
void run_schedule(const ScatterSchedule& schedule, int threads, const Body& body) {
  for (int phase = 0; phase < ScatterSchedule::kPhases; ++phase) {
    const Index first = schedule.phase_begin[static_cast<std::size_t>(phase)];
    const Index last = schedule.phase_begin[static_cast<std::size_t>(phase) + 1];
    run_tasks(threads, static_cast<int>(last - first), [&](int task) {
      const auto g = static_cast<std::size_t>(first + task);
      body(schedule.group_begin[g], schedule.group_begin[g + 1]);
    });
  }
}

}  // namespace fastcorot
