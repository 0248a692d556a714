// Four values of one scalar type in one SIMD register (GCC's vector extension, which Clang shares:
// AVX2 for double, SSE for float; plain code where neither exists). Lane-wise arithmetic with the
// usual operators, so results are those of the same scalar operations, lane by lane. Internal to the
// library's sources and tests (not installed: cmake/install.cmake).
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

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

// |v| lane by lane: the sign bit cleared, as std::abs does (so −0 gives +0).
template <class Real>
inline Packed<Real> packed_abs(const Packed<Real>& v) {
  using Bits = std::conditional_t<sizeof(Real) == 8, std::int64_t, std::int32_t>;
  typedef Bits Mask __attribute__((vector_size(sizeof(Packed<Real>))));
  Mask bits;
  std::memcpy(&bits, &v, sizeof v);
  bits &= std::numeric_limits<Bits>::max();
  Packed<Real> r;
  std::memcpy(&r, &bits, sizeof r);
  return r;
}

// A point's three values and a zero (any vector type with Scalar and operator[], such as Vec3).
template <class Point>
inline Packed<typename Point::Scalar> packed_point(const Point& v) {
  return Packed<typename Point::Scalar>{v[0], v[1], v[2], typename Point::Scalar(0)};
}

// The lanes (v[i0], v[i1], v[i2], v[i3]) of a Packed v.
template <int i0, int i1, int i2, int i3, class Pack>
inline Pack permute(const Pack& v) {
  return __builtin_shufflevector(v, v, i0, i1, i2, i3);
}

// Four points (x, y, z, anything) as rows → their coordinates as three rows of four lanes:
// x = (a[0], b[0], c[0], d[0]), y = (a[1], ...), z = (a[2], ...).
template <class Pack>
inline void points_to_lanes(const Pack& a, const Pack& b, const Pack& c, const Pack& d, Pack& x, Pack& y, Pack& z) {
  const Pack ab02 = __builtin_shufflevector(a, b, 0, 4, 2, 6);  // a0 b0 a2 b2
  const Pack ab13 = __builtin_shufflevector(a, b, 1, 5, 3, 7);  // a1 b1 a3 b3
  const Pack cd02 = __builtin_shufflevector(c, d, 0, 4, 2, 6);
  const Pack cd13 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
  x = __builtin_shufflevector(ab02, cd02, 0, 1, 4, 5);
  y = __builtin_shufflevector(ab13, cd13, 0, 1, 4, 5);
  z = __builtin_shufflevector(ab02, cd02, 2, 3, 6, 7);
}

// The reverse: three rows of four lanes → four points (x[l], y[l], z[l], 0).
template <class Pack>
inline void lanes_to_points(const Pack& x, const Pack& y, const Pack& z, Pack (&points)[4]) {
  const Pack zero{};
  const Pack xy02 = __builtin_shufflevector(x, y, 0, 4, 2, 6);  // x0 y0 x2 y2
  const Pack xy13 = __builtin_shufflevector(x, y, 1, 5, 3, 7);  // x1 y1 x3 y3
  const Pack z02 = __builtin_shufflevector(z, zero, 0, 4, 2, 6);  // z0 0 z2 0
  const Pack z13 = __builtin_shufflevector(z, zero, 1, 5, 3, 7);
  points[0] = __builtin_shufflevector(xy02, z02, 0, 1, 4, 5);
  points[1] = __builtin_shufflevector(xy13, z13, 0, 1, 4, 5);
  points[2] = __builtin_shufflevector(xy02, z02, 2, 3, 6, 7);
  points[3] = __builtin_shufflevector(xy13, z13, 2, 3, 6, 7);
}

}  // namespace fastcorot
