#include "fastcorot/state/rigid3.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <limits>

namespace fastcorot {

template <class Real>
Mat3<Real> RigidCoord<Real>::rotation() const {
  const Real x = orientation.x(), y = orientation.y(), z = orientation.z(), w = orientation.w();
  Mat3<Real> r;
  r(0, 0) = 1 - 2 * (y * y + z * z);
  r(0, 1) = 2 * (x * y - z * w);
  r(0, 2) = 2 * (z * x + y * w);
  r(1, 0) = 2 * (x * y + z * w);
  r(1, 1) = 1 - 2 * (z * z + x * x);
  r(1, 2) = 2 * (y * z - x * w);
  r(2, 0) = 2 * (z * x - y * w);
  r(2, 1) = 2 * (y * z + x * w);
  r(2, 2) = 1 - 2 * (y * y + x * x);
  return r;
}

namespace {

// v + 2w (u×v) + u×(2 u×v), u the vector part: SOFA's rotation of a vector by a quaternion.
template <class Real>
Vec3<Real> rotate_by(const Vec3<Real>& u, Real w, const Vec3<Real>& v) {
  const Vec3<Real> t = u.cross(v) * Real(2);
  return v + w * t + u.cross(t);
}

}  // namespace

template <class Real>
Vec3<Real> RigidCoord<Real>::rotate(const Vec3<Real>& v) const {
  return rotate_by<Real>(orientation.vec(), orientation.w(), v);
}

template <class Real>
Vec3<Real> RigidCoord<Real>::inverse_rotate(const Vec3<Real>& v) const {
  return rotate_by<Real>(-orientation.vec(), orientation.w(), v);
}

template <class Real>
Eigen::Quaternion<Real> quaternion_product(const Eigen::Quaternion<Real>& a, const Eigen::Quaternion<Real>& b) {
  const Real w = a.w() * b.w() - (a.x() * b.x() + a.y() * b.y() + a.z() * b.z());
  const Real x = a.w() * b.x() + a.x() * b.w() + a.y() * b.z() - a.z() * b.y();
  const Real y = a.w() * b.y() + a.y() * b.w() + a.z() * b.x() - a.x() * b.z();
  const Real z = a.w() * b.z() + a.z() * b.w() + a.x() * b.y() - a.y() * b.x();
  return quaternion_xyzw(x, y, z, w);
}

template <class Real>
void normalize_as_sofa(Eigen::Quaternion<Real>& q) {
  const Real squared = q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w();
  if (!(std::abs(squared - 1.0) > static_cast<Real>(1.0e-10))) return;
  if (squared == 0) {
    q.w() = 1;  // SOFA sets w alone: a zero quaternion becomes the identity
    return;
  }
  const Real scale = static_cast<Real>(1.0 / std::sqrt(squared));
  q.coeffs() *= scale;
}

template <class Real>
Eigen::Quaternion<Real> quaternion_inverse(const Eigen::Quaternion<Real>& q) {
  Real norm = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w());
  if (norm == 0) return q;
  norm = 1 / norm;
  return quaternion_xyzw(-q.x() * norm, -q.y() * norm, -q.z() * norm, q.w() * norm);
}

template <class Real>
void quaternion_to_axis(const Eigen::Quaternion<Real>& quaternion, Vec3<Real>& axis, Real& angle) {
  Eigen::Quaternion<Real> q = quaternion;
  if (q.w() < 0) q.coeffs() *= Real(-1);
  Real sin_half;
  if (q.w() > Real(0.999)) {
    sin_half = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z());
    angle = static_cast<Real>(2.0 * std::asin(sin_half));
  } else {
    const Real half = std::acos(q.w());
    sin_half = std::sin(half);
    angle = 2 * half;
  }
  if (sin_half < std::numeric_limits<Real>::epsilon()) {
    axis = Vec3<Real>(0, 1, 0);
  } else {
    axis = Vec3<Real>(q.x(), q.y(), q.z()) / sin_half;
  }
}

template <class Real>
void integrate(RigidCoord<Real>& x, const std::type_identity_t<Vec3<Real>>& dlinear,
               const std::type_identity_t<Vec3<Real>>& dangular) {
  x.center += dlinear;
  const Vec3<Real> half = dangular / Real(2);
  const Real theta = std::sqrt(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]);
  Eigen::Quaternion<Real> e;
  if (theta < std::numeric_limits<Real>::epsilon()) {
    // Below epsilon sin θ/θ and cos θ are 1 to round-off: SOFA's gnomonic fallback.
    e = quaternion_xyzw(half[0], half[1], half[2], Real(1));
    normalize_as_sofa(e);
  } else {
    const Real sinc = std::sin(theta) / theta;
    e = quaternion_xyzw(sinc * half[0], sinc * half[1], sinc * half[2], std::cos(theta));
  }
  x.orientation = quaternion_product(e, x.orientation);
}

namespace {

void check_finite(std::span<const double> values, std::size_t per_rigid, const std::string& where,
                  const char* what) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) {
      throw make_error(where, ": ", what, " of rigid ", k / per_rigid, " has a non-finite value (number ",
                       k % per_rigid + 1, " of ", per_rigid, ")");
    }
  }
}

}  // namespace

template <class Real>
std::vector<RigidCoord<Real>> parse_rigid_coords(std::span<const double> values, const std::string& where) {
  if (values.size() % 7 != 0) {
    throw make_error(where, ": Rigid3 positions need 7 numbers per rigid (x y z qx qy qz qw), got ",
                     values.size(), " numbers");
  }
  check_finite(values, 7, where, "position");
  std::vector<RigidCoord<Real>> coords(values.size() / 7);
  for (std::size_t i = 0; i < coords.size(); ++i) {
    const double* v = values.data() + 7 * i;
    if (v[3] == 0 && v[4] == 0 && v[5] == 0 && v[6] == 0) {
      throw make_error(where, ": rigid ", i, " has a zero quaternion (qx qy qz qw = 0 0 0 0)");
    }
    coords[i].center = Vec3<Real>(Real(v[0]), Real(v[1]), Real(v[2]));
    coords[i].orientation = quaternion_xyzw(Real(v[3]), Real(v[4]), Real(v[5]), Real(v[6]));
  }
  return coords;
}

template <class Real>
std::vector<double> to_values(std::span<const RigidCoord<Real>> coords) {
  std::vector<double> values;
  values.reserve(7 * coords.size());
  for (const RigidCoord<Real>& c : coords) {
    for (int k = 0; k < 3; ++k) values.push_back(double(c.center[k]));
    for (int k = 0; k < 4; ++k) values.push_back(double(c.orientation.coeffs()[k]));  // x y z w
  }
  return values;
}

template <class Real>
std::vector<Vec3<Real>> parse_rigid_derivs(std::span<const double> values, const std::string& where) {
  if (values.size() % 6 != 0) {
    throw make_error(where, ": Rigid3 derivatives need 6 numbers per rigid (vx vy vz wx wy wz), got ",
                     values.size(), " numbers");
  }
  check_finite(values, 6, where, "derivative");
  std::vector<Vec3<Real>> blocks(values.size() / 3);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    blocks[b] = Vec3<Real>(Real(values[3 * b]), Real(values[3 * b + 1]), Real(values[3 * b + 2]));
  }
  return blocks;
}

template <class Real>
std::vector<double> rigid_deriv_values(std::span<const Vec3<Real>> blocks) {
  if (blocks.size() % 2 != 0) {
    throw make_error("rigid derivatives: ", blocks.size(), " Vec3 blocks, not two per rigid");
  }
  std::vector<double> values;
  values.reserve(3 * blocks.size());
  for (const Vec3<Real>& b : blocks) {
    for (int k = 0; k < 3; ++k) values.push_back(double(b[k]));
  }
  return values;
}

template <class Real>
Eigen::Quaternion<Real> quaternion_from_euler(const Vec3<Real>& v) {
  const Real c1 = std::cos(v[0] / 2), c2 = std::cos(v[1] / 2), c3 = std::cos(v[2] / 2);
  const Real s1 = std::sin(v[0] / 2), s2 = std::sin(v[1] / 2), s3 = std::sin(v[2] / 2);
  return quaternion_xyzw<Real>(s1 * c2 * c3 - c1 * s2 * s3, c1 * s2 * c3 + s1 * c2 * s3, c1 * c2 * s3 - s1 * s2 * c3,
                               c1 * c2 * c3 + s1 * s2 * s3);
}

template <class Real>
Eigen::Quaternion<Real> slerp2(const Eigen::Quaternion<Real>& a, const Eigen::Quaternion<Real>& b, Real t) {
  const Real cos_half = a.w() * b.w() + a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
  if (std::abs(cos_half) >= 1.0) return a;
  const Real half = std::acos(cos_half);
  const Real sin_half = static_cast<Real>(std::sqrt(1.0 - cos_half * cos_half));
  Real ratio_a = 0.5, ratio_b = 0.5;
  if (!(std::abs(sin_half) < 0.001)) {
    ratio_a = std::sin((1 - t) * half) / sin_half;
    ratio_b = std::sin(t * half) / sin_half;
  }
  return quaternion_xyzw<Real>(a.x() * ratio_a + b.x() * ratio_b, a.y() * ratio_a + b.y() * ratio_b,
                               a.z() * ratio_a + b.z() * ratio_b, a.w() * ratio_a + b.w() * ratio_b);
}

#define FASTCOROT_INSTANTIATE(Real)                                                                        \
  template struct RigidCoord<Real>;                                                                        \
  template Eigen::Quaternion<Real> quaternion_product(const Eigen::Quaternion<Real>&,                      \
                                                      const Eigen::Quaternion<Real>&);                     \
  template void normalize_as_sofa(Eigen::Quaternion<Real>&);                                               \
  template Eigen::Quaternion<Real> quaternion_inverse(const Eigen::Quaternion<Real>&);                     \
  template void quaternion_to_axis(const Eigen::Quaternion<Real>&, Vec3<Real>&, Real&);                  \
  template Eigen::Quaternion<Real> quaternion_from_euler(const Vec3<Real>&);                               \
  template Eigen::Quaternion<Real> slerp2(const Eigen::Quaternion<Real>&, const Eigen::Quaternion<Real>&, Real); \
  template void integrate(RigidCoord<Real>&, const Vec3<Real>&, const Vec3<Real>&);                        \
  template std::vector<RigidCoord<Real>> parse_rigid_coords(std::span<const double>, const std::string&);  \
  template std::vector<double> to_values(std::span<const RigidCoord<Real>>);                               \
  template std::vector<Vec3<Real>> parse_rigid_derivs(std::span<const double>, const std::string&);        \
  template std::vector<double> rigid_deriv_values(std::span<const Vec3<Real>>);
FASTCOROT_INSTANTIATE(float)
FASTCOROT_INSTANTIATE(double)
#undef FASTCOROT_INSTANTIATE

}  // namespace fastcorot
