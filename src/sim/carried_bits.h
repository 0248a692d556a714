// Carried solver state as integers (checkpoints store it so): a value's bit pattern, and a sparse
// matrix in compressed columns (nonzero count, then column starts, row indices and values; a lone 0
// for an empty matrix), read back with every index checked.
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/core/types.h"

#include <Eigen/SparseCore>

#include <bit>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace fastcorot::carried_bits {

template <class Real>
std::int64_t to_bits(Real value) {
  if constexpr (sizeof(Real) == 8) {
    return std::bit_cast<std::int64_t>(value);
  } else {
    return std::bit_cast<std::int32_t>(value);
  }
}

template <class Real>
Real from_bits(std::int64_t bits) {
  if constexpr (sizeof(Real) == 8) {
    return std::bit_cast<Real>(bits);
  } else {
    return std::bit_cast<Real>(static_cast<std::int32_t>(bits));
  }
}

template <class Real>
void push_matrix(std::vector<std::int64_t>& state, const Eigen::SparseMatrix<Real>& m) {
  state.push_back(m.nonZeros());
  if (m.nonZeros() == 0) return;
  state.insert(state.end(), m.outerIndexPtr(), m.outerIndexPtr() + m.outerSize() + 1);
  state.insert(state.end(), m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
  for (Eigen::Index k = 0; k < m.nonZeros(); ++k) state.push_back(to_bits(m.valuePtr()[k]));
}

// The number of values push_matrix wrote at the start of `state` for a size × size matrix; throws
// fastcorot::Error naming `owner` when they cannot be one.
inline std::size_t matrix_length(std::span<const std::int64_t> state, std::int64_t size, std::string_view owner) {
  if (state.empty() || state[0] < 0 || state[0] > size * size) {
    throw make_error(owner, ": the carried matrix is inconsistent (nonzero count)");
  }
  return state[0] == 0 ? 1 : static_cast<std::size_t>(1 + (size + 1) + 2 * state[0]);
}

// The matrix push_matrix wrote at the start of `state` (size × size; empty for a lone 0).
template <class Real>
Eigen::SparseMatrix<Real> read_matrix(std::span<const std::int64_t> state, std::int64_t size, std::string_view owner) {
  const std::size_t length = matrix_length(state, size, owner);
  const auto fail = [&](const char* why) { return make_error(owner, ": the carried matrix is inconsistent (", why, ")"); };
  if (state.size() < length) throw fail("length");
  const std::int64_t nonzeros = state[0];
  if (nonzeros == 0) return {};
  const auto outer = state.subspan(1, static_cast<std::size_t>(size + 1));
  const auto inner = state.subspan(static_cast<std::size_t>(size + 2), static_cast<std::size_t>(nonzeros));
  const auto values = state.subspan(static_cast<std::size_t>(size + 2 + nonzeros), static_cast<std::size_t>(nonzeros));
  if (outer.front() != 0 || outer.back() != nonzeros) throw fail("column starts");
  std::vector<Eigen::Triplet<Real>> entries;
  entries.reserve(static_cast<std::size_t>(nonzeros));
  for (std::int64_t column = 0; column < size; ++column) {
    const std::int64_t begin = outer[static_cast<std::size_t>(column)];
    const std::int64_t end = outer[static_cast<std::size_t>(column + 1)];
    if (begin > end || end > nonzeros) throw fail("column starts");
    for (std::int64_t k = begin; k < end; ++k) {
      const std::int64_t row = inner[static_cast<std::size_t>(k)];
      if (row < 0 || row >= size || (k > begin && row <= inner[static_cast<std::size_t>(k - 1)])) throw fail("row indices");
      entries.emplace_back(static_cast<Index>(row), static_cast<Index>(column), from_bits<Real>(values[static_cast<std::size_t>(k)]));
    }
  }
  Eigen::SparseMatrix<Real> m(static_cast<Index>(size), static_cast<Index>(size));
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  return m;
}

}  // namespace fastcorot::carried_bits
