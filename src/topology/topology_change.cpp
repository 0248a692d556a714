#include "fastcorot/topology/topology_change.h"

#include <numeric>

namespace fastcorot {

std::vector<Index> old_to_new(Index old_size, std::span<const IndexMove> moves) {
  // Replays the moves on "which old item sits at each position".
  std::vector<Index> item_at(static_cast<std::size_t>(old_size));
  std::iota(item_at.begin(), item_at.end(), Index(0));
  apply_moves(item_at, moves);
  std::vector<Index> result(static_cast<std::size_t>(old_size), Index(-1));
  for (std::size_t position = 0; position < item_at.size(); ++position) {
    result[static_cast<std::size_t>(item_at[position])] = static_cast<Index>(position);
  }
  return result;
}

IndexRenumbering::IndexRenumbering(std::span<const Index> removed, std::span<const IndexMove> moves) {
  // Positions whose occupant changed, replayed like old_to_new but only where something moved.
  std::unordered_map<Index, Index> item_at;
  const auto occupant = [&](Index position) {
    const auto it = item_at.find(position);
    return it == item_at.end() ? position : it->second;
  };
  for (const IndexMove& move : moves) {
    const Index moved = occupant(move.from);
    item_at[move.from] = -1;  // the last position goes
    if (move.from != move.to) item_at[move.to] = moved;
  }
  for (Index r : removed) changed_[r] = -1;
  for (const auto& [position, item] : item_at) {
    if (item >= 0) changed_[item] = position;
  }
}

Index IndexRenumbering::operator()(Index old) const {
  const auto it = changed_.find(old);
  return it == changed_.end() ? old : it->second;
}

}  // namespace fastcorot
