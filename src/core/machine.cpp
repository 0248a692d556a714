#include "fastcorot/core/machine.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <fstream>
#include <limits>
#include <system_error>
#include <thread>

namespace fastcorot {

const char* build_vector_instructions() {
#if defined(__AVX512F__)
  return "AVX-512";
#elif defined(__AVX2__)
  return "AVX2";
#elif defined(__SSE2__)
  return "SSE2";
#else
  return "none";
#endif
}

const char* cpu_vector_instructions() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return "AVX-512";
  if (__builtin_cpu_supports("avx2")) return "AVX2";
  if (__builtin_cpu_supports("sse2")) return "SSE2";
#endif
  return "none";
}

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  const std::string key = "model name";
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.compare(0, key.size(), key) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const auto start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? std::string() : line.substr(start);
  }
  return {};
}

double thread_round_trip_ns(int rounds, std::chrono::nanoseconds budget) {
  using Clock = std::chrono::steady_clock;
  // The initiator writes odd values, the partner answers each with the next even one.
  struct alignas(64) Line {
    std::atomic<long> value{0};
  };
  Line line;
  alignas(64) std::atomic<bool> stop{false};
  constexpr unsigned kPollsBeforeYield = 1u << 16;
  std::thread partner;
  try {
    partner = std::thread([&] {
      for (unsigned idle = 1; !stop.load(std::memory_order_relaxed); ++idle) {
        const long v = line.value.load(std::memory_order_acquire);
        if (v % 2 == 1) {
          line.value.store(v + 1, std::memory_order_release);
          idle = 0;
        } else if (idle % kPollsBeforeYield == 0) {
          std::this_thread::yield();  // (a core shared with the initiator: let it run)
        }
      }
    });
  } catch (const std::system_error&) {
    return std::numeric_limits<double>::quiet_NaN();  // no second thread to be had
  }
  const Clock::time_point deadline = Clock::now() + budget;
  // Waits for the partner's answer to round r; false once the budget is spent. The clock is read
  // every 1024 polls and between batches only, so that reading it does not add to the round trip.
  // Both threads yield after kPollsBeforeYield polls in vain (tens of microseconds, far beyond a
  // round trip between two cores): on a busy machine, where they may share a core, a round then
  // costs that and a switch between them rather than a whole time slice.
  const auto round_trip = [&](long r) {
    line.value.store(2 * r + 1, std::memory_order_release);
    for (unsigned polls = 1;; ++polls) {
      if (line.value.load(std::memory_order_acquire) == 2 * r + 2) return true;
      if (polls % 1024 == 0 && Clock::now() > deadline) return false;
      if (polls % kPollsBeforeYield == 0) std::this_thread::yield();
    }
  };
  // A few untimed rounds first (the partner has to start and the line to settle), then batches of
  // timed ones; a batch the budget cut short does not count.
  constexpr long kWarmup = 64, kBatch = 256;
  bool in_time = true;
  for (long w = 0; w < kWarmup && in_time; ++w) in_time = round_trip(w);
  long done = 0, next = kWarmup;
  double seconds = 0;
  while (in_time && done < rounds) {
    const long batch = std::min<long>(kBatch, rounds - done);
    const Clock::time_point start = Clock::now();
    if (start > deadline) break;
    for (long i = 0; i < batch && in_time; ++i) in_time = round_trip(next++);
    if (!in_time) break;
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    done += batch;
  }
  stop.store(true, std::memory_order_relaxed);
  partner.join();
  return done > 0 ? 1e9 * seconds / static_cast<double>(done) : std::numeric_limits<double>::quiet_NaN();
}

int machine_cores() {
  static const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return cores;
}

int default_thread_count(long points) {
  constexpr long kPointsPerThread = 2000;
  return static_cast<int>(std::clamp<long>(points / kPointsPerThread, 1, machine_cores()));
}

namespace {

// The kernel's count of runnable threads, or -1. The file stays open: each read at offset 0
// renders it afresh, a few microseconds.
int runnable_threads() {
  static const int file = ::open("/proc/loadavg", O_RDONLY | O_CLOEXEC);
  if (file < 0) return -1;
  std::array<char, 128> text{};
  const ssize_t length = ::pread(file, text.data(), text.size() - 1, 0);
  if (length <= 0) return -1;
  // "0.68 1.23 0.75 3/87 6094": the runnable count is the number before the slash.
  const char* slash = static_cast<const char*>(std::memchr(text.data(), '/', static_cast<std::size_t>(length)));
  if (slash == nullptr) return -1;
  const char* start = slash;
  while (start > text.data() && start[-1] >= '0' && start[-1] <= '9') --start;
  if (start == slash) return -1;
  return std::atoi(start);
}

}  // namespace

int cores_left_by_other_processes(int own_runnable) {
  using Clock = std::chrono::steady_clock;
  constexpr auto kPeriod = std::chrono::milliseconds(2);
  static std::atomic<int> answer{machine_cores()};
  static std::atomic<Clock::rep> last_reading{0};
  static std::mutex reading;
  static std::array<int, 3> others{};  // the last readings' counts of other runnable threads
  static std::size_t next = 0;
  // The clock is looked at on one call in 16 of each thread (a parallel loop asks every few
  // microseconds, and a look at the clock costs tens of nanoseconds on a VM).
  thread_local unsigned calls = 0;
  if (++calls % 16 != 1) return answer.load(std::memory_order_relaxed);
  const Clock::rep now = Clock::now().time_since_epoch().count();
  if (now - last_reading.load(std::memory_order_relaxed) < std::chrono::duration_cast<Clock::duration>(kPeriod).count()) {
    return answer.load(std::memory_order_relaxed);
  }
  const std::unique_lock<std::mutex> lock(reading, std::try_to_lock);
  if (!lock.owns_lock()) return answer.load(std::memory_order_relaxed);  // another thread reads it
  last_reading.store(now, std::memory_order_relaxed);
  const int runnable = runnable_threads();
  if (runnable < 0) return machine_cores();
  others[next] = std::max(0, runnable - own_runnable);
  next = (next + 1) % others.size();
  const int fewest = *std::min_element(others.begin(), others.end());
  answer.store(std::max(0, machine_cores() - fewest), std::memory_order_relaxed);
  return answer.load(std::memory_order_relaxed);
}

}  // namespace fastcorot
