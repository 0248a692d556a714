// Deterministic parallel loops: the chunking depends on the size only, and parallel_sum adds the
// chunks' partial sums in chunk order, so the result has the same bits on any thread count.
#include "fastcorot/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

TEST(Chunks, CoverTheRangeInOrder) {
  for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(1023), std::size_t(5000), std::size_t(1000000)}) {
    const Chunks chunks(n);
    EXPECT_LE(chunks.count, Chunks::kMaxChunks);
    std::size_t next = 0;
    for (std::size_t c = 0; c < chunks.count; ++c) {
      EXPECT_EQ(chunks.begin(c), next);
      EXPECT_GT(chunks.end(c), chunks.begin(c));
      next = chunks.end(c);
    }
    EXPECT_EQ(next, n);
  }
}

TEST(ParallelSum, SameBitsOnAnyThreadCountAndChunkOrderSum) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::vector<double> values(300001);
  for (auto& v : values) v = u(rng) * std::exp(u(rng) / 100);  // wide range: order matters
  auto body = [&](std::size_t begin, std::size_t end) {
    double s = 0;
    for (std::size_t i = begin; i < end; ++i) s += values[i];
    return s;
  };
  const double one = parallel_sum<double>(1, values.size(), body);
  // The definition, sequentially: chunk sums added in chunk order.
  const Chunks chunks(values.size());
  double expected = 0;
  for (std::size_t c = 0; c < chunks.count; ++c) expected += body(chunks.begin(c), chunks.end(c));
  EXPECT_EQ(one, expected);
  for (int threads : {2, 3, 8}) EXPECT_EQ(parallel_sum<double>(threads, values.size(), body), one) << threads;
}

TEST(RunTasks, RunsEveryTaskOnce) {
  for (int threads : {1, 2, 5}) {
    std::vector<std::atomic<int>> runs(37);
    run_tasks(threads, 37, [&](int i) { runs[static_cast<std::size_t>(i)]++; });
    for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
  }
}

}  // namespace
}  // namespace fastcorot
