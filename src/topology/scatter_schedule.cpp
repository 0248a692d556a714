#include "fastcorot/topology/scatter_schedule.h"

#include <algorithm>

namespace fastcorot {

template <std::size_t K>
ScatterSchedule make_scatter_schedule(Index num_points, std::span<const std::array<Index, K>> items,
                                      Index min_part) {
  Index bandwidth = 0;
  for (const auto& item : items) {
    const auto [low, high] = std::minmax_element(item.begin(), item.end());
    bandwidth = std::max(bandwidth, *high - *low);
  }
  ScatterSchedule schedule;
  const Index part_size = std::max<Index>({2 * bandwidth + 1, min_part, 1});
  schedule.parts = std::clamp<Index>(num_points / part_size, 1, 64);
  schedule.num_points = num_points;

  // Group key: phase-major, then part.
  const Index parts = schedule.parts;
  const Index groups_before[ScatterSchedule::kPhases + 1] = {0, parts, parts + (parts / 2),
                                                             parts + (parts / 2) + ((parts - 1) / 2),
                                                             parts + (parts / 2) + ((parts - 1) / 2) + 1};
  schedule.group_begin.assign(static_cast<std::size_t>(groups_before[ScatterSchedule::kPhases]) + 1, 0);
  std::vector<Index> group_of(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) group_of[i] = schedule.group_for(items[i]);
  const Index num_groups = groups_before[ScatterSchedule::kPhases];
  for (Index g : group_of) ++schedule.group_begin[static_cast<std::size_t>(g) + 1];
  for (std::size_t g = 0; g < static_cast<std::size_t>(num_groups); ++g) {
    schedule.group_begin[g + 1] += schedule.group_begin[g];
  }
  schedule.order.resize(items.size());
  std::vector<Index> next(schedule.group_begin.begin(), schedule.group_begin.end() - 1);
  for (std::size_t i = 0; i < items.size(); ++i) {
    schedule.order[static_cast<std::size_t>(next[static_cast<std::size_t>(group_of[i])]++)] = static_cast<Index>(i);
  }
  for (int p = 0; p <= ScatterSchedule::kPhases; ++p) schedule.phase_begin[static_cast<std::size_t>(p)] = groups_before[p];
  schedule.group_end.assign(schedule.group_begin.begin() + 1, schedule.group_begin.end());
  return schedule;
}

Index ScatterSchedule::group_at(Index position) const {
  const auto it = std::upper_bound(group_begin.begin(), group_begin.end() - 1, position);
  return static_cast<Index>(it - group_begin.begin()) - 1;
}

template ScatterSchedule make_scatter_schedule(Index, std::span<const std::array<Index, 2>>, Index);
template ScatterSchedule make_scatter_schedule(Index, std::span<const std::array<Index, 4>>, Index);

}  // namespace fastcorot
