// The checks every tetrahedral force field applies to its scene parameters before building: E and
// nu lists of one value or one per tetrahedron, and a finite, non-negative rayleighStiffness.
// (Each value's range is lame_parameters'; the tetrahedra are check_rest_volumes'.)
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/core/types.h"

#include <cmath>
#include <vector>

namespace fastcorot::detail {

template <class Real>
void check_material_lists(const std::vector<Real>& young, const std::vector<Real>& poisson, Real rayleigh_stiffness,
                          Index num_tetrahedra) {
  const auto check = [&](const std::vector<Real>& values, const char* name) {
    if (values.size() != 1 && values.size() != static_cast<std::size_t>(num_tetrahedra)) {
      throw make_error(name, ": ", values.size(), " values given; expected 1 or one per tetrahedron (",
                       num_tetrahedra, ")");
    }
  };
  check(young, "youngModulus");
  check(poisson, "poissonRatio");
  if (!(rayleigh_stiffness >= 0) || !std::isfinite(rayleigh_stiffness)) {
    throw make_error("rayleighStiffness = ", rayleigh_stiffness, ": must be a finite value >= 0");
  }
}

}  // namespace fastcorot::detail
