// Vectors of Vec3 blocks for the mapping tests: seeded random ones (entries in [-1, 1], the same
// every run) and their dot product (for the dot-product test of Jᵀ against J).
#pragma once

#include "fastcorot/core/types.h"

#include <random>
#include <vector>

namespace fastcorot::testing {

inline std::vector<Vec3<double>> random_vectors(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3<double>> v(n);
  for (auto& p : v) p = Vec3<double>(u(rng), u(rng), u(rng));
  return v;
}

inline double dot(const std::vector<Vec3<double>>& a, const std::vector<Vec3<double>>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i].dot(b[i]);
  return s;
}

}  // namespace fastcorot::testing
