// Vector kernels shared by the iterative solvers (conjugate_gradient.cpp,
// preconditioned_conjugate_gradient.cpp): sums over a range of coordinates in a fixed order, so that
// parallel_sum over fixed chunks gives the same bits on any thread count.
#pragma once

#include "fastcorot/core/packed.h"
#include "fastcorot/core/types.h"

#include <cstddef>
#include <span>

namespace fastcorot::solver_vectors {

// Every sum here keeps four interleaved partial sums in one SIMD register (lane k sums the terms
// i = begin + k mod 4, those past the last whole four in lane 0: a fixed order), then adds the
// lanes pairwise.
template <class Real>
Real sum_lanes(const Packed<Real>& partial) {
  return (partial[0] + partial[1]) + (partial[2] + partial[3]);
}

// sum_i a[i] b[i] over [begin, end).
template <class Real>
Real dot_range(const Real* a, const Real* b, std::size_t begin, std::size_t end) {
  Packed<Real> partial{};
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) partial += load_packed(a + i) * load_packed(b + i);
  for (; i < end; ++i) partial[0] += a[i] * b[i];
  return sum_lanes<Real>(partial);
}

// x += alpha p and r -= alpha q over [begin, end), returning the new r^T r summed exactly as
// dot_range(r, r, begin, end) would sum it (the same lanes, in the same order), in the same loop:
// the sum's chain of additions then overlaps the updates instead of running after them.
template <class Real>
Real update_range(Real* x, Real* r, const Real* p, const Real* q, Real alpha, std::size_t begin, std::size_t end) {
  const Packed<Real> a = broadcast(alpha);
  Packed<Real> partial{};
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) {
    store_packed(x + i, load_packed(x + i) + a * load_packed(p + i));
    const Packed<Real> ri = load_packed(r + i) - a * load_packed(q + i);
    store_packed(r + i, ri);
    partial += ri * ri;
  }
  for (; i < end; ++i) {
    x[i] += alpha * p[i];
    r[i] -= alpha * q[i];
    partial[0] += r[i] * r[i];
  }
  return sum_lanes<Real>(partial);
}

template <class Real>
Real* flat(std::span<Vec3<Real>> v) {
  return v.data()->data();
}
template <class Real>
const Real* flat(std::span<const Vec3<Real>> v) {
  return v.data()->data();
}

}  // namespace fastcorot::solver_vectors
