// A mechanical system of unconnected points with lumped masses: with factors (m = 1, 0, 0) its
// matrix is diag(masses) ⊗ I3, whose solves can be worked out by hand (the linear solver tests).
#pragma once

#include "fastcorot/sim/mechanical_system.h"

#include <utility>
#include <vector>

namespace fastcorot::testing {

inline MechanicalSystem<double> mass_system(std::vector<double> masses) {
  MechanicalSystem<double> system;
  system.state.position.assign(masses.size(), Vec3<double>::Zero());
  system.mass = Mass<double>::lumped(std::move(masses));
  system.finalize();
  return system;
}

}  // namespace fastcorot::testing
