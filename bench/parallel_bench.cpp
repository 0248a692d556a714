// The cost of one parallel loop: fastcorot's teams (core/parallel.h) beside oneTBB's parallel_for
// on the same cuts, an empty loop over 12 tasks and a loop updating 12,000 values in chunks of
// 1,024 (a CG vector pass of a small beam). docs/performance.md ("Threads on a busy machine") has
// the figures; for the busy-core ones, start a shell loop beside it:
//   sh -c 'while :; do :; done' & build-release/bench/fastcorot_bench_parallel; kill %1
#include "fastcorot/core/parallel.h"

#include <benchmark/benchmark.h>

#include <vector>

#ifdef FASTCOROT_BENCH_TBB
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#endif

namespace {

constexpr int kTasks = 12;
constexpr std::size_t kValues = 12000;

void Teams_EmptyLoop(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<double> v(kTasks, 1.0);
  for (auto _ : state) fastcorot::run_tasks(threads, kTasks, [&](int t) { v[static_cast<std::size_t>(t)] += 1; });
  benchmark::DoNotOptimize(v.data());
}
BENCHMARK(Teams_EmptyLoop)->Arg(1)->Arg(2)->UseRealTime();

void Teams_UpdateLoop(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<double> v(kValues, 1.0);
  for (auto _ : state) {
    fastcorot::parallel_ranges(threads, v.size(), [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) v[k] = v[k] * 1.0000001 + 1e-9;
    });
  }
  benchmark::DoNotOptimize(v.data());
}
BENCHMARK(Teams_UpdateLoop)->Arg(1)->Arg(2)->UseRealTime();

#ifdef FASTCOROT_BENCH_TBB
void TBB_EmptyLoop(benchmark::State& state) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  std::vector<double> v(kTasks, 1.0);
  for (auto _ : state) {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, kTasks, 1),
        [&](const tbb::blocked_range<int>& r) {
          for (int t = r.begin(); t < r.end(); ++t) v[static_cast<std::size_t>(t)] += 1;
        },
        tbb::simple_partitioner());
  }
  benchmark::DoNotOptimize(v.data());
}
BENCHMARK(TBB_EmptyLoop)->Arg(2)->UseRealTime();

void TBB_UpdateLoop(benchmark::State& state) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  std::vector<double> v(kValues, 1.0);
  const fastcorot::Chunks chunks(kValues);
  for (auto _ : state) {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, v.size(), chunks.length),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t k = r.begin(); k < r.end(); ++k) v[k] = v[k] * 1.0000001 + 1e-9;
        },
        tbb::simple_partitioner());
  }
  benchmark::DoNotOptimize(v.data());
}
BENCHMARK(TBB_UpdateLoop)->Arg(2)->UseRealTime();
#endif

}  // namespace

BENCHMARK_MAIN();
