// SOFA's type::Vec arithmetic where its order or its guards decide results (LocalMinDistance's
// filters and rules): dot products summed x, then + y, then + z, as type::Vec does, so that signs
// near zero fall as SOFA's do; normalize(), which leaves a vector of norm ≤ machine epsilon as it
// is.
#pragma once

#include "fastcorot/core/types.h"

#include <cmath>
#include <limits>

namespace fastcorot::sofa_vec {

template <class Real>
Real dot3(const Vec3<Real>& u, const Vec3<Real>& v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

template <class Real>
Real norm3(const Vec3<Real>& v) {
  return std::sqrt(dot3(v, v));
}

// SOFA's Vec::normalize: divide by the norm when it exceeds machine epsilon, else leave as is.
template <class Real>
Vec3<Real> sofa_normalized(Vec3<Real> v) {
  const Real n = norm3(v);
  if (n > std::numeric_limits<Real>::epsilon()) v /= n;
  return v;
}

template <class Real>
Vec3<Real> unit_triangle_normal(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c) {
  return sofa_normalized(Vec3<Real>((b - a).cross(c - a)));
}

}  // namespace fastcorot::sofa_vec
