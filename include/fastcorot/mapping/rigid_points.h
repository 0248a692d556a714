// RigidPoints<Real>: points that follow the rigid bodies of a MechanicalSystem through a
// RigidMapping, for what reads them after a step: visual models (OglModel under a RigidMapping)
// and mapped MechanicalObjects in dumps and in Python. y_i = c_k + rotate(q_k, p_i) and
// v_i = v_k + ω_k × r_i (r_i = rotate(q_k, p_i)), the rigid's position read from the system's
// Vec3 positions and orientations (state/rigid_blocks.h), as RigidMapping::apply and apply_j do.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/point_mapping.h"
#include "fastcorot/mapping/rigid_mapping.h"
#include "fastcorot/state/rigid_blocks.h"

#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
struct RigidPoints {
  std::shared_ptr<const RigidBlocks<Real>> frames;
  std::vector<Vec3<Real>> local;  // p_i, in the frame of rigid rigid[i]
  std::vector<Index> rigid;       // the rigid of each point (an index into frames)

  // The points of `mapping`, carried by the rigids of `frames`.
  static RigidPoints from(std::shared_ptr<const RigidBlocks<Real>> frames, const RigidMapping<Real>& mapping);

  // `outer` applied after these points (a chain rigid → points → outer's points): a rigid moves its
  // points affinely, so a point whose weights sum to 1 over points of one rigid is that rigid's
  // point at the weighted local coordinates. nullopt when a point mixes rigids or its weights do
  // not sum to 1 (to round-off).
  std::optional<RigidPoints> after(const PointMapping<Real>& outer) const;

  std::size_t size() const { return local.size(); }
  // Positions for the system's positions x (out: size() points).
  void positions(std::span<const Vec3<Real>> x, std::span<Vec3<Real>> out) const;
  // Velocities for the system's positions x and velocities v (out: size() points).
  void velocities(std::span<const Vec3<Real>> x, std::span<const Vec3<Real>> v, std::span<Vec3<Real>> out) const;
};

}  // namespace fastcorot
