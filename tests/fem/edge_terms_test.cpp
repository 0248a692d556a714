// add_dforce's edge loops (src/fem/force_kernels.h): one edge at a time (add_edge_terms) and two
// at a time (add_edge_terms_in_pairs, the one builds with AVX-512 use), both against the plain
// formula out[v] += K w, out[u] -= K^T w with w = in[v] - in[u], on slots sorted by lower vertex
// into runs of every length, and on runs split apart as topological changes leave them. Both
// kernels are tested whichever one this build's force field uses.
#include "fem/force_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

template <class Real>
struct EdgeCase {
  std::vector<std::array<int, 2>> vertices;  // per slot (u, v), u < v
  std::vector<Real> blocks;                  // nine per slot, column-major, then the tail
  std::vector<Real> in;                      // four per point, the fourth 0
  std::vector<Real> out;                     // four per point
};

template <class Real>
EdgeCase<Real> make_case(unsigned seed, bool split_runs) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  const int points = 300;
  EdgeCase<Real> c;
  for (int u = 0; u + 1 < points; ++u) {
    const int length = static_cast<int>(rng() % 9);  // runs of 0..8 edges
    for (int k = 0; k < length; ++k) {
      const int v = u + 1 + static_cast<int>(rng() % static_cast<unsigned>(points - 1 - u));
      c.vertices.push_back({u, v});
    }
  }
  if (split_runs) {
    // Edges placed later into free slots: lower vertices seen before, runs of one or two.
    for (int k = 0; k < 40; ++k) {
      const int u = static_cast<int>(rng() % (points - 1));
      c.vertices.push_back({u, u + 1 + static_cast<int>(rng() % static_cast<unsigned>(points - 1 - u))});
      if (k % 3 == 0) c.vertices.push_back({u, points - 1});
      if (k % 5 == 0) c.vertices.push_back({(u + 7) % (points - 1), points - 1});
    }
  }
  for (std::size_t i = 0; i < 9 * c.vertices.size(); ++i) c.blocks.push_back(static_cast<Real>(value(rng)));
  c.blocks.resize(c.blocks.size() + kernels::kBlockTail, Real(0));
  for (int i = 0; i < points; ++i) {
    for (int j = 0; j < 4; ++j) c.in.push_back(j < 3 ? static_cast<Real>(value(rng)) : Real(0));
    for (int j = 0; j < 4; ++j) c.out.push_back(j < 3 ? static_cast<Real>(value(rng)) : Real(0));
  }
  return c;
}

// The plain formula, in double.
template <class Real>
std::vector<double> plain(const EdgeCase<Real>& c) {
  std::vector<double> out(c.out.begin(), c.out.end());
  for (std::size_t slot = 0; slot < c.vertices.size(); ++slot) {
    const auto u = static_cast<std::size_t>(c.vertices[slot][0]);
    const auto v = static_cast<std::size_t>(c.vertices[slot][1]);
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = 0; j < 3; ++j) {
        const double k_ij = c.blocks[9 * slot + 3 * j + i];
        out[4 * v + i] += k_ij * (static_cast<double>(c.in[4 * v + j]) - c.in[4 * u + j]);
        out[4 * u + j] -= k_ij * (static_cast<double>(c.in[4 * v + i]) - c.in[4 * u + i]);
      }
    }
  }
  return out;
}

// Over the three coordinates of every point (the loops leave anything in the spare fourth value).
template <class Real>
double largest_difference(const std::vector<Real>& got, const std::vector<double>& expected) {
  double largest = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (i % 4 != 3) largest = std::max(largest, std::abs(got[i] - expected[i]));
  }
  return largest;
}

template <class Real>
void both_kernels_match_the_formula(double tolerance) {
  for (bool split_runs : {false, true}) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
      SCOPED_TRACE(testing::Message() << "seed " << seed << (split_runs ? ", runs split" : ""));
      const EdgeCase<Real> c = make_case<Real>(seed, split_runs);
      // Slot ranges that start and end anywhere, as schedule groups do.
      const std::size_t n = c.vertices.size();
      for (const auto& [begin, end] : std::vector<std::array<std::size_t, 2>>{{0, n}, {0, n / 2}, {n / 2, n}}) {
        std::vector<Real> one = c.out, two = c.out;
        EdgeCase<Real> part = c;
        part.vertices.assign(c.vertices.begin() + static_cast<std::ptrdiff_t>(begin),
                             c.vertices.begin() + static_cast<std::ptrdiff_t>(end));
        part.blocks.assign(c.blocks.begin() + static_cast<std::ptrdiff_t>(9 * begin), c.blocks.end());
        const std::vector<double> expected_range = plain(part);
        kernels::add_edge_terms(c.in.data(), one.data(), c.blocks.data(), c.vertices.data(), begin, end);
        kernels::add_edge_terms_in_pairs(c.in.data(), two.data(), c.blocks.data(), c.vertices.data(), begin, end);
        EXPECT_LT(largest_difference(one, expected_range), tolerance) << "one at a time, slots " << begin << ".." << end;
        EXPECT_LT(largest_difference(two, expected_range), tolerance) << "in pairs, slots " << begin << ".." << end;
      }
    }
  }
}

TEST(EdgeTerms, BothLoopsMatchThePlainFormulaDouble) { both_kernels_match_the_formula<double>(1e-12); }

TEST(EdgeTerms, BothLoopsMatchThePlainFormulaFloat) { both_kernels_match_the_formula<float>(2e-5); }

}  // namespace
}  // namespace fastcorot
