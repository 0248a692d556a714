// RigidMappedMass<Real>: the mass of a system of rigid bodies that carry masses on mapped points (a
// UniformMass or DiagonalMass in a node under a RigidMapping), as SOFA's mechanical visitors make it
// act: the mapped points' inertia enters every product through J (M dx ← M_own dx + Jᵀ M_points J dx)
// and their weights come up through Jᵀ. With J_i = [I₃ | -[r_i]×] (r_i the rotated offset of point
// i from its rigid's centre) a point of mass m adds to its rigid's blocks
//   linear–linear m I₃,  linear–angular -m [r]×,  angular–angular m (|r|² I₃ - r rᵀ),
// and its weight m g adds the force m g and the torque r × m g (gravity blocks m I₃ and m [r]×).
// J turns with the rigid, so the mass is recomputed at the positions each step starts from (where
// SOFA's mappings apply before a step). The points' masses must be lumped.
// Design: docs/mechanical-graph.md.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/rigid_points.h"
#include "fastcorot/sim/mass.h"

#include <span>
#include <vector>

namespace fastcorot {

template <class Real>
struct RigidMappedMass {
  // Points carried by the rigids, with their masses and the masses gravity weighs.
  struct Carried {
    RigidPoints<Real> points;
    std::vector<Real> masses;
    std::vector<Real> weights;
  };

  Mass<Real> own;  // the rigids' own mass (block-diagonal), or empty
  std::vector<Carried> carried;

  // The system's mass for positions x: own blocks plus every carried point's, with the couplings
  // and gravity blocks above. `points` is the state's size (blocks of rigid and other points).
  Mass<Real> at(std::span<const Vec3<Real>> x, Index points) const;
};

}  // namespace fastcorot
