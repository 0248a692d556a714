#include "fastcorot/sim/linear_movement.h"

#include "fastcorot/state/rigid3.h"

namespace fastcorot {

template <class Real>
std::optional<std::pair<std::size_t, std::size_t>> LinearMovement<Real>::segment(double time) const {
  // SOFA compares in the state's Real.
  const Real t = static_cast<Real>(time);
  if (key_times.empty() || t < static_cast<Real>(key_times.front()) || t > static_cast<Real>(key_times.back())) return std::nullopt;
  std::size_t previous = 0;
  for (std::size_t k = 0; k < key_times.size(); ++k) {
    if (static_cast<Real>(key_times[k]) <= t) {
      previous = k;
    } else {
      if (static_cast<Real>(key_times[k]) == static_cast<Real>(key_times[previous])) return std::nullopt;
      return std::make_pair(previous, k);
    }
  }
  return std::nullopt;
}

template <class Real>
void LinearMovement<Real>::held(double time, std::vector<Index>& out) const {
  if (!segment(time)) return;
  for (Index p : points) {
    out.push_back(p);
    if (!rigids.empty()) out.push_back(p + 1);
  }
}

template <class Real>
void LinearMovement<Real>::apply(double time, MechanicalState<Real>& state, RigidBlocks<Real>* frames) {
  if (!started) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      start.push_back(state.position[static_cast<std::size_t>(points[i])]);
      if (!rigids.empty()) start_orientation.push_back(frames->orientation[static_cast<std::size_t>(rigids[i])]);
    }
    started = true;
  }
  const auto keys = segment(time);
  if (!keys) return;
  const auto [a, b] = *keys;
  const Real t_a = static_cast<Real>(key_times[a]), t_b = static_cast<Real>(key_times[b]);
  const Real alpha = (static_cast<Real>(time) - t_a) / (t_b - t_a);
  const Real rate = static_cast<Real>(1.0 / (t_b - t_a));
  const Vec3<Real> m = key_movements[a] + (key_movements[b] - key_movements[a]) * alpha;
  const Vec3<Real> velocity = (key_movements[b] - key_movements[a]) * rate;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto p = static_cast<std::size_t>(points[i]);
    state.position[p] = relative ? Vec3<Real>(start[i] + m) : m;
    state.velocity[p] = velocity;
  }
  if (rigids.empty()) return;
  const Eigen::Quaternion<Real> turn =
      slerp2(quaternion_from_euler(key_angles[a]), quaternion_from_euler(key_angles[b]), alpha);
  const Vec3<Real> angular_velocity = (key_angles[b] - key_angles[a]) * rate;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto p = static_cast<std::size_t>(points[i]);
    frames->orientation[static_cast<std::size_t>(rigids[i])] = relative ? quaternion_product(start_orientation[i], turn) : turn;
    state.position[p + 1].setZero();
    state.velocity[p + 1] = angular_velocity;
  }
  frames->rebase(state.position);
}

template struct LinearMovement<float>;
template struct LinearMovement<double>;

}  // namespace fastcorot
