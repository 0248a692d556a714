#include "fastcorot/topology/scatter_schedule.h"

#include <algorithm>

namespace fastcorot {

template <std::size_t K>
ScatterSchedule make_scatter_schedule(Index num_points, std::span<const std::array<Index, K>> items,
                                      Index min_part, Index align) {
  // The bandwidth, and the items counted by lowest point: below[v] items have their lowest point < v.
  Index bandwidth = 0;
  std::vector<std::int64_t> below(static_cast<std::size_t>(num_points) + 1, 0);
  for (const auto& item : items) {
    const auto [low, high] = std::minmax_element(item.begin(), item.end());
    bandwidth = std::max(bandwidth, *high - *low);
    ++below[static_cast<std::size_t>(*low) + 1];
  }
  for (std::size_t v = 1; v < below.size(); ++v) below[v] += below[v - 1];
  ScatterSchedule schedule;
  const Index part_size = std::max<Index>({bandwidth + 1, min_part, 1});
  const Index most = std::clamp<Index>(num_points / part_size, 1, 64);
  const Index parts = most >= 4 ? most / 4 * 4 : std::min<Index>(most, 2);
  schedule.parts = parts;
  // An item goes to the group of its lowest point's part: cut where the count of items by lowest
  // point reaches the next multiple of items / parts, keeping every part at least part_size long.
  schedule.part_begin.assign(static_cast<std::size_t>(parts) + 1, num_points);
  schedule.part_begin[0] = 0;
  for (Index p = 1; p < parts; ++p) {
    const std::int64_t target = static_cast<std::int64_t>(items.size()) * p / parts;
    const auto reached = std::lower_bound(below.begin(), below.end(), target);
    const Index cut = static_cast<Index>(reached - below.begin());
    const auto pi = static_cast<std::size_t>(p);
    schedule.part_begin[pi] = std::clamp<Index>(cut, schedule.part_begin[pi - 1] + part_size,
                                                num_points - (parts - p) * part_size);
  }

  // Group key: phase-major (even parts, odd parts, the serial group), then part.
  const Index groups_before[ScatterSchedule::kPhases + 1] = {0, (parts + 1) / 2, parts, parts + 1};
  schedule.group_begin.assign(static_cast<std::size_t>(groups_before[ScatterSchedule::kPhases]) + 1, 0);
  std::vector<Index> group_of(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) group_of[i] = schedule.group_for(items[i]);
  const auto num_groups = static_cast<std::size_t>(groups_before[ScatterSchedule::kPhases]);
  std::vector<Index> sizes(num_groups, 0);
  for (Index g : group_of) ++sizes[static_cast<std::size_t>(g)];
  // Each group starts at a multiple of `align`; the positions between a group's items and the next
  // group are room (order -1), for items added later.
  const Index step = std::max<Index>(align, 1);
  schedule.group_end.resize(num_groups);
  for (std::size_t g = 0; g < num_groups; ++g) {
    schedule.group_end[g] = schedule.group_begin[g] + sizes[g];
    schedule.group_begin[g + 1] = g + 1 < num_groups ? (schedule.group_end[g] + step - 1) / step * step : schedule.group_end[g];
  }
  schedule.order.assign(static_cast<std::size_t>(schedule.group_begin.back()), -1);
  std::vector<Index> next(schedule.group_begin.begin(), schedule.group_begin.end() - 1);
  for (std::size_t i = 0; i < items.size(); ++i) {
    schedule.order[static_cast<std::size_t>(next[static_cast<std::size_t>(group_of[i])]++)] = static_cast<Index>(i);
  }
  for (int p = 0; p <= ScatterSchedule::kPhases; ++p) schedule.phase_begin[static_cast<std::size_t>(p)] = groups_before[p];
  return schedule;
}

bool ScatterSchedule::has_first_and_last_points() const {
  const auto serial = static_cast<std::size_t>(phase_begin[2]);
  return parts >= 2 && parts % 2 == 0 && group_end[serial] == group_begin[serial];
}

// Groups of phase 0 are those of parts 0, 2, 4, ..., then phase 1's of parts 1, 3, 5, ...
std::array<Index, 2> ScatterSchedule::first_points(Index group) const {
  if (group < phase_begin[0] || group >= phase_begin[1]) return {0, 0};
  const Index p = 2 * (group - phase_begin[0]);
  return {part_begin[static_cast<std::size_t>(p)], part_begin[static_cast<std::size_t>(p + 2)]};
}

std::array<Index, 2> ScatterSchedule::last_points(Index group) const {
  if (group < phase_begin[1] || group >= phase_begin[2]) return {0, 0};
  const Index p = 2 * (group - phase_begin[1]) + 1;
  return {part_begin[static_cast<std::size_t>(p == 1 ? 0 : p)], part_begin[static_cast<std::size_t>(std::min(p + 2, parts))]};
}

Index ScatterSchedule::group_at(Index position) const {
  const auto it = std::upper_bound(group_begin.begin(), group_begin.end() - 1, position);
  return static_cast<Index>(it - group_begin.begin()) - 1;
}

template ScatterSchedule make_scatter_schedule(Index, std::span<const std::array<Index, 2>>, Index, Index);
template ScatterSchedule make_scatter_schedule(Index, std::span<const std::array<Index, 4>>, Index, Index);

}  // namespace fastcorot
