// PatternedAssembly: Eigen's setFromTriplets with the pattern kept between calls. The reference is
// setFromTriplets itself on the same triplets, compared bit for bit.
#include "fastcorot/fem/matrix_sink.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

Eigen::SparseMatrix<double> reference(const Triplets& triplets, Index size) {
  Eigen::SparseMatrix<double> m(size, size);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

void expect_bitwise_equal(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  for (Index c = 0; c <= a.cols(); ++c) ASSERT_EQ(a.outerIndexPtr()[c], b.outerIndexPtr()[c]);
  for (Index k = 0; k < a.nonZeros(); ++k) {
    ASSERT_EQ(a.innerIndexPtr()[k], b.innerIndexPtr()[k]);
    // Bits, so that -0.0 and the order of the sums count.
    EXPECT_EQ(std::memcmp(a.valuePtr() + k, b.valuePtr() + k, sizeof(double)), 0) << "entry " << k;
  }
}

// Triplets on a fixed random pattern with many duplicates (each (row, column) drawn from a few);
// values drawn anew each call, spanning magnitudes so that the order of the sums shows.
struct RandomAssembly {
  std::mt19937 random{7};
  std::vector<std::pair<Index, Index>> pattern;
  Triplets draw() {
    std::uniform_real_distribution<double> mantissa(-1, 1);
    std::uniform_int_distribution<int> exponent(-30, 30);
    Triplets t;
    for (const auto& [r, c] : pattern) t.emplace_back(r, c, std::ldexp(mantissa(random), exponent(random)));
    return t;
  }
};

TEST(PatternedAssembly, EqualsSetFromTripletsBitwiseStepAfterStep) {
  RandomAssembly assembly;
  std::uniform_int_distribution<int> index(0, 11);
  for (int k = 0; k < 400; ++k) assembly.pattern.emplace_back(index(assembly.random), index(assembly.random));
  PatternedAssembly<double> patterned;
  for (int step = 0; step < 5; ++step) {
    Triplets t = assembly.draw();
    expect_bitwise_equal(patterned.to_sparse(t, 12), reference(t, 12));
  }
}

TEST(PatternedAssembly, ANewPatternOrSizeIsLearntAgain) {
  RandomAssembly assembly;
  assembly.pattern = {{0, 0}, {1, 0}, {0, 0}, {2, 2}, {1, 0}};
  PatternedAssembly<double> patterned;
  Triplets t = assembly.draw();
  expect_bitwise_equal(patterned.to_sparse(t, 3), reference(t, 3));
  t = assembly.draw();
  t[3] = Eigen::Triplet<double>(2, 2, -0.0);  // the only value at (2, 2): a signed zero kept
  expect_bitwise_equal(patterned.to_sparse(t, 3), reference(t, 3));
  // One entry moved: the same count, another pattern.
  assembly.pattern[3] = {2, 1};
  t = assembly.draw();
  expect_bitwise_equal(patterned.to_sparse(t, 3), reference(t, 3));
  // Fewer triplets, then a larger matrix with the same triplets.
  assembly.pattern.pop_back();
  t = assembly.draw();
  expect_bitwise_equal(patterned.to_sparse(t, 3), reference(t, 3));
  expect_bitwise_equal(patterned.to_sparse(t, 6), reference(t, 6));
}

}  // namespace
}  // namespace fastcorot
