// What the machine reports beside timings: the thread round trip is a time, and a budget too short
// for any round trip gives NaN rather than a made-up figure; a busy process beside us takes a core.
#include "fastcorot/core/machine.h"

#include "support/busy_core.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

namespace fastcorot {
namespace {

TEST(Machine, ThreadRoundTripIsAPositiveTime) {
  const double ns = thread_round_trip_ns(2000, std::chrono::seconds(5));
  ASSERT_TRUE(std::isfinite(ns));
  EXPECT_GT(ns, 0.0);
  // A finite figure means at least one timed batch of 256 round trips fitted in the budget (on a
  // loaded machine, under ThreadSanitizer, not all 2000 may), so each took less than 5 s / 256.
  EXPECT_LT(ns, 5e9 / 256);
}

TEST(Machine, NoTimeForAnyRoundTripIsNaN) {
  EXPECT_TRUE(std::isnan(thread_round_trip_ns(1000, std::chrono::nanoseconds(0))));
}

TEST(Machine, DefaultThreadsAreOnePer2000PointsAtMostEveryCore) {
  const int cores = machine_cores();
  EXPECT_EQ(default_thread_count(0), 1);
  EXPECT_EQ(default_thread_count(3999), 1);
  EXPECT_EQ(default_thread_count(4000), std::min(cores, 2));
  EXPECT_EQ(default_thread_count(1L << 40), cores);
}

TEST(Machine, ABusyProcessLeavesACoreLess) {
  const int cores = machine_cores();
  const testing::BusyCore busy;
  // Readings are taken at most every 2 ms and the least of three counts: poll for a while.
  int left = cores;
  const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (left >= cores && std::chrono::steady_clock::now() < limit) {
    left = cores_left_by_other_processes(1);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_LE(left, cores - 1);
  EXPECT_GE(left, 0);
}

}  // namespace
}  // namespace fastcorot
