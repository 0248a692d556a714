// What the library was built for and what the machine running it offers, stated beside timings so
// that figures from different machines (or builds) can be compared: the kernels' speed depends
// above all on the width of the vector instructions they were compiled for (-march=native).
#pragma once

#include <chrono>
#include <string>

namespace fastcorot {

// The widest vector instruction set the library was compiled for: "AVX-512", "AVX2", "SSE2", or
// "none" (another architecture, or a build without any).
const char* build_vector_instructions();

// The widest of the same sets this CPU supports ("none" off x86).
const char* cpu_vector_instructions();

// The CPU's model name as the system gives it (Linux: /proc/cpuinfo), or "" where it does not.
std::string cpu_model();

// How long a value written by one thread takes to reach a second thread and come back, in
// nanoseconds: the mean over up to `rounds` round trips of one cache line between two new threads
// (placed by the system, as a parallel loop's are), stopped after `budget`; NaN if not one batch
// of 256 round trips (after 64 untimed ones) fitted in it. Parallel loops start and end with such
// a handshake, so this bounds how short a loop can pay off, and it depends on where the system
// puts the threads: on the 2-core VM of 2026-12-02 it was about 100 ns in some spells and 500 ns in others (two cores sharing a cache
// or not, most likely), and two-thread steps of the 40×10×10 beam ran at medians of 824 and 615
// steps/s accordingly (README, "Performance"). On a busy machine, where the two threads may share
// a core, it is tens of microseconds.
double thread_round_trip_ns(int rounds, std::chrono::nanoseconds budget);

// The machine's cores (online processors).
int machine_cores();

// The thread count fastcorot chooses for a simulation of `points` points when none is asked for:
// one thread per 2,000 points, at least one, at most every core. A parallel loop costs about a
// microsecond of hand-over between two threads on the 2-core VM, which smaller scenes do not win
// back (docs/performance.md, "Threads on a busy machine": 1,920 points ran faster on one thread,
// 4,000 on two).
int default_thread_count(long points);

// How many of the machine's cores other processes leave free just now: the cores less the threads
// the kernel has runnable (Linux: /proc/loadavg's fourth field, every runnable thread of every
// process, this one's included) less `own_runnable` of them that are this process's. A
// CPU-bound process beside us shows in every reading, a passing one in few: the figure uses the
// least count of others of the last three readings, taken at most every 2 ms (calls in between
// answer the last figure, cheaply). All cores where the count cannot be read. Safe to call from
// any thread.
int cores_left_by_other_processes(int own_runnable);

}  // namespace fastcorot
