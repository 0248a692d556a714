#include "fastcorot/mapping/rigid_points.h"

#include <cmath>
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
std::optional<RigidPoints<Real>> RigidPoints<Real>::after(const PointMapping<Real>& outer) const {
  RigidPoints result;
  result.frames = frames;
  for (std::size_t i = 0; i < outer.size(); ++i) {
    Vec3<Real> p = Vec3<Real>::Zero();
    Real sum = 0;
    Index body = -1;
    for (std::size_t k = 0; k < static_cast<std::size_t>(PointMapping<Real>::kSlots); ++k) {
      const Real w = outer.weights[i][k];
      if (w == 0) continue;
      const auto v = static_cast<std::size_t>(outer.vertices[i][k]);
      if (v >= size() || (body >= 0 && rigid[v] != body)) return std::nullopt;
      body = rigid[v];
      p += w * local[v];
      sum += w;
    }
    if (body < 0 || std::abs(sum - 1) > Real(1e-6)) return std::nullopt;
    result.local.push_back(p);
    result.rigid.push_back(body);
  }
  return result;
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
