// What the machine reports beside timings: the thread round trip is a time, and a budget too short
// for any round trip gives NaN rather than a made-up figure.
#include "fastcorot/core/machine.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

namespace fastcorot {
namespace {

TEST(Machine, ThreadRoundTripIsAPositiveTime) {
  const double ns = thread_round_trip_ns(2000, std::chrono::seconds(5));
  ASSERT_TRUE(std::isfinite(ns));
  EXPECT_GT(ns, 0.0);
  // 2000 round trips took less than the budget, so each far less than 5 s / 2000.
  EXPECT_LT(ns, 5e9 / 2000);
}

TEST(Machine, NoTimeForAnyRoundTripIsNaN) {
  EXPECT_TRUE(std::isnan(thread_round_trip_ns(1000, std::chrono::nanoseconds(0))));
}

}  // namespace
}  // namespace fastcorot
