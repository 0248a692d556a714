// A solver's carried vector (Newmark's a_t, the variational integrator's momentum) as the integers
// checkpoints store: a flag saying whether it is set, then the bits of each value as a double.
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/core/types.h"

#include <cstdint>
#include <cstring>
#include <vector>

namespace fastcorot::detail {

template <class Real>
std::vector<std::int64_t> encode_carried(bool set, const std::vector<Vec3<Real>>& values) {
  std::vector<std::int64_t> state{set ? 1 : 0};
  for (const auto& v : values) {
    for (int k = 0; k < 3; ++k) {
      const double value = static_cast<double>(v[k]);
      std::int64_t bits = 0;
      std::memcpy(&bits, &value, sizeof bits);
      state.push_back(bits);
    }
  }
  return state;
}

// Restores into `values` (whose size fixes the expected length); `what` names the solver in errors.
template <class Real>
bool decode_carried(const std::vector<std::int64_t>& state, std::vector<Vec3<Real>>& values, const char* what) {
  if (state.size() != 1 + 3 * values.size() || (state[0] != 0 && state[0] != 1)) {
    throw make_error(what, ": expected a flag and 3 values for each of ", values.size(), " points, got ", state.size(), " values");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      double value = 0;
      std::memcpy(&value, &state[1 + 3 * i + static_cast<std::size_t>(k)], sizeof value);
      values[i][k] = static_cast<Real>(value);
    }
  }
  return state[0] == 1;
}

}  // namespace fastcorot::detail
