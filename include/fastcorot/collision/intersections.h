// The pair rules of SOFA's MinProximityIntersection (Sofa/Component/Collision/Detection/
// Intersection: MeshMinProximityIntersection.{h,cpp}, MinProximityIntersection.cpp) as pure
// functions of positions: whether two collision elements are within the alarm distance, and if so
// the detection output SOFA makes (two points, the unit normal from the first to the second, and
// value = distance - contact distance). The first step of the collision layer (docs/collision.md,
// §2.2, §2.4, §8 step 1); the pipeline that calls them comes next.
//
// Distances, per pair: alarm A = alarmDistance + cd₁ + cd₂ and contact C = contactDistance + cd₁ +
// cd₂ (cd the models' contactDistance); spheres add their radius to both. Rules, first element
// first:
// - Point–Point: always (within A).
// - Line–Point: the closest point of segment AB, its parameter clamped to [0, 1] (ends included;
//   a segment of zero length is its point A, where SOFA divides by zero).
// - Line–Line: the closest points of the two lines (2×2 normal equations by Cramer's rule); when
//   |det| ≤ 1e-15 (parallel) both parameters are ½, else both must lie in [1e-6, 0.999999].
// - Triangle–Point: the point's projection on the triangle's plane (barycentric α on AB, β on AC
//   by Cramer's rule), kept only strictly inside: α ≥ 1e-6, β ≥ 1e-6, α + β ≤ 0.999999.
// - Sphere–Point, Line–Sphere, Triangle–Sphere: as the point rules with the sphere's centre (Line
//   and Triangle: inside only, α in [1e-6, 0.999999]; Line–Sphere takes SOFA's point, the mirror
//   of the closest one about the segment's middle); the sphere's point is its centre for a Vec3
//   sphere, centre − r n for a rigid one (SOFA's getContactPointByNormal).
// - Sphere–Sphere: the centres (rigid spheres: their surface points along the normal).
// A zero distance (≤ 1e-15) gives SOFA's normal (1, 0, 0) and sets `null_distance` (SOFA warns).
// Beyond SOFA: a degenerate triangle (its Gram determinant not > 0, where SOFA divides by zero and
// reports NaN points) gives no output; `degenerate_triangle` lets the caller count them.
#pragma once

#include "fastcorot/core/types.h"

#include <optional>

namespace fastcorot {

template <class Real>
struct ProximityDistances {
  Real alarm = 0;    // A
  Real contact = 0;  // C
};

template <class Real>
struct ProximityOutput {
  Vec3<Real> point[2];  // on the first element, on the second
  Vec3<Real> normal;    // unit, from point[0] to point[1]
  Real value = 0;       // |point[1] - point[0]| - C
  bool null_distance = false;
};

// A sphere in a rule: its centre and radius; `rigid` when it is SOFA's RigidSphereModel (its
// contact point lies on its surface).
template <class Real>
struct ProximitySphere {
  Vec3<Real> center;
  Real radius = 0;
  bool rigid = false;
};

template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_point_point(const Vec3<Real>& p, const Vec3<Real>& q,
                                                               const ProximityDistances<Real>& d);
// Segment (a, b) first, point p second.
template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_line_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& p,
                                                              const ProximityDistances<Real>& d);
// Segments (a, b) and (c, e).
template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_line_line(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                             const Vec3<Real>& e, const ProximityDistances<Real>& d);
// Triangle (a, b, c) first, point p second. `surface_normal` (SOFA's useSurfaceNormals): the
// output's normal is that unit normal instead (the triangle model's).
template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_triangle_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                  const Vec3<Real>& p, const ProximityDistances<Real>& d,
                                                                  const Vec3<Real>* surface_normal = nullptr);
// Sphere first, point second; `d` without the radius (added here).
template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_sphere_point(const ProximitySphere<Real>& s, const Vec3<Real>& p,
                                                                ProximityDistances<Real> d);
template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_sphere_sphere(const ProximitySphere<Real>& s, const ProximitySphere<Real>& t,
                                                                 ProximityDistances<Real> d);
template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_line_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const ProximitySphere<Real>& s,
                                                               ProximityDistances<Real> d);
template <class Real>
std::optional<ProximityOutput<Real>> min_proximity_triangle_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                   const ProximitySphere<Real>& s, ProximityDistances<Real> d);

// Whether triangle (a, b, c) has no plane: its Gram determinant |AB|²|AC|² - (AB·AC)² is not > 0.
template <class Real>
bool degenerate_triangle(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c);

}  // namespace fastcorot
