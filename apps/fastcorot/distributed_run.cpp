#include "distributed_run.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/petsc_runtime.h"

namespace fastcorot::cli {

DistributedRun::DistributedRun(Simulation<double>& simulation) {
  if (process_count() == 1) return;
  if (simulation.constraints) {
    throw make_error("a FreeMotionAnimationLoop scene runs in one process: its constraints couple whole objects "
                     "(run it without mpirun)");
  }
  if (simulation.collisions) {
    throw make_error("a scene with collision detection runs in one process: its contacts join points across the "
                     "object (run it without mpirun)");
  }
  fingerprints_ = scene_fingerprints(simulation);
  for (auto& object : simulation.objects) distributions_.push_back(distribute(object));
}

void DistributedRun::gather_state(Simulation<double>& simulation) const {
  for (std::size_t o = 0; o < distributions_.size(); ++o) {
    auto& state = simulation.objects[o].system.state;
    // Rank 0 reads its own points before it writes every point: the same array serves both.
    distributions_[o]->gather(state.position, state.position);
    distributions_[o]->gather(state.velocity, state.velocity);
  }
}

std::vector<std::vector<Vec3<double>>> DistributedRun::gather_forces(Simulation<double>& simulation) const {
  std::vector<std::vector<Vec3<double>>> forces;
  for (std::size_t o = 0; o < distributions_.size(); ++o) {
    auto& system = simulation.objects[o].system;
    std::vector<Vec3<double>> force(static_cast<std::size_t>(system.size()), Vec3<double>::Zero());
    system.compute_force(system.state.position, force);
    distributions_[o]->gather(force, force);
    forces.push_back(std::move(force));
  }
  return forces;
}

std::size_t DistributedRun::bytes_sent_per_exchange() const {
  std::size_t bytes = 0;
  for (const auto& distribution : distributions_) bytes += distribution->bytes_sent_per_exchange();
  return bytes;
}

}  // namespace fastcorot::cli
