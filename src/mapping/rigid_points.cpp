#include "fastcorot/mapping/rigid_points.h"

#include <utility>

namespace fastcorot {

template <class Real>
RigidPoints<Real> RigidPoints<Real>::from(std::shared_ptr<const RigidBlocks<Real>> frames,
                                          const RigidMapping<Real>& mapping) {
  RigidPoints points;
  points.frames = std::move(frames);
  points.local.assign(mapping.local_points().begin(), mapping.local_points().end());
  points.rigid.assign(mapping.rigid_of_point().begin(), mapping.rigid_of_point().end());
  return points;
}

template <class Real>
void RigidPoints<Real>::positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> out) const {
  const std::vector<RigidCoord<Real>> coords = frames->coords(x);
  for (std::size_t i = 0; i < size(); ++i) out[i] = coords[static_cast<std::size_t>(rigid[i])].project_point(local[i]);
}

template <class Real>
void RigidPoints<Real>::velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v,
                                   std::span<Vec3<Real>> out) const {
  const std::vector<RigidCoord<Real>> coords = frames->coords(x);
  for (std::size_t i = 0; i < size(); ++i) {
    const auto k = static_cast<std::size_t>(rigid[i]);
    const auto b = static_cast<std::size_t>(frames->block[k]);
    out[i] = v[b] + v[b + 1].cross(coords[k].rotate(local[i]));
  }
}

template struct RigidPoints<float>;
template struct RigidPoints<double>;

}  // namespace fastcorot
