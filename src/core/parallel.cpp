#include "fastcorot/core/parallel.h"

#include "fastcorot/core/machine.h"

#include <pthread.h>

#include <array>
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

namespace fastcorot {
namespace {

using Call = void (*)(const void*, int);
using Clock = std::chrono::steady_clock;

// How long a worker spins for the next parallel loop before it sleeps: longer than the gaps
// between the loops of a time step, short enough not to hold a core when the simulation pauses.
constexpr auto kWorkerSpin = std::chrono::microseconds(500);
// How long the caller spins, at least, for tasks that other threads are running and that make no
// progress before it sleeps (wait_for_tasks): a task usually ends within microseconds; one that
// has not by then is on a thread the system has descheduled, which is better handed the caller's
// core.
constexpr auto kCallerSpin = std::chrono::microseconds(100);
// A worker spinning for the next loop that finds it was off its core this long (the clock jumped
// between two looks) shares its core with another runnable thread: it sleeps at once rather than
// spin on.
constexpr auto kDescheduled = std::chrono::microseconds(100);

// The threads of all teams, workers and callers: with more than the machine's cores, spinning
// threads yield rather than pause, so that the ones with work get the cores.
std::atomic<int> threads_in_use{0};

bool crowded() { return threads_in_use.load(std::memory_order_relaxed) > machine_cores(); }

// This process's threads that the system counts runnable, as far as the teams know them: callers
// inside a parallel loop and workers not asleep. On a cache line of its own: callers change it
// around every loop, and workers read the counts above between loops.
alignas(64) std::atomic<int> awake{0};

std::atomic<bool> yield_to_others{true};

// True on a team's workers, and on a caller while it runs tasks: a parallel loop inside a task
// runs on that task's thread, as nested OpenMP regions did.
thread_local bool inside_task = false;

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Spins until done() or `limit` has passed, or until the thread finds it was descheduled; true
// if done() (checked once more at the end).
template <class Done>
bool spin_until(const Done& done, Clock::duration limit) {
  const bool yield = crowded();
  const auto start = Clock::now();
  auto last = start;
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    if (yield) {
      std::this_thread::yield();
    } else {
      relax();
    }
    if (yield || i % 64 == 0) {  // the clock costs tens of nanoseconds on a VM; a yield, a time slice
      const auto now = Clock::now();
      if (now - start > limit || now - last > kDescheduled) return done();
      last = now;
    }
  }
}

// What a run publishes in one word: run number (32 bits), thread count (8), task count (16).
struct RunWord {
  static constexpr int kMaxThreads = 128;
  static constexpr int kMaxTasks = (1 << 15) - 1;  // a share's bounds take 15 bits (Share)

  std::uint32_t run = 0;
  int threads = 0;
  int count = 0;

  std::uint64_t pack() const {
    return std::uint64_t{run} << 32 | static_cast<std::uint64_t>(threads) << 16 | static_cast<std::uint64_t>(count);
  }
  static RunWord unpack(std::uint64_t word) {
    return {static_cast<std::uint32_t>(word >> 32), static_cast<int>(word >> 16 & 0xff), static_cast<int>(word & 0xffff)};
  }
  // Thread k's share of the tasks, as OpenMP's static schedule cuts them.
  int share_begin(int k) const { return static_cast<int>(static_cast<long long>(count) * k / threads); }
};

// What is left of one thread's share of a run, in one word, so that a thread takes a task with
// one compare-and-swap that also checks the run: run number (32 bits), whether the owner has
// started (1), next task (15), end (15). The owner takes tasks from the front, other threads from
// the back. Nobody resets the word for a new run: a word stamped with an earlier run stands for
// the whole share, untouched, and the first thread to take a task stamps it with the new run.
class Share {
 public:
  // A task of `run`'s share k not yet taken, or -1.
  int take_front(const RunWord& run, int k) { return take(run, k, true, false); }
  // The same from the back; with `unstarted_only`, only while the owner has taken none.
  int take_back(const RunWord& run, int k, bool unstarted_only) { return take(run, k, false, unstarted_only); }

  // Changes whenever a task is taken: how another thread sees that the owner is progressing.
  std::uint64_t progress() const { return word_.load(std::memory_order_relaxed); }
  // Whether a thread has taken a task of `run` from the share whose progress this is.
  static bool started(std::uint64_t progress, const RunWord& run) {
    return static_cast<std::uint32_t>(progress >> 32) == run.run;
  }

  // Stamps an untouched share with run `before`, so that it reads as untouched for the run after
  // it: for a share left out of runs for about 2^31 of them, whose stamp would read as later.
  void restamp(std::uint32_t before) { word_.store(std::uint64_t{before} << 32, std::memory_order_relaxed); }

 private:
  static constexpr std::uint64_t kStarted = std::uint64_t{1} << 31;
  static constexpr int kMask = RunWord::kMaxTasks;

  static std::uint64_t pack(std::uint32_t run, bool started, int next, int end) {
    return std::uint64_t{run} << 32 | (started ? kStarted : 0) | static_cast<std::uint64_t>(next) << 15 |
           static_cast<std::uint64_t>(end);
  }

  int take(const RunWord& run, int k, bool front, bool unstarted_only) {
    std::uint64_t word = word_.load(std::memory_order_acquire);
    for (;;) {
      const auto stamp = static_cast<std::uint32_t>(word >> 32);
      bool started = false;
      int next = 0;
      int end = 0;
      if (stamp == run.run) {
        started = (word & kStarted) != 0;
        next = static_cast<int>(word >> 15 & kMask);
        end = static_cast<int>(word & kMask);
      } else if (static_cast<std::int32_t>(run.run - stamp) > 0) {
        next = run.share_begin(k);
        end = run.share_begin(k + 1);
      } else {
        return -1;  // a later run's: ours has ended
      }
      if (next >= end || (unstarted_only && started)) return -1;
      const std::uint64_t taken = front ? pack(run.run, true, next + 1, end) : pack(run.run, started, next, end - 1);
      if (word_.compare_exchange_weak(word, taken, std::memory_order_acq_rel, std::memory_order_acquire)) {
        return front ? next : end - 1;
      }
    }
  }

  alignas(64) std::atomic<std::uint64_t> word_{0};
};

// One caller's workers. A run has one share of its tasks per thread (thread k of t starts on the
// tasks [k count / t, (k + 1) count / t), so that each thread keeps to the same part of the arrays
// from one loop to the next); the caller raises `signal_` with the run's number, thread and task
// counts. The caller, thread 0, runs its own share; a worker takes the tasks of its share one at a
// time, then those of other workers' shares whose owner has not started (from the back). The
// caller, done with its share, takes from the back of workers' shares not started or making no
// progress: a thread the system has descheduled holds up at most the task it is running. The
// caller returns when every task has ended. Workers spin for a while after a run, then sleep
// until the next; they are never stopped (they end with the process).
class Team {
 public:
  static constexpr int kMaxThreads = RunWord::kMaxThreads;

  Team() = default;
  Team(const Team&) = delete;
  Team& operator=(const Team&) = delete;

  void run(int threads, int count, Call call, const void* context) {
    while (static_cast<int>(workers_.size()) + 1 < threads) {
      const int index = static_cast<int>(workers_.size()) + 1;
      awake.fetch_add(1, std::memory_order_relaxed);
      threads_in_use.fetch_add(1, std::memory_order_relaxed);
      workers_.emplace_back([this, index, seen = signal_.load()] { work(index, seen); });
    }
    const RunWord run{RunWord::unpack(signal_.load(std::memory_order_relaxed)).run + 1, threads, count};
    for (int k = 1; k < threads; ++k) {  // the caller's share (0) has no word
      auto& last = last_run_of_share_[static_cast<std::size_t>(k)];
      if (run.run - last > (std::uint32_t{1} << 30)) shares_[static_cast<std::size_t>(k)].restamp(run.run - 1);
      last = run.run;
    }
    call_.store(call, std::memory_order_relaxed);
    context_.store(context, std::memory_order_relaxed);
    ended_.store(0, std::memory_order_relaxed);
    // seq_cst, as sleepers_: a worker going to sleep either sees the new signal or is counted.
    signal_.store(run.pack());
    if (sleepers_.load() > 0) {
      { const std::lock_guard<std::mutex> lock(sleep_mutex_); }
      wake_.notify_all();
    }
    inside_task = true;
    // The caller's share is its own: no other thread takes from it (the caller starts on it at
    // once), so it runs without claiming its tasks.
    const auto start = Clock::now();
    const int own = run.share_begin(1);
    for (int task = 0; task < own; ++task) execute(task);
    wait_for_tasks(count - own, run, start, own);
    inside_task = false;
    // Tasks are not meant to throw; one that does (out of memory, say) skips the tasks not yet
    // started and its exception reaches the caller, as in a serial loop.
    if (failed_.load(std::memory_order_relaxed)) {
      failed_.store(false, std::memory_order_relaxed);
      std::rethrow_exception(std::exchange(failure_, nullptr));
    }
  }

 private:
  // On worker `index`: runs the tasks left in its share of `run`, from the front, then those of
  // the other workers' shares whose owners have not started, from the back (not the caller's,
  // which the caller runs itself). Returns how many it ran.
  int take_tasks(int index, const RunWord& run) noexcept {
    int ran = 0;
    Share& own = shares_[static_cast<std::size_t>(index)];
    for (int task = own.take_front(run, index); task >= 0; task = own.take_front(run, index)) {
      execute(task);
      ++ran;
    }
    for (int k = 1; k < run.threads; ++k) {
      if (k == index) continue;
      Share& share = shares_[static_cast<std::size_t>(k)];
      for (int task = share.take_back(run, k, true); task >= 0; task = share.take_back(run, k, true)) {
        execute(task);
        ++ran;
      }
    }
    return ran;
  }

  void execute(int task) noexcept {
    // A task taken in this run keeps the run open until it has ended, so call_ and context_ are
    // this run's.
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      call_.load(std::memory_order_relaxed)(context_.load(std::memory_order_relaxed), task);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex_);
      if (!failure_) failure_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
    }
  }

  // The caller, once its own share is done (begun at `began`, `ran` tasks): returns when the
  // workers have ended `left` tasks (less those the caller runs here). It looks at the workers'
  // shares once per grace period (two of its own task times, and a little): a share not started,
  // or in which no task was taken since the last look, belongs to a thread that has not woken or
  // that the system has descheduled, and the caller runs what is left of it, from the back. When
  // no share has progressed for a while, the caller sleeps, so that a descheduled worker holding a
  // task can have its core. It looks no more often than that: a look takes the cache line a
  // worker writes, and costs the worker a miss.
  void wait_for_tasks(int left, const RunWord& run, Clock::time_point began, int ran) noexcept {
    const auto others_done = [&] { return ended_.load(std::memory_order_acquire) == left; };
    const bool yield = crowded();
    // The clock is read rarely (it costs tens of nanoseconds on a VM): here first after some
    // spinning, which the usual wait of a free machine does not outlast.
    unsigned i = 1;
    for (; i <= 64; ++i) {
      if (others_done()) return;
      relax();
    }
    const auto start = Clock::now();
    const Clock::duration per_task = (start - began) / std::max(ran, 1);
    const Clock::duration grace = 2 * per_task + std::chrono::microseconds(5);
    const Clock::duration patience = std::max<Clock::duration>(kCallerSpin, 4 * per_task);
    std::array<std::uint64_t, kMaxThreads> seen{};
    auto last_progress = start;
    auto last_look = start;
    for (; !others_done(); ++i) {
      if (yield) {
        std::this_thread::yield();
      } else {
        relax();
      }
      if (!yield && i % 64 != 0) continue;  // a yield may take a time slice: look after each
      auto now = Clock::now();
      if (now - last_look < grace) continue;
      const bool first_look = last_look == start;
      last_look = now;
      for (int k = 1; k < run.threads; ++k) {
        const auto s = static_cast<std::size_t>(k);
        Share& share = shares_[s];
        const std::uint64_t progress = share.progress();
        if (progress != seen[s] && !first_look && Share::started(progress, run)) {
          seen[s] = progress;
          last_progress = now;
          continue;
        }
        if (!first_look || !Share::started(progress, run)) {
          for (int task = share.take_back(run, k, false); task >= 0; task = share.take_back(run, k, false)) {
            execute(task);
            --left;
            last_progress = now = Clock::now();
          }
        }
        seen[s] = share.progress();
      }
      // Only after a second look: by then every share without progress has been emptied, and
      // what is left runs on the workers (a long first wait may be the caller's own time off its core).
      if (!first_look && now - last_progress > patience) break;
    }
    if (others_done()) return;
    awake.fetch_sub(1, std::memory_order_relaxed);
    caller_sleeping_.store(true, std::memory_order_seq_cst);
    for (int ended = ended_.load(std::memory_order_seq_cst); ended != left;
         ended = ended_.load(std::memory_order_seq_cst)) {
      ended_.wait(ended, std::memory_order_seq_cst);
    }
    caller_sleeping_.store(false, std::memory_order_relaxed);
    awake.fetch_add(1, std::memory_order_relaxed);
  }

  void work(int index, std::uint64_t seen) {
    inside_task = true;
    for (;;) {
      const auto changed = [&] { return signal_.load(std::memory_order_relaxed) != seen; };
      if (!spin_until(changed, kWorkerSpin)) {
        std::unique_lock<std::mutex> lock(sleep_mutex_);
        sleepers_.fetch_add(1);
        awake.fetch_sub(1, std::memory_order_relaxed);
        wake_.wait(lock, changed);
        awake.fetch_add(1, std::memory_order_relaxed);
        sleepers_.fetch_sub(1);
      }
      seen = signal_.load(std::memory_order_acquire);
      const RunWord run = RunWord::unpack(seen);
      if (index >= run.threads) continue;
      const int ran = take_tasks(index, run);
      if (ran == 0) continue;
      // One write to the shared counter per worker and run, not one per task.
      ended_.fetch_add(ran, std::memory_order_seq_cst);
      if (caller_sleeping_.load(std::memory_order_seq_cst)) ended_.notify_one();
    }
  }

  std::array<Share, kMaxThreads> shares_;
  // Written by the caller once a run, read by the workers: the run and its task.
  alignas(64) std::atomic<std::uint64_t> signal_{0};
  std::atomic<Call> call_{nullptr};
  std::atomic<const void*> context_{nullptr};
  std::atomic<bool> failed_{false};
  // Written by the workers, read by the caller.
  alignas(64) std::atomic<int> ended_{0};  // tasks of the run that workers have ended
  std::atomic<bool> caller_sleeping_{false};
  alignas(64) std::atomic<int> sleepers_{0};
  std::mutex sleep_mutex_;
  std::condition_variable wake_;
  std::exception_ptr failure_;  // the first exception a task of the run threw
  std::mutex failure_mutex_;
  std::vector<std::thread> workers_;
  std::array<std::uint32_t, kMaxThreads> last_run_of_share_{};  // the caller's: the last run each share took part in
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
        awake.store(0, std::memory_order_relaxed);
        threads_in_use.store(0, std::memory_order_relaxed);
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

// The threads a loop asked for `wanted` gets: all of them on a machine no other process keeps
// busy; otherwise no more than the cores left free, and at least the caller. A thread that must
// share its core with a busy process is descheduled for milliseconds at a time, and every loop it
// takes part in waits for it.
int threads_to_use(int wanted) {
  if (!yield_to_others.load(std::memory_order_relaxed)) return wanted;
  const int cores = machine_cores();
  const int left = cores_left_by_other_processes(awake.load(std::memory_order_relaxed) + 1);
  return left >= cores ? wanted : std::clamp(left, 1, wanted);
}

}  // namespace

void set_yield_cores_to_other_processes(bool yield) { yield_to_others.store(yield, std::memory_order_relaxed); }

namespace detail {

void run_tasks(int threads, int count, void (*call)(const void*, int), const void* context) {
  threads = std::min({threads, count, Team::kMaxThreads});
  if (threads > 1 && !inside_task) threads = threads_to_use(threads);
  if (threads <= 1 || inside_task) {
    for (int i = 0; i < count; ++i) call(context, i);
    return;
  }
  Teams& teams = Teams::instance();
  struct Lease {
    Teams& teams;
    Team* team;
    ~Lease() {
      awake.fetch_sub(1, std::memory_order_relaxed);
      teams.release(team);
    }
  } lease{teams, teams.acquire()};
  awake.fetch_add(1, std::memory_order_relaxed);
  // A run holds at most RunWord::kMaxTasks tasks; more run as several runs, one after the other.
  if (count <= RunWord::kMaxTasks) {
    lease.team->run(threads, count, call, context);
    return;
  }
  struct Slice {
    Call call;
    const void* context;
    int first;
  };
  for (int first = 0; first < count; first += RunWord::kMaxTasks) {
    const Slice slice{call, context, first};
    const int size = std::min(count - first, RunWord::kMaxTasks);
    lease.team->run(
        std::min(threads, size), size,
        [](const void* c, int i) {
          const auto* s = static_cast<const Slice*>(c);
          s->call(s->context, s->first + i);
        },
        &slice);
  }
}

}  // namespace detail
}  // namespace fastcorot
