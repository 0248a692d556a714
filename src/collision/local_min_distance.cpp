#include "fastcorot/collision/local_min_distance.h"

#include "fastcorot/core/error.h"
#include "sofa_vec.h"

#include <cmath>

namespace fastcorot {

namespace {

using sofa_vec::dot3;
using sofa_vec::norm3;
using sofa_vec::sofa_normalized;
using sofa_vec::unit_triangle_normal;

// The output from p (first element) to q (second); a zero distance takes `fallback`.
template <class Real>
ProximityOutput<Real> output(const Vec3<Real>& p, const Vec3<Real>& q, Real contact,
                             const Vec3<Real>& fallback) {
  ProximityOutput<Real> out;
  out.point[0] = p;
  out.point[1] = q;
  out.normal = q - p;
  out.value = norm3(out.normal);
  if (out.value > 0) {
    out.normal /= out.value;
  } else {
    out.normal = fallback;
    out.null_distance = true;
  }
  out.value -= contact;
  return out;
}

template <class Real>
bool within(const Vec3<Real>& pq, Real alarm) {
  return dot3(pq, pq) < alarm * alarm;
}

// Barycentric α (on AB), β (on AC) of p's projection, SOFA's Cramer's rule; nullopt for a
// degenerate triangle or a projection not strictly inside.
template <class Real>
std::optional<Vec3<Real>> triangle_foot(const Vec3<Real>& a, const Vec3<Real>& b,
                                        const Vec3<Real>& c, const Vec3<Real>& p) {
  const Vec3<Real> ab = b - a, ac = c - a, ap = p - a;
  const Real a00 = dot3(ab, ab), a11 = dot3(ac, ac), a01 = dot3(ab, ac);
  const Real b0 = dot3(ap, ab), b1 = dot3(ap, ac);
  const Real det = a00 * a11 - a01 * a01;
  if (!(det > 0)) return std::nullopt;
  const Real alpha = (b0 * a11 - b1 * a01) / det;
  const Real beta = (b1 * a00 - b0 * a01) / det;
  if (alpha < Real(0.000001) || beta < Real(0.000001) || alpha + beta > Real(0.999999))
    return std::nullopt;
  return Vec3<Real>(a + ab * alpha + ac * beta);
}

// The foot of p on segment AB with α in [1e-6, 0.999999], after SOFA's guard |AB| < 1e-12 |AP|.
template <class Real>
std::optional<Vec3<Real>> segment_foot(const Vec3<Real>& a, const Vec3<Real>& b,
                                       const Vec3<Real>& p) {
  const Vec3<Real> ab = b - a, ap = p - a;
  const Real length2 = dot3(ab, ab);
  if (!(length2 > 0) || norm3(ab) < Real(0.000000000001) * norm3(ap)) return std::nullopt;
  const Real alpha = dot3(ap, ab) / length2;
  if (alpha < Real(0.000001) || alpha > Real(0.999999)) return std::nullopt;
  return Vec3<Real>(a + ab * alpha);
}

template <class Real>
void check_vec3_sphere(const ProximitySphere<Real>& sphere) {
  if (sphere.rigid)
    throw make_error(
        "LocalMinDistance: a rigid sphere has no rule (SOFA registers Vec3 spheres only)");
}

// max(0, coneFactor × n·t) + angleCone: the cone's widening along t.
template <class Real>
Real widened_cone(const Vec3<Real>& n, const Vec3<Real>& t,
                  const LocalMinDistanceSettings<Real>& s) {
  Real cone = dot3(n, t) * s.cone_factor;
  if (cone < 0) cone = 0;
  return cone + s.angle_cone;
}

}  // namespace

template <class Real>
bool local_min_distance_point_validity(
    const LocalMinDistancePointCone<std::type_identity_t<Real>>* cone, const Vec3<Real>& v,
    const LocalMinDistanceSettings<Real>& s) {
  if (!s.filter_intersection || !cone) return true;
  Vec3<Real> mean = cone->normal_sum;
  const Real length = norm3(v);
  if (norm3(mean) > Real(0.0000000001)) {
    mean = sofa_normalized(mean);
    if (dot3(mean, v) < -s.angle_cone * length && !cone->both_side) return false;
  }
  for (const Vec3<Real>& e : cone->edge_directions) {
    if (dot3(e, v) < -widened_cone(mean, e, s) * length) return false;
  }
  return true;
}

template <class Real>
bool local_min_distance_line_validity(const Vec3<Real>& a, const Vec3<Real>& b,
                                      const LocalMinDistanceLineCone<Real>& cone,
                                      const Vec3<Real>& v,
                                      const LocalMinDistanceSettings<Real>& s) {
  if (!s.filter_intersection) return true;
  const Vec3<Real> u = sofa_normalized(Vec3<Real>(b - a));
  if (!cone.two_triangles) {
    // SOFA's check that v is perpendicular to the segment (its guard for parallel segments).
    return !(std::abs(dot3(u, sofa_normalized(v))) > s.angle_cone + Real(0.0001));
  }
  const Vec3<Real> t_right = sofa_normalized(Vec3<Real>(cone.right_normal.cross(u)));
  const Vec3<Real> t_left = sofa_normalized(Vec3<Real>(u.cross(cone.left_normal)));
  const Vec3<Real> mean = sofa_normalized(Vec3<Real>(cone.right_normal + cone.left_normal));
  if (dot3(mean, v) < 0 && !cone.both_side) return false;
  const Real length = norm3(v);
  if (dot3(t_right, v) < -widened_cone(mean, t_right, s) * length) return false;
  return !(dot3(t_left, v) < -widened_cone(mean, t_left, s) * length);
}

template <class Real>
bool local_min_distance_triangle_validity(const Vec3<Real>& a, const Vec3<Real>& b,
                                          const Vec3<Real>& c, bool both_side, const Vec3<Real>& v,
                                          const LocalMinDistanceSettings<Real>& s) {
  if (!s.filter_intersection || both_side) return true;
  return dot3(Vec3<Real>((b - a).cross(c - a)), v) >= 0;
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_point_point(
    const Vec3<Real>& p, const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
    const Vec3<Real>& q, const LocalMinDistancePointCone<std::type_identity_t<Real>>* q_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s) {
  const Vec3<Real> pq = q - p;
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters && (!local_min_distance_point_validity(p_cone, pq, s) ||
                             !local_min_distance_point_validity(q_cone, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(p, q, d.contact, Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_point(
    const Vec3<Real>& a, const Vec3<Real>& b, const LocalMinDistanceLineCone<Real>& line_cone,
    const Vec3<Real>& p, const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s) {
  const auto q = segment_foot(a, b, p);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - p;  // from the point toward the segment
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters &&
      (!local_min_distance_point_validity(p_cone, pq, s) ||
       !local_min_distance_line_validity(a, b, line_cone, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(*q, p, d.contact, Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_line(
    const Vec3<Real>& a, const Vec3<Real>& b, const LocalMinDistanceLineCone<Real>& ab_cone,
    const Vec3<Real>& c, const Vec3<Real>& e, const LocalMinDistanceLineCone<Real>& ce_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s) {
  const Vec3<Real> ab = b - a, ce = e - c, ac = c - a;
  const Real a00 = dot3(ab, ab), a11 = dot3(ce, ce), a01 = -dot3(ce, ab);
  if (!(a00 > 0) || !(a11 > 0)) return std::nullopt;  // beyond SOFA: a segment of no length
  const Real b0 = dot3(ab, ac), b1 = -dot3(ce, ac);
  const Real det = a00 * a11 - a01 * a01;
  Real alpha = 0.5, beta = 0.5;
  if (det < Real(-1.0e-30) || det > Real(1.0e-30)) {
    alpha = (b0 * a11 - b1 * a01) / det;
    beta = (b1 * a00 - b0 * a01) / det;
    if (alpha < Real(1e-15) || alpha > Real(1.0 - 1e-15) || beta < Real(1e-15) ||
        beta > Real(1.0 - 1e-15))
      return std::nullopt;
  }
  const Vec3<Real> p = a + ab * alpha, q = c + ce * beta;
  const Vec3<Real> pq = q - p;
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters &&
      (!local_min_distance_line_validity(a, b, ab_cone, pq, s) ||
       !local_min_distance_line_validity(c, e, ce_cone, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(p, q, d.contact, Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_triangle_point(
    const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c, bool triangle_both_side,
    const Vec3<Real>& p, const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s) {
  const auto q = triangle_foot(a, b, c, p);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - p;  // from the point toward the triangle
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters &&
      (!local_min_distance_point_validity(p_cone, pq, s) ||
       !local_min_distance_triangle_validity(a, b, c, triangle_both_side, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(*q, p, d.contact, unit_triangle_normal(a, b, c));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_sphere_point(
    const ProximitySphere<Real>& sphere, const Vec3<Real>& p,
    const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone, ProximityDistances<Real> d,
    const LocalMinDistanceSettings<Real>& s) {
  check_vec3_sphere(sphere);
  const Vec3<Real> pq = p - sphere.center;
  if (!within(pq, Real(d.alarm + sphere.radius))) return std::nullopt;
  // The sphere's own filter accepts every direction.
  if (!s.use_lmd_filters && !local_min_distance_point_validity(p_cone, Vec3<Real>(-pq), s))
    return std::nullopt;
  return output(sphere.center, p, Real(d.contact + sphere.radius), Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_sphere(
    const Vec3<Real>& a, const Vec3<Real>& b, const LocalMinDistanceLineCone<Real>& line_cone,
    const ProximitySphere<Real>& sphere, ProximityDistances<Real> d,
    const LocalMinDistanceSettings<Real>& s) {
  check_vec3_sphere(sphere);
  const auto q = segment_foot(a, b, sphere.center);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - sphere.center;
  if (!within(pq, Real(d.alarm + sphere.radius))) return std::nullopt;
  if (!s.use_lmd_filters && !local_min_distance_line_validity(a, b, line_cone, Vec3<Real>(-pq), s))
    return std::nullopt;
  return output(*q, sphere.center, Real(d.contact + sphere.radius),
                Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_triangle_sphere(
    const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c, bool triangle_both_side,
    const ProximitySphere<Real>& sphere, ProximityDistances<Real> d,
    const LocalMinDistanceSettings<Real>& s) {
  check_vec3_sphere(sphere);
  const auto q = triangle_foot(a, b, c, sphere.center);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - sphere.center;
  if (!within(pq, Real(d.alarm + sphere.radius))) return std::nullopt;
  if (!s.use_lmd_filters &&
      !local_min_distance_triangle_validity(a, b, c, triangle_both_side, Vec3<Real>(-pq), s))
    return std::nullopt;
  return output(*q, sphere.center, Real(d.contact + sphere.radius), unit_triangle_normal(a, b, c));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_sphere_sphere(
    const ProximitySphere<Real>& sphere1, const ProximitySphere<Real>& sphere2,
    ProximityDistances<Real> d) {
  check_vec3_sphere(sphere1);
  check_vec3_sphere(sphere2);
  const Vec3<Real> pq = sphere2.center - sphere1.center;
  const Real radii = sphere1.radius + sphere2.radius;
  if (!within(pq, Real(d.alarm + radii))) return std::nullopt;
  return output(sphere1.center, sphere2.center, Real(d.contact + radii),
                Vec3<Real>(Vec3<Real>::UnitX()));
}

#define FASTCOROT_LOCAL_MIN_DISTANCE(Real)                                                         \
  template bool local_min_distance_point_validity(const LocalMinDistancePointCone<Real>*,          \
                                                  const Vec3<Real>&,                               \
                                                  const LocalMinDistanceSettings<Real>&);          \
  template bool local_min_distance_line_validity(                                                  \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&,                 \
      const Vec3<Real>&, const LocalMinDistanceSettings<Real>&);                                   \
  template bool local_min_distance_triangle_validity(const Vec3<Real>&, const Vec3<Real>&,         \
                                                     const Vec3<Real>&, bool, const Vec3<Real>&,   \
                                                     const LocalMinDistanceSettings<Real>&);       \
  template std::optional<ProximityOutput<Real>> local_min_distance_point_point(                    \
      const Vec3<Real>&, const LocalMinDistancePointCone<Real>*, const Vec3<Real>&,                \
      const LocalMinDistancePointCone<Real>*, const ProximityDistances<Real>&,                     \
      const LocalMinDistanceSettings<Real>&);                                                      \
  template std::optional<ProximityOutput<Real>> local_min_distance_line_point(                     \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&,                 \
      const Vec3<Real>&, const LocalMinDistancePointCone<Real>*, const ProximityDistances<Real>&,  \
      const LocalMinDistanceSettings<Real>&);                                                      \
  template std::optional<ProximityOutput<Real>> local_min_distance_line_line(                      \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&,                 \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&,                 \
      const ProximityDistances<Real>&, const LocalMinDistanceSettings<Real>&);                     \
  template std::optional<ProximityOutput<Real>> local_min_distance_triangle_point(                 \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, bool, const Vec3<Real>&,            \
      const LocalMinDistancePointCone<Real>*, const ProximityDistances<Real>&,                     \
      const LocalMinDistanceSettings<Real>&);                                                      \
  template std::optional<ProximityOutput<Real>> local_min_distance_sphere_point(                   \
      const ProximitySphere<Real>&, const Vec3<Real>&, const LocalMinDistancePointCone<Real>*,     \
      ProximityDistances<Real>, const LocalMinDistanceSettings<Real>&);                            \
  template std::optional<ProximityOutput<Real>> local_min_distance_line_sphere(                    \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&,                 \
      const ProximitySphere<Real>&, ProximityDistances<Real>,                                      \
      const LocalMinDistanceSettings<Real>&);                                                      \
  template std::optional<ProximityOutput<Real>> local_min_distance_triangle_sphere(                \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, bool, const ProximitySphere<Real>&, \
      ProximityDistances<Real>, const LocalMinDistanceSettings<Real>&);                            \
  template std::optional<ProximityOutput<Real>> local_min_distance_sphere_sphere(                  \
      const ProximitySphere<Real>&, const ProximitySphere<Real>&, ProximityDistances<Real>);
FASTCOROT_LOCAL_MIN_DISTANCE(float)
FASTCOROT_LOCAL_MIN_DISTANCE(double)
#undef FASTCOROT_LOCAL_MIN_DISTANCE

}  // namespace fastcorot
