// --threads of run, view and bench: 0, the default, means every core of the machine, or one per
// rank in a distributed run (its ranks share the cores). Parallel loops then use fewer while other
// processes keep cores busy (core/parallel.h), so all cores are the fastest choice on a free
// machine and on a loaded one alike (docs/performance.md, "Threads on a busy machine").
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/core/machine.h"

namespace fastcorot::cli {

inline int threads_to_run(int requested, bool distributed = false) {
  if (requested < 0) throw make_error("--threads ", requested, ": must be >= 1 (or 0: every core)");
  if (requested > 0) return requested;
  return distributed ? 1 : machine_cores();
}

}  // namespace fastcorot::cli
