#include "fastcorot/core/parallel.h"

#include <pthread.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace fastcorot::detail {
namespace {

using Call = void (*)(const void*, int);
using Clock = std::chrono::steady_clock;

// How long a waiting thread spins before it sleeps (workers) or yields (the caller): longer than
// the gaps between the parallel loops of a time step, short enough not to hold a core when the
// simulation pauses.
constexpr auto kSpin = std::chrono::microseconds(500);

// True on a team's workers, and on a caller while it runs its own share: a parallel loop inside a
// task runs on that task's thread, as nested OpenMP regions did.
thread_local bool inside_task = false;

// The threads of all teams, workers and a caller each: with more than the machine's cores, waiting
// threads yield instead of spinning, so that the ones with work get the cores.
std::atomic<int> threads_in_use{0};

bool crowded() {
  static const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return threads_in_use.load(std::memory_order_relaxed) > cores;
}

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Spins until done() or kSpin has passed; true if done() (checked once more at the end).
template <class Done>
bool spin_until(const Done& done) {
  const bool yield = crowded();
  const auto start = Clock::now();
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    if (yield) {
      std::this_thread::yield();
    } else {
      relax();
    }
    if (i % 64 == 0 && Clock::now() - start > kSpin) return done();
  }
}

// One caller's workers. A run publishes its task in the team and raises `signal` (run number and
// thread count in one word, so that a worker left out of a run never reads the task); thread k of
// t runs the tasks [k count / t, (k + 1) count / t), the caller being thread 0, like OpenMP's
// static schedule. Workers spin for kSpin after a run, then sleep until the next; they are never
// stopped (they end with the process).
class Team {
 public:
  Team() = default;
  Team(const Team&) = delete;
  Team& operator=(const Team&) = delete;

  void run(int threads, int count, Call call, const void* context) {
    while (static_cast<int>(workers_.size()) + 1 < threads) {
      const int index = static_cast<int>(workers_.size()) + 1;
      workers_.emplace_back([this, index, seen = signal_.load()] { work(index, seen); });
      threads_in_use.fetch_add(1, std::memory_order_relaxed);
    }
    call_ = call;
    context_ = context;
    count_ = count;
    failure_ = nullptr;
    remaining_.store(threads - 1, std::memory_order_relaxed);
    const std::uint64_t run_number = (signal_.load(std::memory_order_relaxed) >> kThreadBits) + 1;
    signal_.store(run_number << kThreadBits | static_cast<std::uint64_t>(threads));
    if (sleepers_.load() > 0) {
      { const std::lock_guard<std::mutex> lock(sleep_mutex_); }
      wake_.notify_all();
    }
    inside_task = true;
    share(0, threads);
    inside_task = false;
    if (!spin_until([this] { return remaining_.load(std::memory_order_acquire) == 0; })) {
      while (remaining_.load(std::memory_order_acquire) != 0) std::this_thread::yield();
    }
    // Tasks are not meant to throw; one that does (out of memory, say) ends the run's other tasks
    // normally and its exception reaches the caller, as in a serial loop.
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
  }

  static constexpr int kMaxThreads = (1 << 16) - 1;

 private:
  static constexpr int kThreadBits = 16;

  void share(int index, int threads) noexcept {
    const int begin = static_cast<int>(static_cast<long long>(count_) * index / threads);
    const int end = static_cast<int>(static_cast<long long>(count_) * (index + 1) / threads);
    try {
      for (int i = begin; i < end; ++i) call_(context_, i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex_);
      if (!failure_) failure_ = std::current_exception();
    }
  }

  void work(int index, std::uint64_t seen) {
    inside_task = true;
    for (;;) {
      const auto changed = [&] { return signal_.load() != seen; };
      if (!spin_until(changed)) {
        std::unique_lock<std::mutex> lock(sleep_mutex_);
        sleepers_.fetch_add(1);
        wake_.wait(lock, changed);
        sleepers_.fetch_sub(1);
      }
      seen = signal_.load(std::memory_order_acquire);
      const int threads = static_cast<int>(seen & ((std::uint64_t{1} << kThreadBits) - 1));
      if (index < threads) {
        share(index, threads);
        remaining_.fetch_sub(1, std::memory_order_release);
      }
    }
  }

  std::atomic<std::uint64_t> signal_{0};
  std::atomic<int> remaining_{0};
  std::atomic<int> sleepers_{0};
  std::mutex sleep_mutex_;
  std::condition_variable wake_;
  // The current run's task, written before signal_ is raised.
  Call call_ = nullptr;
  const void* context_ = nullptr;
  int count_ = 0;
  std::exception_ptr failure_;  // the first exception a task of the run threw
  std::mutex failure_mutex_;
  std::vector<std::thread> workers_;
};

// The teams, one per concurrent caller (objects of a Simulation step on threads of their own, each
// with its own team), created on demand and kept for the process.
class Teams {
 public:
  Team* acquire() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!idle_.empty()) {
      Team* team = idle_.back();
      idle_.pop_back();
      return team;
    }
    teams_.push_back(std::make_unique<Team>());
    threads_in_use.fetch_add(1, std::memory_order_relaxed);  // its caller
    return teams_.back().get();
  }

  void release(Team* team) {
    const std::lock_guard<std::mutex> lock(mutex_);
    idle_.push_back(team);
  }

  // Teams and their workers last as long as the process. A child forked from it has none of these
  // threads, so it starts with new teams (the parent's stay reachable, never used).
  static Teams& instance() {
    static const bool forks_start_afresh = [] {
      pthread_atfork(nullptr, nullptr, [] {
        Teams* fresh = new Teams;
        fresh->parent_ = current();
        current() = fresh;
      });
      current() = new Teams;
      return true;
    }();
    (void)forks_start_afresh;
    return *current();
  }

 private:
  static Teams*& current() {
    static Teams* teams = nullptr;
    return teams;
  }

  Teams* parent_ = nullptr;  // in a forked child: the parent's teams
  std::mutex mutex_;
  std::vector<std::unique_ptr<Team>> teams_;
  std::vector<Team*> idle_;
};

}  // namespace

void run_tasks(int threads, int count, void (*call)(const void*, int), const void* context) {
  threads = std::min({threads, count, Team::kMaxThreads});
  if (threads <= 1 || inside_task) {
    for (int i = 0; i < count; ++i) call(context, i);
    return;
  }
  Teams& teams = Teams::instance();
  struct Lease {
    Teams& teams;
    Team* team;
    ~Lease() { teams.release(team); }
  } lease{teams, teams.acquire()};
  lease.team->run(threads, count, call, context);
}

}  // namespace fastcorot::detail
