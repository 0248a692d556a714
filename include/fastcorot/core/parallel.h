// Deterministic parallel loops. Work is cut into tasks whose boundaries depend on the problem size
// only, never on the thread count, and anything combined across tasks (sums, scatters into shared
// arrays) is combined in task order. So results are bitwise the same for 1 thread or many, and
// whichever thread runs a task.
// Threads are a team of workers per concurrent caller (src/core/parallel.cpp). A loop gives each
// thread a share of its tasks, and a thread that has finished its share takes the tasks of shares
// whose thread has not started or makes no progress (one the system has descheduled), so a busy
// core holds a loop up for at most the task its thread is running. Workers spin briefly between
// the short parallel loops of a time step, so that starting one costs well under a microsecond,
// then sleep. While other processes keep cores busy, loops use no more threads than the cores
// left free (set_yield_cores_to_other_processes).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace fastcorot {

// Whether parallel loops give up threads while other processes keep cores busy (the default):
// a loop then runs on no more threads than the cores left free (cores_left_by_other_processes in
// core/machine.h), down to its caller alone. Results are the same bits either way; off, loops
// always use the threads asked for (as when timing a fixed thread count on purpose).
void set_yield_cores_to_other_processes(bool yield);

namespace detail {
void run_tasks(int threads, int count, void (*call)(const void*, int), const void* context);
}  // namespace detail

// Calls task(i) for every i in [0, count), on up to `threads` threads; returns when all are done.
// Tasks that run concurrently must write disjoint memory. If a task throws, the tasks not yet
// started are skipped, those running end, and the first exception reaches the caller.
template <class Task>
void run_tasks(int threads, int count, const Task& task) {
  if (threads <= 1 || count <= 1) {
    for (int i = 0; i < count; ++i) task(i);
    return;
  }
  detail::run_tasks(
      threads, count, [](const void* context, int i) { (*static_cast<const Task*>(context))(i); }, &task);
}

// A fixed cut of [0, n) into at most kMaxChunks ranges of at least kMinChunk items.
struct Chunks {
  static constexpr std::size_t kMaxChunks = 64;
  static constexpr std::size_t kMinChunk = 1024;

  explicit Chunks(std::size_t n)
      : size(n), length(std::max(kMinChunk, (n + kMaxChunks - 1) / kMaxChunks)), count((n + length - 1) / length) {}

  std::size_t begin(std::size_t chunk) const { return chunk * length; }
  std::size_t end(std::size_t chunk) const { return std::min(size, (chunk + 1) * length); }

  std::size_t size;
  std::size_t length;
  std::size_t count;
};

// Calls body(begin, end) on the chunks of [0, n).
template <class Body>
void parallel_ranges(int threads, std::size_t n, const Body& body) {
  const Chunks chunks(n);
  run_tasks(threads, static_cast<int>(chunks.count), [&](int c) {
    body(chunks.begin(static_cast<std::size_t>(c)), chunks.end(static_cast<std::size_t>(c)));
  });
}

// Sum over the chunks of [0, n) of body(begin, end), added in chunk order: the same bits for any
// thread count.
template <class Real, class Body>
Real parallel_sum(int threads, std::size_t n, const Body& body) {
  const Chunks chunks(n);
  std::array<Real, Chunks::kMaxChunks> partial{};
  run_tasks(threads, static_cast<int>(chunks.count), [&](int c) {
    const auto i = static_cast<std::size_t>(c);
    partial[i] = body(chunks.begin(i), chunks.end(i));
  });
  Real sum = 0;
  for (std::size_t c = 0; c < chunks.count; ++c) sum += partial[c];
  return sum;
}

}  // namespace fastcorot
