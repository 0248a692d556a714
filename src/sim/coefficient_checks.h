// The check every ODE solver makes of its damping and scheme coefficients (internal to src/sim).
#pragma once

#include "fastcorot/core/error.h"

#include <cmath>

namespace fastcorot::detail {

// Throws fastcorot::Error "NAME = VALUE: must be finite and >= 0" (name: "Solver: attribute").
template <class Real>
void check_coefficient(Real value, const char* name) {
  if (!(value >= 0) || !std::isfinite(value)) throw make_error(name, " = ", value, ": must be finite and >= 0");
}

}  // namespace fastcorot::detail
