// The period of an oscillation a scene makes, measured from its upward zero crossings (for tests
// against small-amplitude closed forms: pendulums, torsion springs).
#pragma once

#include "fastcorot/scene/scene_builder.h"

#include <functional>
#include <vector>

namespace fastcorot::testing {

// Steps `scene` `steps` times (time step dt) and returns the times at which `angle()` crosses zero
// upwards, each interpolated linearly within its step.
inline std::vector<double> upward_crossings(LoadedScene& scene, int steps, double dt, const std::function<double()>& angle) {
  std::vector<double> crossings;
  double previous = angle();
  for (int s = 1; s <= steps; ++s) {
    scene.simulation.step();
    const double now = angle();
    if (previous < 0 && now >= 0) crossings.push_back((s - 1 + previous / (previous - now)) * dt);
    previous = now;
  }
  return crossings;
}

// The mean period between the first and last of `crossings` (needs at least two).
inline double mean_period(const std::vector<double>& crossings) {
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

}  // namespace fastcorot::testing
