// A random right-hand side for the linear-solver tests: entries in [-1, 1] (seeded, so the same
// every run), projected as the ODE solvers project theirs (fixed points zero).
#pragma once

#include "fastcorot/sim/mechanical_system.h"
#include "support/deformations.h"

#include <random>
#include <vector>

namespace fastcorot::testing {

inline std::vector<Vec3<double>> projected_rhs(const MechanicalSystem<double>& system, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Vec3<double>> b =
      perturbed(std::vector<Vec3<double>>(static_cast<std::size_t>(system.size()), Vec3<double>::Zero()), 1.0, rng);
  system.project(b);
  return b;
}

}  // namespace fastcorot::testing
