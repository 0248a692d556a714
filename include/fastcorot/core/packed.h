// Four values of one scalar type in one SIMD register (GCC's vector extension, which Clang shares:
// AVX2 for double, SSE for float; plain code where neither exists). Lane-wise arithmetic with the
// usual operators, so results are those of the same scalar operations, lane by lane. Internal to the
// library's sources and tests (not installed: cmake/install.cmake).
#pragma once

#include <cstring>

namespace fastcorot {

template <class Real>
struct PackedType;
template <>
struct PackedType<double> {
  typedef double type __attribute__((vector_size(32)));
};
template <>
struct PackedType<float> {
  typedef float type __attribute__((vector_size(16)));
};
template <class Real>
using Packed = typename PackedType<Real>::type;

// The four values at p (no alignment needed).
template <class Real>
inline Packed<Real> load_packed(const Real* p) {
  Packed<Real> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <class Real>
inline void store_packed(Real* p, const Packed<Real>& v) {
  std::memcpy(p, &v, sizeof v);
}

template <class Real>
inline Packed<Real> broadcast(Real a) {
  return Packed<Real>{a, a, a, a};
}

// The lanes (v[i0], v[i1], v[i2], v[i3]) of a Packed v.
template <int i0, int i1, int i2, int i3, class Pack>
inline Pack permute(const Pack& v) {
  return __builtin_shufflevector(v, v, i0, i1, i2, i3);
}

}  // namespace fastcorot
