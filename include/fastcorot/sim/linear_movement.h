// LinearMovement<Real>: SOFA's LinearMovementProjectiveConstraint (Sofa.Component.Constraint.
// Projective, LinearMovementProjectiveConstraint.inl, master 2a278d891f) on points or rigid bodies.
// Key times t_0 <= t_1 <= ... with one movement each; at context time t (a step's start, as SOFA's
// solve and its end-of-step projection read it) the segment [t_a, t_b) holding t is found as SOFA's
// findKeyTimes does. Only inside a segment (t_0 <= t < t_last) does anything happen:
// - during the solve the points are held (increments projected to zero);
// - after the step, m = M_a + (M_b - M_a)(t - t_a)/(t_b - t_a) and the point is set to x0 + m
//   (relativeMovements, the default) or m, its velocity to (M_b - M_a)(1/(t_b - t_a)).
// A rigid's movement is 6 numbers: the centre's (as a point's) and Euler angles, whose orientation
// becomes q0 ⊗ slerp2(q(E_a), q(E_b), α) (SOFA's createQuaterFromEuler, slerp2; absolute: without
// q0); its angular velocity is the angles' rate. x0 (and q0) are the positions at the first apply,
// which the scene builder makes at time 0 as SOFA's init does (its first projectPosition). Before
// t_0 and from t_last on, the points are free, as in SOFA.
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/sim/mechanical_state.h"
#include "fastcorot/state/rigid_blocks.h"

#include <optional>
#include <vector>

namespace fastcorot {

template <class Real>
struct LinearMovement {
  std::vector<Index> points;  // the blocks moved: points, or rigid centres (each rigid's angular block follows)
  std::vector<Index> rigids;  // for rigid bodies: the rigid of each entry of `points` (empty for points)
  std::vector<double> key_times;
  std::vector<Vec3<Real>> key_movements;  // per key: the point's (or centre's) movement
  std::vector<Vec3<Real>> key_angles;     // per key, rigid bodies only: Euler angles (radians)
  bool relative = true;
  // x0 and q0, recorded at the first apply() (at init: the scene's positions, so a run rebuilt
  // from the scene, as a resumed checkpoint is, has the same).
  std::vector<Vec3<Real>> start;
  std::vector<Eigen::Quaternion<Real>> start_orientation;
  bool started = false;

  // The segment (a, b) of key indices whose [t_a, t_b) holds `time`, t_a < t_b; nullopt outside
  // every segment (SOFA's findKeyTimes leaving `finished` false or nextT == prevT).
  std::optional<std::pair<std::size_t, std::size_t>> segment(double time) const;
  // The blocks held during a step starting at `time` (both blocks of a rigid).
  void held(double time, std::vector<Index>& out) const;
  // The end-of-step projection at `time`: positions, velocities and, for rigid bodies, the
  // orientations in `frames` (then re-based so that followers see them).
  void apply(double time, MechanicalState<Real>& state, RigidBlocks<Real>* frames);
};

}  // namespace fastcorot
