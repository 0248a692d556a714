// RigidBlocks<Real>: where the Rigid3 degrees of freedom of a MechanicalSystem live in its Vec3
// vectors, and the orientations those vectors cannot hold. Rigid k occupies the two consecutive
// blocks block[k] (linear: centre, velocity v, force f) and block[k] + 1 (angular: rotation
// offset θ, angular velocity ω, torque τ), all in the world frame (state/rigid3.h).
//
// Positions: the solvers add to the angular block as to any other (x ← x + h v), so between steps
// it holds zero and during a step the rotation the step has added so far. The rigid's position is
// then the RigidCoord (x[block], q_k) displaced by θ as SOFA's `x += dx` displaces it:
// q = exp(θ/2) ⊗ q_k (state/rigid3.h, integrate). At the end of a step rebase() folds θ into q_k
// and sets it back to zero. A solver that adds to the positions once a step (implicit and explicit
// Euler) therefore turns the rigids exactly as SOFA's vector operation does, to the bit.
// Design: docs/mechanical-graph.md.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/state/rigid3.h"

#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace fastcorot {

template <class Real>
struct RigidBlocks {
  std::vector<Index> block;                              // the linear block of each rigid
  std::vector<Eigen::Quaternion<Real>> orientation;      // q_k, the orientation at the last rebase
  std::vector<Eigen::Quaternion<Real>> rest_orientation;  // from the state's rest_position
  // The rigid blocks of the objects merged into this one (sim/merged_objects.h), each with the
  // index of its first rigid here: rebase() copies their orientations to them, so that what was
  // built on an object's own blocks (force fields on its range of the state) reads them.
  std::vector<std::pair<std::shared_ptr<RigidBlocks>, std::size_t>> followers;

  std::size_t size() const { return block.size(); }

  // The position of rigid k for the Vec3 positions x.
  RigidCoord<Real> coord(std::span<const Vec3<Real>> x, std::size_t k) const;
  std::vector<RigidCoord<Real>> coords(std::span<const Vec3<Real>> x) const;
  // The rest position of rigid k for the Vec3 rest positions (angular blocks zero).
  RigidCoord<Real> rest_coord(std::span<const Vec3<Real>> rest, std::size_t k) const;

  // q_k ← exp(θ_k/2) ⊗ q_k and θ_k ← 0 for every rigid (the end of a step); then the followers'.
  void rebase(std::span<Vec3<Real>> x);

  // Throws fastcorot::Error when a block is outside a state of `points` blocks or the sizes differ.
  void check(Index points) const;
};

}  // namespace fastcorot
