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

}  // namespace fastcorot
