// `fastcorot run` on several MPI ranks (mpirun -np N fastcorot run scene.scn, docs/scaling.md):
// every object is shared out over the ranks (sim/distribution.h), every rank steps its part, and
// rank 0 gathers the state it writes (frames, --dump-state, checkpoints, the summary).
#pragma once

#include "fastcorot/io/checkpoint.h"
#include "fastcorot/sim/distribution.h"
#include "fastcorot/sim/simulation.h"

#include <memory>
#include <vector>

namespace fastcorot::cli {

class DistributedRun {
 public:
  // Distributes every object of `simulation` when this run has more than one rank (collective);
  // does nothing with one. Throws fastcorot::Error naming the object that cannot be distributed.
  explicit DistributedRun(Simulation<double>& simulation);

  bool active() const { return !distributions_.empty(); }
  // The objects' checkpoint fingerprints as the scene was built, before it was shared out (what
  // checkpoints record and check); null when the run is not distributed.
  const std::vector<ObjectFingerprint>* fingerprints() const { return active() ? &fingerprints_ : nullptr; }
  // Every object's positions and velocities, complete, into rank 0's state (collective).
  void gather_state(Simulation<double>& simulation) const;
  // Every object's forces at its positions, complete on rank 0 (collective).
  std::vector<std::vector<Vec3<double>>> gather_forces(Simulation<double>& simulation) const;
  // What this rank sends per exchange of shared points, summed over the objects.
  std::size_t bytes_sent_per_exchange() const;

 private:
  std::vector<std::shared_ptr<Distribution>> distributions_;
  std::vector<ObjectFingerprint> fingerprints_;
};

}  // namespace fastcorot::cli
