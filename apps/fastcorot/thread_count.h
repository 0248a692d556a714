// --threads of run, view and bench: 0, the default, means fastcorot's choice for the scene's size
// (default_thread_count in core/machine.h: one thread per 2,000 points, at most every core), or one
// per rank in a distributed run (its ranks share the cores). Parallel loops then use fewer while
// other processes keep cores busy (core/parallel.h), so the choice is the fastest on a free machine
// and on a loaded one alike (docs/performance.md, "Threads on a busy machine").
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/core/machine.h"

namespace fastcorot::cli {

// Throws for a --threads value that is neither a count nor 0 (checked before a scene loads).
inline void check_threads_option(int requested) {
  if (requested < 0) throw make_error("--threads ", requested, ": must be >= 1 (or 0: fastcorot's choice)");
}

inline int threads_to_run(int requested, bool distributed, long points) {
  check_threads_option(requested);
  if (requested > 0) return requested;
  return distributed ? 1 : default_thread_count(points);
}

// The points of every simulated object of a scene.
template <class Simulation>
long simulated_points(const Simulation& simulation) {
  long points = 0;
  for (const auto& object : simulation.objects) points += static_cast<long>(object.system.size());
  return points;
}

}  // namespace fastcorot::cli
