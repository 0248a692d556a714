// CorotationalForceField: following topological changes (the rest of the class is in
// corotational_force_field.cpp). Each change costs time proportional to the tetrahedra and edges
// it touches: removed tetrahedra leave their schedule group (its last member takes the place),
// removed edges leave a free slot in theirs, and new items go to the group their points select
// when it has room, else to the serial group of the last phase. When too much has gone there or
// too many slots are free, everything is rebuilt once (amortised over the changes that led there).
#include "fastcorot/fem/corotational_force_field.h"

#include "fastcorot/core/error.h"
#include "force_kernels.h"

#include <algorithm>

namespace fastcorot {

template <class Real>
void CorotationalForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron> tetrahedra) const {
  check_rest_volumes<Real>(tetrahedra, rest_positions_, mesh_->num_tetrahedra());
}

template <class Real>
TopologyChange CorotationalForceField<Real>::add_tetrahedra(std::span<const Tetrahedron> tetrahedra) {
  check_new_tetrahedra(tetrahedra);
  TopologyChange change = mesh_->add_tetrahedra(tetrahedra);
  apply(change);
  return change;
}

template <class Real>
TopologyChange CorotationalForceField<Real>::remove_tetrahedra(std::span<const Index> indices) {
  TopologyChange change = mesh_->remove_tetrahedra(indices);
  apply(change);
  return change;
}

template <class Real>
void CorotationalForceField<Real>::apply(const TopologyChange& change) {
  ScatterSchedule& tets = tetrahedron_schedule_;
  // Removed tetrahedra: each leaves its group (the group's last member moves into its position),
  // then the mesh's last tetrahedron takes its index.
  for (std::size_t k = 0; k < change.tetrahedron_moves.size(); ++k) {
    const Index hole = change.removed_tetrahedra[k];
    const IndexMove move = change.tetrahedron_moves[k];
    const auto p = static_cast<std::size_t>(position_[static_cast<std::size_t>(hole)]);
    const auto g = static_cast<std::size_t>(tets.group_at(static_cast<Index>(p)));
    const auto last = static_cast<std::size_t>(--tets.group_end[g]);
    if (p != last) {
      tets.order[p] = tets.order[last];
      position_[static_cast<std::size_t>(tets.order[p])] = static_cast<Index>(p);
      move_rest_data(last, p);  // rest data stays with its position
    }
    tets.order[last] = -1;
    const auto from = static_cast<std::size_t>(move.from), to = static_cast<std::size_t>(move.to);
    if (from != to) {
      position_[to] = position_[from];
      tets.order[static_cast<std::size_t>(position_[to])] = move.to;
    }
    position_.pop_back();
  }
  // Per-tetrahedron parameter lists follow; a single value applies to every tetrahedron.
  if (young_per_tetrahedron_) apply_moves(parameters_.young_modulus, std::span<const IndexMove>(change.tetrahedron_moves));
  if (poisson_per_tetrahedron_) apply_moves(parameters_.poisson_ratio, std::span<const IndexMove>(change.tetrahedron_moves));

  // Removed edges free their slots (no tetrahedron adds to them any more: zero blocks).
  for (std::size_t k = 0; k < change.edge_moves.size(); ++k) {
    const Index slot = edge_slot_[static_cast<std::size_t>(change.removed_edges[k])];
    free_slots_[static_cast<std::size_t>(edge_schedule_.group_at(slot))].push_back(slot);
    ++num_free_slots_;
    const IndexMove move = change.edge_moves[k];
    edge_slot_[static_cast<std::size_t>(move.to)] = edge_slot_[static_cast<std::size_t>(move.from)];
    edge_slot_.pop_back();
  }

  // Added edges, then added tetrahedra (new tetrahedra take entry 0 of per-tetrahedron lists).
  for (Index e = change.first_added_edge; e < change.first_added_edge + change.num_added_edges; ++e) {
    edge_slot_.push_back(place_edge(slot_edge(mesh_->edges()[static_cast<std::size_t>(e)])));
  }
  const Index first = change.first_added_tetrahedron;
  for (Index t = first; t < first + change.num_added_tetrahedra; ++t) {
    if (young_per_tetrahedron_) parameters_.young_modulus.push_back(added_young_);
    if (poisson_per_tetrahedron_) parameters_.poisson_ratio.push_back(added_poisson_);
    place_tetrahedron(t);
    set_rest_data(t);
  }

  if (schedules_degraded()) {
    rebuild();
  } else {
    stale_ = true;
  }
}

template <class Real>
Index CorotationalForceField<Real>::place_edge(const Edge& edge) {
  auto& own = free_slots_[static_cast<std::size_t>(edge_schedule_.group_for(edge))];
  auto& serial = free_slots_.back();
  if (own.empty() && serial.empty()) {
    // A new slot at the end, owned by the last (serial) group.
    serial.push_back(static_cast<Index>(edge_vertices_.size()));
    edge_vertices_.push_back(edge);
    blocks_.resize(9 * edge_vertices_.size() + kernels::kBlockTail, Real(0));
    ++num_free_slots_;
    edge_schedule_.group_begin.back() = static_cast<Index>(edge_vertices_.size());
    edge_schedule_.group_end.back() = static_cast<Index>(edge_vertices_.size());
  }
  auto& from = own.empty() ? serial : own;
  const Index slot = from.back();
  from.pop_back();
  --num_free_slots_;
  edge_vertices_[static_cast<std::size_t>(slot)] = edge;
  return slot;
}

template <class Real>
void CorotationalForceField<Real>::place_tetrahedron(Index t) {
  ScatterSchedule& tets = tetrahedron_schedule_;
  auto g = static_cast<std::size_t>(tets.group_for(internal(mesh_->tetrahedron(t))));
  if (tets.group_end[g] == tets.group_begin[g + 1]) g = static_cast<std::size_t>(tets.num_groups() - 1);
  if (tets.group_end[g] == tets.group_begin[g + 1]) {
    // The serial group is the last one: it grows at the end.
    tets.order.push_back(-1);
    ++tets.group_begin[g + 1];
  }
  const auto position = static_cast<std::size_t>(tets.group_end[g]++);
  tets.order[position] = t;
  position_.push_back(static_cast<Index>(position));
}

// True when the serial phase or the free slots have grown enough to cost more than a rebuild.
template <class Real>
bool CorotationalForceField<Real>::schedules_degraded() const {
  const ScatterSchedule& tets = tetrahedron_schedule_;
  const std::size_t serial = static_cast<std::size_t>(tets.group_end.back() - tets.group_begin[tets.group_begin.size() - 2]);
  const std::size_t n = position_.size();
  return serial > std::max<std::size_t>(1024, n / 8) ||
         static_cast<std::size_t>(num_free_slots_) > std::max<std::size_t>(1024, edge_slot_.size() / 4);
}

// The members defined here, for both scalars (the class itself is instantiated with the others).
#define FASTCOROT_TOPOLOGY_MEMBERS(Real)                                                                  \
  template void CorotationalForceField<Real>::check_new_tetrahedra(std::span<const Tetrahedron>) const; \
  template TopologyChange CorotationalForceField<Real>::add_tetrahedra(std::span<const Tetrahedron>);   \
  template TopologyChange CorotationalForceField<Real>::remove_tetrahedra(std::span<const Index>);      \
  template void CorotationalForceField<Real>::apply(const TopologyChange&);                            \
  template Index CorotationalForceField<Real>::place_edge(const Edge&);                                \
  template void CorotationalForceField<Real>::place_tetrahedron(Index);                                \
  template bool CorotationalForceField<Real>::schedules_degraded() const;
FASTCOROT_TOPOLOGY_MEMBERS(float)
FASTCOROT_TOPOLOGY_MEMBERS(double)
#undef FASTCOROT_TOPOLOGY_MEMBERS

}  // namespace fastcorot
