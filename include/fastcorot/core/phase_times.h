// PhaseTimes: wall-clock seconds spent in each phase of time steps, for `fastcorot bench` and for
// profiling. Components add to the PhaseTimes they are given (none by default: no clock is read).
#pragma once

#include <chrono>

namespace fastcorot {

struct PhaseTimes {
  double add_force = 0;          // force-field forces and the stiffness refresh that follows them
  double matrix_vector = 0;      // products (m M + b B + k K) dx: add_dforce, mass, projection
  double solver_vectors = 0;     // the linear solver's own vector work (and direct factorisation)
  double mass_constraints = 0;   // gravity, constant forces, integration and constraint updates
  double output = 0;             // writing results

  double total() const { return add_force + matrix_vector + solver_vectors + mass_constraints + output; }
};

// Adds the time between construction and destruction to `*slot` (nothing when slot is null).
class PhaseTimer {
 public:
  explicit PhaseTimer(double* slot) : slot_(slot) {
    if (slot_) start_ = std::chrono::steady_clock::now();
  }
  ~PhaseTimer() {
    if (slot_) *slot_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  double* slot_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace fastcorot
