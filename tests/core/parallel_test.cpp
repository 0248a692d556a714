// Deterministic parallel loops: the chunking depends on the size only, and parallel_sum adds the
// chunks' partial sums in chunk order, so the result has the same bits on any thread count.
#include "fastcorot/core/parallel.h"

#include "support/busy_core.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>
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

// The sum of 0..count-1, each task adding its index on whichever thread runs it.
long long sum_of_tasks(int threads, int count) {
  std::atomic<long long> sum{0};
  run_tasks(threads, count, [&](int i) { sum += i; });
  return sum.load();
}

long long expected_sum(int count) { return static_cast<long long>(count) * (count - 1) / 2; }

TEST(RunTasks, ThreadCountsChangingBetweenRuns) {
  // Workers left out of a run (fewer threads than last time) must not run its tasks, and must join
  // the next run that wants them.
  for (int round = 0; round < 200; ++round) {
    for (int threads : {2, 5, 3, 1, 4, 2}) {
      const int count = 1 + (round * 7 + threads) % 40;
      ASSERT_EQ(sum_of_tasks(threads, count), expected_sum(count)) << threads << " threads, " << count << " tasks";
    }
  }
}

TEST(RunTasks, WakesWorkersThatFellAsleep) {
  EXPECT_EQ(sum_of_tasks(3, 30), expected_sum(30));
  // Well past the time workers spin before they sleep.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(sum_of_tasks(3, 30), expected_sum(30));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(sum_of_tasks(2, 30), expected_sum(30));
}

TEST(RunTasks, NestedLoopsRunInsideTheirTask) {
  std::vector<long long> inner(8, 0);
  run_tasks(2, 8, [&](int i) {
    std::atomic<long long> sum{0};
    run_tasks(2, 100, [&](int j) { sum += j; });
    inner[static_cast<std::size_t>(i)] = sum.load();
  });
  for (long long s : inner) EXPECT_EQ(s, expected_sum(100));
}

TEST(RunTasks, ConcurrentCallersEachGetTheirOwnWorkers) {
  // As when a Simulation steps its objects on threads of their own.
  std::vector<std::thread> callers;
  std::atomic<int> failures{0};
  for (int c = 0; c < 4; ++c) {
    callers.emplace_back([&failures, c] {
      for (int round = 0; round < 300; ++round) {
        const int count = 1 + (round + c) % 25;
        if (sum_of_tasks(2 + c % 2, count) != expected_sum(count)) ++failures;
      }
    });
  }
  for (auto& caller : callers) caller.join();
  EXPECT_EQ(failures.load(), 0);
}

TEST(RunTasks, ATaskThatThrowsReachesTheCallerAfterTheOthersRan) {
  for (int thrower : {0, 9, 19}) {  // the caller's share, and the workers'
    std::vector<std::atomic<int>> runs(20);
    EXPECT_THROW(run_tasks(3, 20,
                           [&](int i) {
                             runs[static_cast<std::size_t>(i)]++;
                             if (i == thrower) throw std::runtime_error("task failed");
                           }),
                 std::runtime_error)
        << "task " << thrower;
    // Tasks not started when one failed are skipped; nothing ran twice.
    for (const auto& r : runs) EXPECT_LE(r.load(), 1);
    EXPECT_EQ(runs[static_cast<std::size_t>(thrower)].load(), 1);
  }
  EXPECT_EQ(sum_of_tasks(3, 20), expected_sum(20));  // the team still works
}

// Which thread runs the task before it must not matter: a task of a worker's share blocks (as if
// the system had descheduled its thread) until the rest of its share has run, which only another
// thread can do. With a fixed share per thread (a static schedule) it would wait out the timeout.
TEST(RunTasks, TasksOfAStalledThreadRunElsewhere) {
  set_yield_cores_to_other_processes(false);  // two threads even on a busy machine
  for (int round = 0; round < 20; ++round) {
    constexpr int kCount = 20;
    std::vector<std::atomic<int>> runs(kCount);
    std::atomic<int> rest_of_share{0};
    std::atomic<bool> timed_out{false};
    run_tasks(2, kCount, [&](int i) {
      runs[static_cast<std::size_t>(i)]++;
      if (i > kCount / 2) ++rest_of_share;
      if (i != kCount / 2) return;
      const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (rest_of_share.load() < kCount / 2 - 1) {
        if (std::chrono::steady_clock::now() > limit) {
          timed_out = true;
          return;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
    ASSERT_FALSE(timed_out.load()) << "round " << round;
    for (const auto& r : runs) ASSERT_EQ(r.load(), 1);
  }
  set_yield_cores_to_other_processes(true);
}

TEST(RunTasks, ManyTasksRunInSlices) {
  // More tasks than one run holds (32767): every task once, on any thread count.
  for (int threads : {1, 2, 3}) {
    std::vector<std::atomic<char>> runs(70001);
    run_tasks(threads, static_cast<int>(runs.size()), [&](int i) { runs[static_cast<std::size_t>(i)]++; });
    for (const auto& r : runs) ASSERT_EQ(r.load(), 1) << threads;
  }
}

TEST(RunTasks, SameBitsWithACoreBusy) {
  // The same sums whether the loop gives up threads to a busy process or keeps them all.
  std::vector<double> values(200001);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::sin(static_cast<double>(i)) * 1e3 / (1.0 + i % 7);
  auto body = [&](std::size_t begin, std::size_t end) {
    double s = 0;
    for (std::size_t i = begin; i < end; ++i) s += values[i] * values[i] - values[i];
    return s;
  };
  const double one = parallel_sum<double>(1, values.size(), body);
  const testing::BusyCore busy;
  for (bool yield : {true, false}) {
    set_yield_cores_to_other_processes(yield);
    for (int round = 0; round < 200; ++round) {
      for (int threads : {2, 3}) ASSERT_EQ(parallel_sum<double>(threads, values.size(), body), one) << threads;
    }
  }
  set_yield_cores_to_other_processes(true);
}

TEST(RunTasks, ForkedChildRunsItsOwnWorkers) {
  ASSERT_EQ(sum_of_tasks(2, 16), expected_sum(16));  // the parent's workers exist
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    alarm(20);  // a child whose workers never come ends here, and fails
    _exit(sum_of_tasks(2, 16) == expected_sum(16) && sum_of_tasks(3, 9) == expected_sum(9) ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(sum_of_tasks(2, 16), expected_sum(16));
}

}  // namespace
}  // namespace fastcorot
