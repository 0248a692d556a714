#include "fastcorot/collision/intersections.h"

#include <cmath>

namespace fastcorot {

namespace {

// The output from point p (on the first element) to q (on the second): SOFA's normal q - p, its
// length minus C, (1, 0, 0) for a zero length.
template <class Real>
ProximityOutput<Real> output(const Vec3<Real>& p, const Vec3<Real>& q, Real contact) {
  ProximityOutput<Real> out;
  out.point[0] = p;
  out.point[1] = q;
  out.normal = q - p;
  out.value = out.normal.norm();
  if (out.value > Real(1e-15)) {
    out.normal /= out.value;
  } else {
    out.normal = Vec3<Real>::UnitX();
    out.null_distance = true;
  }
  out.value -= contact;
  return out;
}

// A sphere's contact point for a normal pointing away from it (SOFA's getContactPointByNormal with
// the normal toward the sphere): a rigid sphere's surface point, a Vec3 sphere's centre.
template <class Real>
Vec3<Real> sphere_point(const ProximitySphere<Real>& s, const Vec3<Real>& toward_sphere) {
  return s.rigid ? Vec3<Real>(s.center - toward_sphere * s.radius) : s.center;
}

// Barycentric (α on AB, β on AC) of p's projection on the plane of (a, b, c) by Cramer's rule on
// the 2×2 normal equations, as SOFA writes them; nullopt for a degenerate triangle.
template <class Real>
std::optional<std::pair<Real, Real>> barycentric(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c, const Vec3<Real>& p) {
  const Vec3<Real> ab = b - a, ac = c - a, ap = p - a;
  const Real a00 = ab.dot(ab), a11 = ac.dot(ac), a01 = ab.dot(ac);
  const Real b0 = ap.dot(ab), b1 = ap.dot(ac);
  const Real det = a00 * a11 - a01 * a01;
  if (!(det > 0)) return std::nullopt;
  return std::make_pair((b0 * a11 - b1 * a01) / det, (b1 * a00 - b0 * a01) / det);
}

template <class Real>
bool strictly_inside(Real alpha, Real beta) {
  return !(alpha < Real(1e-6) || beta < Real(1e-6) || alpha + beta > Real(0.999999));
}

template <class Real>
ProximityDistances<Real> with_radius(ProximityDistances<Real> d, Real radius) {
  d.alarm += radius;
  d.contact += radius;
  return d;
}

}  // namespace

template <class Real>
bool degenerate_triangle(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c) {
  return !barycentric(a, b, c, a).has_value();
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_point_point(const Vec3<Real>& p, const Vec3<Real>& q,
                                                               const ProximityDistances<Real>& d) {
  if ((q - p).squaredNorm() >= d.alarm * d.alarm) return std::nullopt;
  return output(p, q, d.contact);
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_line_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& p,
                                                              const ProximityDistances<Real>& d) {
  const Vec3<Real> ab = b - a;
  const Real length2 = ab.dot(ab);
  // Beyond SOFA (which divides by zero there): a segment of zero length is its point a.
  const Real alpha = length2 > 0 ? (p - a).dot(ab) / length2 : Real(0);
  const Vec3<Real> q = alpha <= 0 ? a : alpha >= 1 ? b : Vec3<Real>(a + ab * alpha);
  if ((p - q).squaredNorm() >= d.alarm * d.alarm) return std::nullopt;
  return output(q, p, d.contact);
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_line_line(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                             const Vec3<Real>& e, const ProximityDistances<Real>& d) {
  const Vec3<Real> ab = b - a, ce = e - c, ac = c - a;
  const Real a00 = ab.dot(ab), a11 = ce.dot(ce), a01 = -ce.dot(ab);
  const Real b0 = ab.dot(ac), b1 = -ce.dot(ac);
  const Real det = a00 * a11 - a01 * a01;
  Real alpha = 0.5, beta = 0.5;
  if (det < Real(-1e-15) || det > Real(1e-15)) {
    alpha = (b0 * a11 - b1 * a01) / det;
    beta = (b1 * a00 - b0 * a01) / det;
    if (alpha < Real(1e-6) || alpha > Real(0.999999) || beta < Real(1e-6) || beta > Real(0.999999)) return std::nullopt;
  }
  const Vec3<Real> p = a + ab * alpha, q = c + ce * beta;
  if ((q - p).squaredNorm() >= d.alarm * d.alarm) return std::nullopt;
  return output(p, q, d.contact);
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_triangle_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                  const Vec3<Real>& p, const ProximityDistances<Real>& d,
                                                                  const Vec3<Real>* surface_normal) {
  const auto coordinates = barycentric(a, b, c, p);
  if (!coordinates || !strictly_inside(coordinates->first, coordinates->second)) return std::nullopt;
  const Vec3<Real> q = a + (b - a) * coordinates->first + (c - a) * coordinates->second;
  if ((p - q).squaredNorm() >= d.alarm * d.alarm) return std::nullopt;
  auto out = output(q, p, d.contact);
  if (surface_normal) out.normal = *surface_normal;
  return out;
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_sphere_point(const ProximitySphere<Real>& s, const Vec3<Real>& p,
                                                                ProximityDistances<Real> d) {
  d = with_radius(d, s.radius);
  if ((p - s.center).squaredNorm() >= d.alarm * d.alarm) return std::nullopt;
  auto out = output(s.center, p, d.contact);
  out.point[0] = sphere_point(s, Vec3<Real>(-out.normal));
  return out;
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_sphere_sphere(const ProximitySphere<Real>& s, const ProximitySphere<Real>& t,
                                                                 ProximityDistances<Real> d) {
  const Real r = s.radius + t.radius;
  // SOFA's DiscreteIntersection sphere rule: the alarm boundary included.
  if ((t.center - s.center).squaredNorm() > (d.alarm + r) * (d.alarm + r)) return std::nullopt;
  auto out = output(s.center, t.center, d.contact + r);
  out.point[0] = sphere_point(s, Vec3<Real>(-out.normal));
  out.point[1] = sphere_point(t, out.normal);
  return out;
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_line_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const ProximitySphere<Real>& s,
                                                               ProximityDistances<Real> d) {
  d = with_radius(d, s.radius);
  // SOFA's parameter is measured from b toward a, and its point taken from a with it: the mirror
  // of the closest point about the segment's middle (docs/collision.md, §9), kept as SOFA has it.
  const Vec3<Real> ba = a - b;
  if (!(ba.dot(ba) > 0)) return std::nullopt;  // beyond SOFA: no segment, no contact (SOFA's is NaN)
  const Real alpha = ba.dot(s.center - b) / ba.dot(ba);
  if (alpha < Real(1e-6) || alpha > Real(0.999999)) return std::nullopt;
  const Vec3<Real> q = a - ba * alpha;
  if ((s.center - q).squaredNorm() >= d.alarm * d.alarm) return std::nullopt;
  auto out = output(q, s.center, d.contact);
  out.point[1] = sphere_point(s, out.normal);
  return out;
}

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_triangle_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                   const ProximitySphere<Real>& s, ProximityDistances<Real> d) {
  d = with_radius(d, s.radius);
  const auto coordinates = barycentric(a, b, c, s.center);
  if (!coordinates || !strictly_inside(coordinates->first, coordinates->second)) return std::nullopt;
  const Vec3<Real> q = a + (b - a) * coordinates->first + (c - a) * coordinates->second;
  if ((s.center - q).squaredNorm() >= d.alarm * d.alarm) return std::nullopt;
  auto out = output(q, s.center, d.contact);
  out.point[1] = sphere_point(s, out.normal);
  return out;
}

#define FASTCOROT_INTERSECTIONS(Real)                                                                                                \
  template bool degenerate_triangle(const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&);                                        \
  template std::optional<ProximityOutput<Real>> min_proximity_point_point(const Vec3<Real>&, const Vec3<Real>&,                     \
                                                                          const ProximityDistances<Real>&);                          \
  template std::optional<ProximityOutput<Real>> min_proximity_line_point(const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&,   \
                                                                         const ProximityDistances<Real>&);                           \
  template std::optional<ProximityOutput<Real>> min_proximity_line_line(const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&,    \
                                                                        const Vec3<Real>&, const ProximityDistances<Real>&);         \
  template std::optional<ProximityOutput<Real>> min_proximity_triangle_point(                                                        \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, const ProximityDistances<Real>&, const Vec3<Real>*); \
  template std::optional<ProximityOutput<Real>> min_proximity_sphere_point(const ProximitySphere<Real>&, const Vec3<Real>&,         \
                                                                           ProximityDistances<Real>);                                \
  template std::optional<ProximityOutput<Real>> min_proximity_sphere_sphere(const ProximitySphere<Real>&,                           \
                                                                            const ProximitySphere<Real>&, ProximityDistances<Real>); \
  template std::optional<ProximityOutput<Real>> min_proximity_line_sphere(const Vec3<Real>&, const Vec3<Real>&,                     \
                                                                          const ProximitySphere<Real>&, ProximityDistances<Real>);   \
  template std::optional<ProximityOutput<Real>> min_proximity_triangle_sphere(                                                       \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, const ProximitySphere<Real>&, ProximityDistances<Real>);
FASTCOROT_INTERSECTIONS(float)
FASTCOROT_INTERSECTIONS(double)
#undef FASTCOROT_INTERSECTIONS

}  // namespace fastcorot
