// Rigid3 states, as SOFA's StdRigidTypes<3> holds them (Sofa/framework/DefaultType/src/sofa/
// defaulttype/RigidCoord.h, RigidDeriv.h; quaternion arithmetic of Sofa/framework/Type/src/sofa/
// type/Quat.h/.inl). A rigid's position is a RigidCoord: a centre and a unit quaternion, written in
// text as "x y z qx qy qz qw" (the vector part first). Its velocity, a small displacement, a force
// are each two Vec3 blocks [linear, angular] in the world frame: (v, ω), (dx, dθ), (f, τ); in text
// "vx vy vz wx wy wz". Solver vectors hold them as consecutive Vec3 blocks [v0, ω0, v1, ω1, ...].
// A displacement is applied as SOFA's `x += dx`: the centre moves by the linear part and the
// orientation turns by the exponential of the angular part, on the left (world frame).
#pragma once

#include "fastcorot/core/types.h"

#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace fastcorot {

template <class Real>
struct RigidCoord {
  Vec3<Real> center = Vec3<Real>::Zero();
  // Eigen stores (x, y, z, w), SOFA's order. Beware Eigen's four-scalar constructor, which takes w
  // first: build one with `quaternion_xyzw`.
  Eigen::Quaternion<Real> orientation = Eigen::Quaternion<Real>::Identity();

  // SOFA's Quat::toMatrix: the rotation matrix of a unit quaternion (entries quadratic in q, so a
  // quaternion that is not unit gives a matrix that is not a rotation, as in SOFA).
  Mat3<Real> rotation() const;
  // SOFA's Quat::rotate: v + 2w (q×v) + 2 q×(q×v) (q the vector part), = rotation() v for unit q.
  Vec3<Real> rotate(const Vec3<Real>& v) const;
  // SOFA's Quat::inverseRotate: rotate by the conjugate quaternion.
  Vec3<Real> inverse_rotate(const Vec3<Real>& v) const;
  // SOFA's RigidCoord::mult / projectPoint: a point of the body frame in the world, rotate(p) + c.
  Vec3<Real> project_point(const Vec3<Real>& p) const { return rotate(p) + center; }
};

// [r]×: the matrix of v ↦ r × v (a rigid's J block for a point at offset r is [I₃ | −[r]×]).
template <class Real>
Mat3<Real> cross_matrix(const Vec3<Real>& r) {
  Mat3<Real> m;
  m << Real(0), -r.z(), r.y(), r.z(), Real(0), -r.x(), -r.y(), r.x(), Real(0);
  return m;
}

// The quaternion (x, y, z, w) in SOFA's order.
template <class Real>
Eigen::Quaternion<Real> quaternion_xyzw(Real x, Real y, Real z, Real w) {
  return Eigen::Quaternion<Real>(w, x, y, z);
}

// SOFA's Quat::operator*: the Hamilton product a ⊗ b (rotate by b, then by a), with SOFA's
// grouping of terms. Not normalised.
template <class Real>
Eigen::Quaternion<Real> quaternion_product(const Eigen::Quaternion<Real>& a, const Eigen::Quaternion<Real>& b);

// SOFA's Quat::normalize: divides by the norm only when |‖q‖² - 1| > 1e-10; a zero quaternion
// becomes (0, 0, 0, 1).
template <class Real>
void normalize_as_sofa(Eigen::Quaternion<Real>& q);

// SOFA's Quat::inverse: the conjugate divided by the norm (not its square); zero stays zero.
template <class Real>
Eigen::Quaternion<Real> quaternion_inverse(const Eigen::Quaternion<Real>& q);

// SOFA's Quat::quatToAxis: the axis and angle in [0, π] of q (negated first when w < 0); the angle
// from asin of the vector part's norm when w > 0.999, else from acos(w); axis (0, 1, 0) when the
// vector part's norm is below machine epsilon.
template <class Real>
void quaternion_to_axis(const Eigen::Quaternion<Real>& q, Vec3<Real>& axis, Real& angle);

// SOFA's Quat::createQuaterFromEuler with its default order (EulerOrder::ZYX): the quaternion of
// the Euler angles v (radians), terms as SOFA writes them.
template <class Real>
Eigen::Quaternion<Real> quaternion_from_euler(const Vec3<Real>& v);

// SOFA's Quat::slerp2: from a (t = 0) to b (t = 1) along the great arc, with no shortest-path flip;
// a when |a·b| >= 1, the halfway sum when the arc's sine is below 0.001. Not normalised.
template <class Real>
Eigen::Quaternion<Real> slerp2(const Eigen::Quaternion<Real>& a, const Eigen::Quaternion<Real>& b, Real t);

// SOFA's RigidCoord `x += dx` for a displacement (dlinear, dangular) in the world frame:
// center += dlinear; q ← e ⊗ q with e = exp(dangular / 2) = (sin θ/θ · dangular/2, cos θ),
// θ = |dangular/2|; when θ < machine epsilon of Real, e = (dangular/2, 1) normalised
// (normalize_as_sofa, which leaves it unchanged there). The product is not renormalised (SOFA
// does not), so |q| drifts only by round-off. Implicit Euler's x ← x + h v turns a rigid by h ω.
// (Real is taken from x alone, so Eigen expressions can be passed.)
template <class Real>
void integrate(RigidCoord<Real>& x, const std::type_identity_t<Vec3<Real>>& dlinear,
               const std::type_identity_t<Vec3<Real>>& dangular);

// Rigid3 positions from their text values, 7 per rigid: x y z qx qy qz qw (a MechanicalObject's
// position or rest_position). The quaternion is kept as written: SOFA's reader normalises it only
// in debug builds (RigidCoord.h operator>>, under !NDEBUG), and the release build, which produces
// SOFA's reference results, uses it as given. Throws fastcorot::Error naming `where` and the rigid
// for a count that is not a multiple of 7, a non-finite value or a zero quaternion.
template <class Real>
std::vector<RigidCoord<Real>> parse_rigid_coords(std::span<const double> values, const std::string& where);

// The text values of rigid positions, 7 per rigid, SOFA's order.
template <class Real>
std::vector<double> to_values(std::span<const RigidCoord<Real>> coords);

// Rigid3 derivatives (velocity, force) from their text values, 6 per rigid: vx vy vz wx wy wz,
// as two Vec3 blocks per rigid [linear, angular] (2 #rigids blocks). Throws fastcorot::Error
// naming `where` and the rigid for a count that is not a multiple of 6 or a non-finite value.
template <class Real>
std::vector<Vec3<Real>> parse_rigid_derivs(std::span<const double> values, const std::string& where);

// The text values of rigid derivatives given as 2 #rigids Vec3 blocks, 6 per rigid.
template <class Real>
std::vector<double> rigid_deriv_values(std::span<const Vec3<Real>> blocks);

}  // namespace fastcorot
