// The 3x3-block sparsity pattern of a system's assembled matrix (mass, force fields, identity
// blocks at held points), for the PETSc solver's compressed rows and a distribution's
// preallocation: per point, the sorted points of its nonzero blocks.
#pragma once

#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/sim/mechanical_system.h"

#include <algorithm>
#include <vector>

namespace fastcorot::sim_detail {

// Whether each point is held (fixed or isolated): its row and column hold only the identity block.
inline std::vector<bool> held_points(const MechanicalSystem<double>& system) {
  std::vector<bool> held(static_cast<std::size_t>(system.size()), false);
  for (Index i : system.fixed) held[static_cast<std::size_t>(i)] = true;
  for (Index i : system.isolated) held[static_cast<std::size_t>(i)] = true;
  for (Index i : system.moving) held[static_cast<std::size_t>(i)] = true;
  return held;
}

class PatternSink final : public MatrixSink<double> {
 public:
  PatternSink(Index points, const std::vector<bool>& held) : rows(static_cast<std::size_t>(points)), held_(held) {
    for (Index i = 0; i < points; ++i) rows[static_cast<std::size_t>(i)].push_back(i);
  }
  void add_block(Index row, Index col, const Mat3<double>&) override {
    const Index i = row / 3, j = col / 3;
    if (held_[static_cast<std::size_t>(i)] || held_[static_cast<std::size_t>(j)]) return;
    auto& columns = rows[static_cast<std::size_t>(i)];
    if (std::find(columns.begin(), columns.end(), j) == columns.end()) columns.push_back(j);
  }
  std::vector<std::vector<Index>> rows;

 private:
  const std::vector<bool>& held_;
};

// Every point's sorted block columns (the diagonal always among them).
inline std::vector<std::vector<Index>> block_pattern(const MechanicalSystem<double>& system,
                                                     const std::vector<bool>& held) {
  PatternSink sink(system.size(), held);
  if (system.mass.size() != 0) system.mass.add_to_matrix(sink, 1.0);
  for (const auto& field : system.force_fields) field->add_stiffness(sink, 1.0, 0, 1.0);
  for (auto& columns : sink.rows) {
    std::sort(columns.begin(), columns.end());
    columns.shrink_to_fit();
  }
  return std::move(sink.rows);
}

}  // namespace fastcorot::sim_detail
