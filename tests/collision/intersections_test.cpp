// MinProximityIntersection's pair rules against references written differently, in long double:
// closest points on segments by golden-section search, on lines by the cross-product formulas, on
// triangles by projecting along the unit normal and testing inside with sub-triangle areas; on
// random primitives, plus SOFA's thresholds at their boundaries, the rigid spheres' surface points,
// SOFA's mirrored Line–Sphere point, zero distances and degenerate elements (no NaN).
#include "fastcorot/collision/intersections.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fastcorot {
namespace {

using V = Vec3<double>;
using L = Eigen::Matrix<long double, 3, 1>;

L wide(const V& v) { return v.cast<long double>(); }

V random_point(std::mt19937& rng, double scale = 1) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return V(u(rng), u(rng), u(rng));
}

// The parameter of the closest point of segment [a, b] to p, by golden-section search.
long double segment_parameter(const L& a, const L& b, const L& p) {
  long double lo = 0, hi = 1;
  const long double g = (std::sqrt(5.0L) - 1) / 2;
  const auto f = [&](long double t) { return (a + (b - a) * t - p).squaredNorm(); };
  for (int i = 0; i < 200; ++i) {
    const long double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (f(x1) < f(x2)) hi = x2; else lo = x1;
  }
  return (lo + hi) / 2;
}

const ProximityDistances<double> kWide{10.0, 0.25};

TEST(MinProximity, LinePointIsTheClampedClosestPoint) {
  std::mt19937 rng(1);
  for (int k = 0; k < 500; ++k) {
    const V a = random_point(rng), b = random_point(rng), p = random_point(rng);
    const auto out = min_proximity_line_point(a, b, p, kWide);
    ASSERT_TRUE(out);
    const long double t = segment_parameter(wide(a), wide(b), wide(p));
    const L q = wide(a) + (wide(b) - wide(a)) * t;
    EXPECT_LT((wide(out->point[0]) - q).norm(), 1e-9L) << k;
    EXPECT_EQ(out->point[1], p);
    EXPECT_NEAR(out->value, static_cast<double>((wide(p) - q).norm()) - 0.25, 1e-9);
    EXPECT_NEAR(out->normal.norm(), 1.0, 1e-15);
    EXPECT_GT(out->normal.dot(p - out->point[0]), 0);
  }
  // Beyond the alarm distance (exclusive, as SOFA's >=): nothing.
  EXPECT_FALSE(min_proximity_line_point(V(0, 0, 0), V(1, 0, 0), V(0.5, 2, 0), {2.0, 0.0}));
  EXPECT_TRUE(min_proximity_line_point(V(0, 0, 0), V(1, 0, 0), V(0.5, 1.999, 0), {2.0, 0.0}));
  // A segment of no length is its point (SOFA would divide by zero).
  const auto collapsed = min_proximity_line_point(V(1, 1, 1), V(1, 1, 1), V(1, 1, 2), kWide);
  ASSERT_TRUE(collapsed);
  EXPECT_EQ(collapsed->point[0], V(1, 1, 1));
}

TEST(MinProximity, LineLineMatchesTheCrossProductFormulaInsideAndRejectsEndsAndFarPairs) {
  std::mt19937 rng(2);
  int found = 0;
  for (int k = 0; k < 2000; ++k) {
    const V a = random_point(rng), b = random_point(rng), c = random_point(rng), e = random_point(rng);
    const auto out = min_proximity_line_line(a, b, c, e, kWide);
    const L d1 = wide(b) - wide(a), d2 = wide(e) - wide(c), w = wide(c) - wide(a), n = d1.cross(d2);
    const long double s = w.cross(d2).dot(n) / n.squaredNorm(), t = w.cross(d1).dot(n) / n.squaredNorm();
    const bool inside = s >= 1e-6L && s <= 0.999999L && t >= 1e-6L && t <= 0.999999L;
    if (std::abs(s - 1e-6L) < 1e-9L || std::abs(t - 1e-6L) < 1e-9L || std::abs(s - 0.999999L) < 1e-9L ||
        std::abs(t - 0.999999L) < 1e-9L) {
      continue;  // too near a threshold for the two formulas to agree on the side
    }
    ASSERT_EQ(out.has_value(), inside) << k;
    if (!out) continue;
    ++found;
    EXPECT_LT((wide(out->point[0]) - (wide(a) + d1 * s)).norm(), 1e-9L);
    EXPECT_LT((wide(out->point[1]) - (wide(c) + d2 * t)).norm(), 1e-9L);
  }
  EXPECT_GT(found, 50);
  // Parallel segments (|det| ≤ 1e-15): both midpoints, whatever their overlap.
  const auto parallel = min_proximity_line_line(V(0, 0, 0), V(1, 0, 0), V(5, 0.5, 0), V(7, 0.5, 0), kWide);
  ASSERT_TRUE(parallel);
  EXPECT_EQ(parallel->point[0], V(0.5, 0, 0));
  EXPECT_EQ(parallel->point[1], V(6, 0.5, 0));
}

// Whether p's projection lies strictly inside triangle (a, b, c) by at least `margin` of the
// barycentric range, and the projection (long double, along the unit normal).
struct Projection {
  L q;
  long double u, v, w;  // barycentric weights of a, b, c by sub-triangle areas
};
Projection project(const L& a, const L& b, const L& c, const L& p) {
  const L n = (b - a).cross(c - a);
  const long double area = n.norm();
  const L unit = n / area;
  Projection r;
  r.q = p - unit * (p - a).dot(unit);
  r.u = (b - r.q).cross(c - r.q).dot(unit) / area;
  r.v = (c - r.q).cross(a - r.q).dot(unit) / area;
  r.w = (a - r.q).cross(b - r.q).dot(unit) / area;
  return r;
}

TEST(MinProximity, TrianglePointKeepsOnlyProjectionsStrictlyInside) {
  std::mt19937 rng(3);
  int found = 0;
  for (int k = 0; k < 2000; ++k) {
    const V a = random_point(rng), b = random_point(rng), c = random_point(rng), p = random_point(rng);
    const Projection r = project(wide(a), wide(b), wide(c), wide(p));
    // SOFA's α is the weight of b, β of c; inside when α, β ≥ 1e-6 and α + β ≤ 0.999999.
    const long double alpha = r.v, beta = r.w;
    if (std::abs(alpha - 1e-6L) < 1e-9L || std::abs(beta - 1e-6L) < 1e-9L || std::abs(alpha + beta - 0.999999L) < 1e-9L) continue;
    const bool inside = alpha >= 1e-6L && beta >= 1e-6L && alpha + beta <= 0.999999L;
    const auto out = min_proximity_triangle_point(a, b, c, p, kWide);
    ASSERT_EQ(out.has_value(), inside) << k;
    if (!out) continue;
    ++found;
    EXPECT_LT((wide(out->point[0]) - r.q).norm(), 1e-9L);
    EXPECT_EQ(out->point[1], p);
    EXPECT_NEAR(out->value, static_cast<double>((wide(p) - r.q).norm()) - 0.25, 1e-9);
  }
  EXPECT_GT(found, 100);
  // useSurfaceNormals: the triangle's normal instead.
  const V n(0, 0, 1);
  const auto surface = min_proximity_triangle_point(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0.2, 0.2, -0.1), kWide, &n);
  ASSERT_TRUE(surface);
  EXPECT_EQ(surface->normal, n);
  // A point on an edge is not inside: SOFA's thresholds.
  EXPECT_FALSE(min_proximity_triangle_point(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0.5, 0, 0.1), kWide));
  EXPECT_TRUE(min_proximity_triangle_point(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0.5, 2e-6, 0.1), kWide));
}

TEST(MinProximity, DegenerateTrianglesAndZeroDistancesGiveNoNaN) {
  // Collinear corners: SOFA divides by a zero determinant; here no output, and the caller counts it.
  EXPECT_TRUE(degenerate_triangle(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)));
  EXPECT_FALSE(degenerate_triangle(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)));
  EXPECT_FALSE(min_proximity_triangle_point(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), V(1, 0.1, 0), kWide));
  EXPECT_FALSE(min_proximity_triangle_sphere(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), {V(1, 0.1, 0), 0.5, false}, kWide));
  // Two points at the same place: SOFA's normal (1, 0, 0), flagged.
  const auto same = min_proximity_point_point(V(1, 2, 3), V(1, 2, 3), kWide);
  ASSERT_TRUE(same);
  EXPECT_TRUE(same->null_distance);
  EXPECT_EQ(same->normal, V(1, 0, 0));
  EXPECT_EQ(same->value, -0.25);
  const auto spheres = min_proximity_sphere_sphere({V(0, 0, 0), 1, false}, {V(0, 0, 0), 1, false}, kWide);
  ASSERT_TRUE(spheres);
  EXPECT_TRUE(spheres->normal.allFinite());
}

TEST(MinProximity, SpheresAddTheirRadiiAndRigidOnesMeetOnTheirSurface) {
  // Two spheres of radii 1 and 0.5, centres 2 apart along x: value = 2 - 1.5 - C.
  const ProximityDistances<double> d{0.5, 0.1};
  const auto vec3 = min_proximity_sphere_sphere({V(0, 0, 0), 1, false}, {V(2, 0, 0), 0.5, false}, d);
  ASSERT_TRUE(vec3);
  EXPECT_NEAR(vec3->value, 2 - 1.5 - 0.1, 1e-15);
  EXPECT_EQ(vec3->point[0], V(0, 0, 0));  // a Vec3 sphere's point is its centre
  EXPECT_EQ(vec3->point[1], V(2, 0, 0));
  const auto rigid = min_proximity_sphere_sphere({V(0, 0, 0), 1, true}, {V(2, 0, 0), 0.5, true}, d);
  ASSERT_TRUE(rigid);
  EXPECT_EQ(rigid->point[0], V(1, 0, 0));  // surface points, facing each other
  EXPECT_EQ(rigid->point[1], V(1.5, 0, 0));
  // Alarm: r₁ + r₂ + A = 2, inclusive for sphere pairs (SOFA's DiscreteIntersection rule).
  EXPECT_TRUE(min_proximity_sphere_sphere({V(0, 0, 0), 1, false}, {V(2, 0, 0), 0.5, false}, d));
  EXPECT_FALSE(min_proximity_sphere_sphere({V(0, 0, 0), 1, false}, {V(2.01, 0, 0), 0.5, false}, d));
  // A rigid sphere of radius 2 above a triangle (SOFA's Triangle_test setting): on the face, the
  // sphere's point on its surface below the centre.
  const auto face = min_proximity_triangle_sphere(V(-1, -1, 0), V(1, -1, 0), V(0, 1, 0), {V(0, 0, 2.01), 2, true}, {1.0, 0.0});
  ASSERT_TRUE(face);
  EXPECT_LT((face->point[0] - V(0, 0, 0)).norm(), 1e-15);
  EXPECT_LT((face->point[1] - V(0, 0, 0.01)).norm(), 1e-15);
  EXPECT_LT((face->normal - V(0, 0, 1)).norm(), 1e-15);
  EXPECT_NEAR(face->value, 0.01, 1e-15);
  // Sphere first, point second: the rigid sphere's point faces the point.
  const auto point = min_proximity_sphere_point({V(0, 0, 0), 1, true}, V(0, 3, 0), {3.0, 0.0});
  ASSERT_TRUE(point);
  EXPECT_EQ(point->point[0], V(0, 1, 0));
  EXPECT_NEAR(point->value, 2.0, 1e-15);
}

TEST(MinProximity, LineSphereTakesSofasMirroredPoint) {
  // The sphere's centre projects at a quarter of the segment from a; SOFA's rule puts its point at
  // three quarters (its parameter is measured from b, its point taken from a).
  const auto out = min_proximity_line_sphere(V(0, 0, 0), V(4, 0, 0), {V(1, 1, 0), 0.5, false}, kWide);
  ASSERT_TRUE(out);
  EXPECT_LT((out->point[0] - V(3, 0, 0)).norm(), 1e-15);
  EXPECT_EQ(out->point[1], V(1, 1, 0));
  // Symmetric about the middle: the right point there.
  const auto middle = min_proximity_line_sphere(V(0, 0, 0), V(4, 0, 0), {V(2, 1, 0), 0.5, false}, kWide);
  ASSERT_TRUE(middle);
  EXPECT_LT((middle->point[0] - V(2, 0, 0)).norm(), 1e-15);
  // Beyond either end: nothing; a segment of no length: nothing.
  EXPECT_FALSE(min_proximity_line_sphere(V(0, 0, 0), V(4, 0, 0), {V(-1, 1, 0), 0.5, false}, kWide));
  EXPECT_FALSE(min_proximity_line_sphere(V(1, 1, 1), V(1, 1, 1), {V(1, 2, 1), 0.5, false}, kWide));
}

}  // namespace
}  // namespace fastcorot
