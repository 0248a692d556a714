// The mutable state of one deformable object (SOFA's MechanicalObject): positions, velocities and
// rest positions of #V points. Models (force field, mass, constraints) never own it; solvers update it.
#pragma once

#include "fastcorot/core/types.h"

#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
struct MechanicalState {
  std::vector<Vec3<Real>> position;
  std::vector<Vec3<Real>> velocity;
  std::vector<Vec3<Real>> rest_position;

  Index size() const { return static_cast<Index>(position.size()); }
};

// Small vector kernels over arrays of points, used by solvers.
template <class Real>
using Points = std::vector<Vec3<Real>>;

template <class Real>
Real dot(std::span<const Vec3<Real>> a, std::span<const Vec3<Real>> b) {
  Real sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += a[i].dot(b[i]);
  return sum;
}

template <class Real>
void set_zero(std::span<Vec3<Real>> a) {
  for (auto& v : a) v.setZero();
}

// True when every coordinate is finite.
template <class Real>
bool all_finite(std::span<const Vec3<Real>> a) {
  for (const auto& v : a) {
    if (!v.allFinite()) return false;
  }
  return true;
}

}  // namespace fastcorot
