// LocalMinDistance's pair rules and cone filters against references written differently, in long
// double: feet of perpendiculars along unit directions, closest points of lines by the
// cross-product formulas, projections on triangles with sub-triangle areas, front sides and cones
// as angles (atan2); on thousands of random primitives, plus SOFA's thresholds at their boundaries,
// and hand-made meshes whose cones are known in closed form (a face, a regular tetrahedron's
// corner, a roof ridge, a flat and a boundary edge). SOFA's own LocalMinDistance_test only checks
// its four data names and no values; the settings' defaults are checked against
// LocalMinDistance.cpp's initData.
#include "fastcorot/collision/local_min_distance.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>

namespace fastcorot {
namespace {

using V = Vec3<double>;
using L = Eigen::Matrix<long double, 3, 1>;
using Settings = LocalMinDistanceSettings<double>;
using PointCone = LocalMinDistancePointCone<double>;
using LineCone = LocalMinDistanceLineCone<double>;

L wide(const V& v) {
  return v.cast<long double>();
}
V random_point(std::mt19937& rng, double scale = 1) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return V(u(rng), u(rng), u(rng));
}
bool near(long double x, long double threshold) {
  return std::abs(x - threshold) < 1e-9L;
}

const ProximityDistances<double> kWide{10.0, 0.25};
const Settings kSofa{};
Settings unfiltered() {
  Settings s;
  s.filter_intersection = false;
  return s;
}

TEST(LocalMinDistanceSettings, DefaultsAreSofasData) {
  // LocalMinDistance.cpp: filterIntersection true, angleCone 0.0, coneFactor 0.5, useLMDFilters
  // false.
  EXPECT_TRUE(kSofa.filter_intersection);
  EXPECT_EQ(kSofa.angle_cone, 0.0);
  EXPECT_EQ(kSofa.cone_factor, 0.5);
  EXPECT_FALSE(kSofa.use_lmd_filters);
}

TEST(LocalMinDistanceRules, LinePointKeepsOnlyFeetInsideTheSegment) {
  std::mt19937 rng(11);
  int found = 0, outside = 0;
  for (int k = 0; k < 4000; ++k) {
    const V a = random_point(rng), b = random_point(rng), p = random_point(rng);
    const L u = (wide(b) - wide(a)).normalized();
    const L q = wide(a) + u * u.dot(wide(p) - wide(a));
    const long double t = (q - wide(a)).dot(u) / (wide(b) - wide(a)).norm();
    if (near(t, 1e-6L) || near(t, 0.999999L)) continue;
    const auto out = local_min_distance_line_point(a, b, LineCone{}, p, nullptr, kWide, kSofa);
    ASSERT_EQ(out.has_value(), t >= 1e-6L && t <= 0.999999L) << k;
    if (!out) {
      ++outside;
      continue;
    }
    ++found;
    EXPECT_LT((wide(out->point[0]) - q).norm(), 1e-12L);
    EXPECT_EQ(out->point[1], p);
    EXPECT_NEAR(out->value, double((wide(p) - q).norm()) - 0.25, 1e-12);
    EXPECT_LT((wide(out->normal) - (wide(p) - q).normalized()).norm(), 1e-9L);
  }
  EXPECT_GT(found, 1000);
  EXPECT_GT(outside, 1000);
  // α = AP·AB / AB·AB exactly 1e-6 and 0.999999 are kept, the next doubles out are not.
  const V a(0, 0, 0), b(1, 0, 0);
  EXPECT_TRUE(
      local_min_distance_line_point(a, b, LineCone{}, V(1e-6, 0.5, 0), nullptr, kWide, kSofa));
  EXPECT_FALSE(local_min_distance_line_point(a, b, LineCone{}, V(std::nextafter(1e-6, 0.0), 0.5, 0),
                                             nullptr, kWide, kSofa));
  EXPECT_TRUE(
      local_min_distance_line_point(a, b, LineCone{}, V(0.999999, 0.5, 0), nullptr, kWide, kSofa));
  EXPECT_FALSE(local_min_distance_line_point(
      a, b, LineCone{}, V(std::nextafter(0.999999, 1.0), 0.5, 0), nullptr, kWide, kSofa));
  // MinProximity clamps to the end; LocalMinDistance has nothing beyond it.
  EXPECT_TRUE(min_proximity_line_point(a, b, V(1.5, 0.5, 0), kWide));
  EXPECT_FALSE(
      local_min_distance_line_point(a, b, LineCone{}, V(1.5, 0.5, 0), nullptr, kWide, kSofa));
  // Alarm exclusive; SOFA's guard |AB| < 1e-12 |AP|; a segment of no length.
  EXPECT_FALSE(
      local_min_distance_line_point(a, b, LineCone{}, V(0.5, 2, 0), nullptr, {2.0, 0.0}, kSofa));
  EXPECT_TRUE(local_min_distance_line_point(a, b, LineCone{}, V(0.5, 1.999, 0), nullptr, {2.0, 0.0},
                                            kSofa));
  EXPECT_FALSE(local_min_distance_line_point(a, V(1e-13, 0, 0), LineCone{}, V(5e-14, 1, 0), nullptr,
                                             kWide, kSofa));
  EXPECT_FALSE(local_min_distance_line_point(a, a, LineCone{}, a, nullptr, kWide, kSofa));
}

TEST(LocalMinDistanceRules, LineLineUsesItsOwnThresholdsAndTheLineFilterCatchesParallelPairs) {
  std::mt19937 rng(12);
  int found = 0;
  for (int k = 0; k < 4000; ++k) {
    const V a = random_point(rng), b = random_point(rng), c = random_point(rng),
            e = random_point(rng);
    const L d1 = wide(b) - wide(a), d2 = wide(e) - wide(c), w = wide(c) - wide(a), n = d1.cross(d2);
    const long double s = w.cross(d2).dot(n) / n.squaredNorm(),
                      t = w.cross(d1).dot(n) / n.squaredNorm();
    if (near(s, 1e-15L) || near(t, 1e-15L) || near(s, 1 - 1e-15L) || near(t, 1 - 1e-15L)) continue;
    const bool inside = s >= 1e-15L && s <= 1 - 1e-15L && t >= 1e-15L && t <= 1 - 1e-15L;
    const auto out = local_min_distance_line_line(a, b, LineCone{}, c, e, LineCone{}, kWide, kSofa);
    ASSERT_EQ(out.has_value(), inside) << k;
    if (!out) continue;
    ++found;
    const L p = wide(a) + d1 * s, q = wide(c) + d2 * t;
    EXPECT_LT((wide(out->point[0]) - p).norm(), 1e-9L);
    EXPECT_LT((wide(out->point[1]) - q).norm(), 1e-9L);
    EXPECT_NEAR(out->value, double((q - p).norm()) - 0.25, 1e-9);
  }
  EXPECT_GT(found, 500);
  // Crossing segments built so that α = t exactly: 1e-15 and 1 − 1e-15 kept, the next doubles out
  // not.
  const auto cross_at = [&](double t) {
    return local_min_distance_line_line(V(0, 0, 0), V(1, 0, 0), LineCone{}, V(t, -1, 1), V(t, 1, 1),
                                        LineCone{}, kWide, kSofa);
  };
  EXPECT_TRUE(cross_at(1e-15));
  EXPECT_FALSE(cross_at(std::nextafter(1e-15, 0.0)));
  EXPECT_TRUE(cross_at(1.0 - 1e-15));
  EXPECT_FALSE(cross_at(std::nextafter(1.0 - 1e-15, 2.0)));
  EXPECT_TRUE(cross_at(1e-7));  // MinProximity's [1e-6, 0.999999] would reject it
  EXPECT_FALSE(
      min_proximity_line_line(V(0, 0, 0), V(1, 0, 0), V(1e-7, -1, 1), V(1e-7, 1, 1), kWide));
  // det = |AB × CD|² = s⁴: s = 1e-8 is parallel (≤ 1e-30), the midpoints; s = 1e-7 is not.
  const double s8 = 1e-8, s7 = 1e-7;
  const auto parallel =
      local_min_distance_line_line(V(0, 0, 0), V(s8, 0, 0), LineCone{}, V(0, -s8 / 2, 1),
                                   V(0, s8 / 2, 1), LineCone{}, kWide, kSofa);
  ASSERT_TRUE(parallel);
  EXPECT_EQ(parallel->point[0], V(s8 / 2, 0, 0));
  EXPECT_EQ(parallel->point[1], V(0, 0, 1));
  EXPECT_FALSE(local_min_distance_line_line(V(0, 0, 0), V(s7, 0, 0), LineCone{}, V(0, -s7 / 2, 1),
                                            V(0, s7 / 2, 1), LineCone{}, kWide,
                                            kSofa));  // α = 0
  // Parallel segments side by side: midpoints along the segments, so the segment filter (no two
  // triangles: |u·v̂| ≤ 1e-4) rejects it; unfiltered (and under MinProximity) it is a contact.
  const V a(0, 0, 0), b(1, 0, 0), c(5, 0.5, 0), e(7, 0.5, 0);
  EXPECT_FALSE(local_min_distance_line_line(a, b, LineCone{}, c, e, LineCone{}, kWide, kSofa));
  EXPECT_TRUE(
      local_min_distance_line_line(a, b, LineCone{}, c, e, LineCone{}, kWide, unfiltered()));
  EXPECT_TRUE(min_proximity_line_line(a, b, c, e, kWide));
  EXPECT_FALSE(local_min_distance_line_line(a, a, LineCone{}, c, e, LineCone{}, kWide,
                                            unfiltered()));  // no length
}

struct Projection {
  L q;
  long double alpha, beta;  // weights of b and c by sub-triangle areas
};
Projection project(const L& a, const L& b, const L& c, const L& p) {
  const L n = (b - a).cross(c - a), unit = n / n.norm();
  Projection r;
  r.q = p - unit * (p - a).dot(unit);
  r.alpha = (c - r.q).cross(a - r.q).dot(unit) / n.norm();
  r.beta = (a - r.q).cross(b - r.q).dot(unit) / n.norm();
  return r;
}

TEST(LocalMinDistanceRules, TrianglePointAndSphereKeepInsideAndFrontOnly) {
  std::mt19937 rng(13);
  int front = 0, behind = 0;
  for (int k = 0; k < 4000; ++k) {
    const V a = random_point(rng), b = random_point(rng), c = random_point(rng),
            p = random_point(rng);
    const Projection r = project(wide(a), wide(b), wide(c), wide(p));
    if (near(r.alpha, 1e-6L) || near(r.beta, 1e-6L) || near(r.alpha + r.beta, 0.999999L)) continue;
    const bool inside = r.alpha >= 1e-6L && r.beta >= 1e-6L && r.alpha + r.beta <= 0.999999L;
    // Front: p on the side of (b − a) × (c − b), the same normal written from another corner.
    const long double side = (wide(p) - r.q).dot((wide(b) - wide(a)).cross(wide(c) - wide(b)));
    const auto out = local_min_distance_triangle_point(a, b, c, false, p, nullptr, kWide, kSofa);
    ASSERT_EQ(out.has_value(), inside && side >= 0) << k;
    ASSERT_EQ(
        local_min_distance_triangle_point(a, b, c, true, p, nullptr, kWide, kSofa).has_value(),
        inside)
        << k;  // bothSide
    const ProximitySphere<double> sphere{p, 0.1, false};
    const auto ball = local_min_distance_triangle_sphere(a, b, c, false, sphere, kWide, kSofa);
    ASSERT_EQ(ball.has_value(), inside && side >= 0) << k;
    if (!out) {
      behind += inside;
      continue;
    }
    ++front;
    EXPECT_LT((wide(out->point[0]) - r.q).norm(), 1e-9L);
    EXPECT_EQ(out->point[1], p);
    EXPECT_NEAR(out->value, double((wide(p) - r.q).norm()) - 0.25, 1e-9);
    EXPECT_EQ(ball->point[1], p);  // a Vec3 sphere's point is its centre; its radius joins C
    EXPECT_NEAR(ball->value, out->value - 0.1, 1e-12);
  }
  EXPECT_GT(front, 200);
  EXPECT_GT(behind, 200);
  // α, β from Cramer's rule on the unit right triangle are the coordinates themselves.
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(
      local_min_distance_triangle_point(a, b, c, false, V(1e-6, 0.3, 0.1), nullptr, kWide, kSofa));
  EXPECT_FALSE(local_min_distance_triangle_point(
      a, b, c, false, V(std::nextafter(1e-6, 0.0), 0.3, 0.1), nullptr, kWide, kSofa));
  ASSERT_EQ(0.25 + 0.749999, 0.999999);
  EXPECT_TRUE(local_min_distance_triangle_point(a, b, c, false, V(0.25, 0.749999, 0.1), nullptr,
                                                kWide, kSofa));
  EXPECT_FALSE(local_min_distance_triangle_point(
      a, b, c, false, V(0.25, std::nextafter(0.749999, 1.0), 0.1), nullptr, kWide, kSofa));
}

TEST(LocalMinDistanceRules, SpheresAddTheirRadiiAndLineSphereTakesTheTrueFoot) {
  const ProximityDistances<double> d{0.5, 0.1};
  // Sphere–Sphere: centres 2 apart, radii 1 and 0.5; A + r₁ + r₂ = 2 is exclusive here
  // (MinProximity keeps it).
  EXPECT_FALSE(local_min_distance_sphere_sphere<double>({V(0, 0, 0), 1, false},
                                                        {V(2, 0, 0), 0.5, false}, d));
  EXPECT_TRUE(
      min_proximity_sphere_sphere<double>({V(0, 0, 0), 1, false}, {V(2, 0, 0), 0.5, false}, d));
  const auto spheres = local_min_distance_sphere_sphere<double>({V(0, 0, 0), 1, false},
                                                                {V(1.9, 0, 0), 0.5, false}, d);
  ASSERT_TRUE(spheres);
  EXPECT_EQ(spheres->point[0], V(0, 0, 0));
  EXPECT_EQ(spheres->point[1], V(1.9, 0, 0));
  EXPECT_NEAR(spheres->value, 1.9 - 1.5 - 0.1, 1e-15);
  // Sphere–Point: the centre first.
  const auto point = local_min_distance_sphere_point<double>({V(0, 0, 0), 1, false}, V(0, 1.2, 0),
                                                             nullptr, d, kSofa);
  ASSERT_TRUE(point);
  EXPECT_EQ(point->normal, V(0, 1, 0));
  EXPECT_NEAR(point->value, 1.2 - 1.1, 1e-15);
  // Line–Sphere: the centre projects at a quarter of the segment, and the point is there
  // (MinProximity: three quarters).
  const auto line = local_min_distance_line_sphere<double>(V(0, 0, 0), V(4, 0, 0), LineCone{},
                                                           {V(1, 1, 0), 0.5, false}, kWide, kSofa);
  ASSERT_TRUE(line);
  EXPECT_EQ(line->point[0], V(1, 0, 0));
  EXPECT_EQ(line->point[1], V(1, 1, 0));
  EXPECT_NEAR(line->value, 1 - 0.75, 1e-15);
  const auto mirrored =
      min_proximity_line_sphere<double>(V(0, 0, 0), V(4, 0, 0), {V(1, 1, 0), 0.5, false}, kWide);
  ASSERT_TRUE(mirrored);
  EXPECT_EQ(mirrored->point[0], V(3, 0, 0));
  // Rigid spheres have no LocalMinDistance rule in SOFA.
  EXPECT_THROW(
      local_min_distance_sphere_sphere<double>({V(0, 0, 0), 1, true}, {V(1, 0, 0), 1, false}, d),
      Error);
}

TEST(LocalMinDistanceRules, ZeroDistancesAndDegenerateElementsGiveNoNaN) {
  // SOFA divides by the zero distance; here the triangle's normal, or (1, 0, 0), flagged.
  const auto on_face = local_min_distance_triangle_point(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), false,
                                                         V(0.2, 0.2, 0), nullptr, kWide, kSofa);
  ASSERT_TRUE(on_face);
  EXPECT_TRUE(on_face->null_distance);
  EXPECT_EQ(on_face->normal, V(0, 0, 1));
  EXPECT_EQ(on_face->value, -0.25);
  const auto same = local_min_distance_point_point<double>(V(1, 2, 3), nullptr, V(1, 2, 3), nullptr,
                                                           kWide, kSofa);
  ASSERT_TRUE(same);
  EXPECT_EQ(same->normal, V(1, 0, 0));
  // Collinear corners: no output (SOFA's NaN barycentrics).
  EXPECT_FALSE(local_min_distance_triangle_point(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), true,
                                                 V(1, 0.1, 0), nullptr, kWide, unfiltered()));
  EXPECT_FALSE(local_min_distance_triangle_sphere<double>(
      V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), true, {V(1, 0.1, 0), 0.5, false}, kWide, unfiltered()));
}

// A mesh and its neighbourhood at its positions.
struct Mesh {
  Mesh() = default;
  Mesh(std::vector<V> points, std::vector<Triangle> faces, std::vector<Edge> lines)
      : x(std::move(points)), triangles(std::move(faces)), edges(std::move(lines)) {
    build();
  }
  std::vector<V> x;
  std::vector<Triangle> triangles;
  std::vector<Edge> edges;
  LocalMinDistanceTopology topology;
  LocalMinDistanceNeighbourhood<double> cones;
  void build() {
    topology = local_min_distance_topology(Index(x.size()), triangles, edges);
    compute_local_min_distance_neighbourhood<double>(topology, x, cones);
  }
};

TEST(LocalMinDistanceCones, PointBehindAFaceIsRejectedInFrontKept) {
  // A square of two triangles facing +z; a point below or above the first one.
  Mesh m{{V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)},
         {{0, 1, 2}, {0, 2, 3}},
         {{0, 1}, {1, 2}, {2, 0}, {2, 3}, {3, 0}}};
  const auto test = [&](double z, bool both_side, const Settings& s) {
    return local_min_distance_triangle_point(m.x[0], m.x[1], m.x[2], both_side, V(0.6, 0.3, z),
                                             nullptr, kWide, s)
        .has_value();
  };
  EXPECT_TRUE(test(0.2, false, kSofa));
  EXPECT_FALSE(test(-0.2, false, kSofa));
  EXPECT_TRUE(test(-0.2, true, kSofa));          // the triangle model's bothSide
  EXPECT_TRUE(test(-0.2, false, unfiltered()));  // filterIntersection = false
  Settings skip;
  skip.use_lmd_filters = true;
  EXPECT_TRUE(test(-0.2, false, skip));
  // The square's corner 1 (one triangle, normal +z) against a point above and below it.
  const PointCone corner = m.cones.point_cone(1);
  const auto pair = [&](const V& q, const Settings& s) {
    return local_min_distance_point_point(m.x[1], &corner, q, nullptr, kWide, s).has_value();
  };
  EXPECT_TRUE(pair(V(1.05, -0.05, 0.3), kSofa));
  EXPECT_FALSE(pair(V(1.05, -0.05, -0.3), kSofa));
  EXPECT_TRUE(pair(V(1.05, -0.05, -0.3), unfiltered()));
  EXPECT_TRUE(local_min_distance_point_point<double>(m.x[1], nullptr, V(1.05, -0.05, -0.3), nullptr,
                                                     kWide, kSofa));  // no LineModel
}

TEST(LocalMinDistanceCones, ConvexCornerKeepsItsConeAndRejectsOutside) {
  // A regular tetrahedron about the origin, faces outward; corner 0 = (1, 1, 1): nMean = (1, 1,
  // 1)/√3 by symmetry, edges e_k = unit(x₀ − x_k) with nMean·e_k = √(2/3).
  Mesh m{{V(1, 1, 1), V(1, -1, -1), V(-1, 1, -1), V(-1, -1, 1)},
         {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}},
         {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
  const V n = V(1, 1, 1).normalized();
  EXPECT_LT((m.cones.normal_sum[0].normalized() - n).norm(), 1e-15);
  const V e1 = V(0, 1, 1).normalized();
  const V w = (e1 - n * n.dot(e1)).normalized();  // e₁'s part across nMean: e₁·(−w) = −1/√3
  const PointCone cone = m.cones.point_cone(0);
  const auto kept = [&](const V& v, const Settings& s, const PointCone& c) {
    return local_min_distance_point_point(m.x[0], &c, V(m.x[0] + 0.1 * v), nullptr, kWide, s)
        .has_value();
  };
  EXPECT_TRUE(kept(n, kSofa, cone));
  EXPECT_TRUE(kept(V(n + 0.5 * w), kSofa, cone));
  // v = −w + 0.05 n: nMean·v > 0, e₁·v = −0.577 + 0.041 below −coneFactor √(2/3) = −0.408:
  // rejected; with coneFactor 1 (−0.816) kept, as unfiltered.
  const V outside = -w + 0.05 * n;
  EXPECT_FALSE(kept(outside, kSofa, cone));
  Settings wide_cone;
  wide_cone.cone_factor = 1;
  EXPECT_TRUE(kept(outside, wide_cone, cone));
  EXPECT_TRUE(kept(outside, unfiltered(), cone));
  // angleCone adds to every edge's cone: 0.408 + 0.15 > 0.536.
  Settings angle;
  angle.angle_cone = 0.15;
  EXPECT_TRUE(kept(outside, angle, cone));
  // From behind: rejected; bothSide skips only the nMean test, the edges still reject it (e·(−n) =
  // −0.816).
  EXPECT_FALSE(kept(-n, kSofa, cone));
  EXPECT_FALSE(kept(-n, kSofa, m.cones.point_cone(0, true)));
  EXPECT_TRUE(kept(-n, unfiltered(), cone));
  // No LineCollisionModel near the point model: no cone at all.
  EXPECT_TRUE(local_min_distance_point_point<double>(m.x[0], nullptr, V(m.x[0] - 0.1 * n), nullptr,
                                                     kWide, kSofa));
}

TEST(LocalMinDistanceCones, SegmentConesOfARidgeAFlatEdgeAndABoundaryEdge) {
  // Edge (0, 1) along x; the left triangle lists 0→1, the right one 1→0. h > 0: a convex ridge
  // whose faces lean by atan(h); nMean = +z, t_left = (0, −1, h)/√(1+h²), t_right = (0, 1,
  // h)/√(1+h²), each widened by coneFactor nMean·t = 0.5 h/√(1+h²).
  const auto ridge = [](double h, bool left_first) {
    return Mesh({V(0, 0, 0), V(1, 0, 0), V(0.5, 1, -h), V(0.5, -1, -h)},
                left_first ? std::vector<Triangle>{{0, 1, 2}, {1, 0, 3}}
                           : std::vector<Triangle>{{1, 0, 3}, {0, 1, 2}},
                {{0, 1}, {0, 2}, {1, 2}, {0, 3}, {1, 3}});
  };
  const auto kept = [](const Mesh& m, double phi, const Settings& s = kSofa) {
    const V v(0, std::sin(phi), std::cos(phi));  // tilted from +z toward +y (the left side)
    return local_min_distance_line_validity(m.x[0], m.x[1], m.cones.line_cone(0), v, s);
  };
  const double deg = std::acos(-1.0) / 180;
  for (bool left_first : {true, false}) {
    const Mesh m = ridge(0.5, left_first);
    EXPECT_EQ(m.topology.edge_right_left[0],
              (left_first ? std::array<Index, 2>{1, 0} : std::array<Index, 2>{0, 1}));
    // t_left·v = (−sin φ + h cos φ)/√(1+h²) ≥ −0.5 h/√(1+h²) while sin φ − h cos φ ≤ h/2, i.e.
    // φ ≤ atan h + asin(h/2/√(1+h²)) = 39.486° for h = 0.5 (the faces' own normals lean by 26.57°).
    const double limit = std::atan(0.5) + std::asin(0.25 / std::sqrt(1.25));
    EXPECT_TRUE(kept(m, 0));
    EXPECT_TRUE(kept(m, limit - 0.2 * deg));
    EXPECT_FALSE(kept(m, limit + 0.2 * deg));
    EXPECT_TRUE(kept(m, -limit + 0.2 * deg));
    EXPECT_FALSE(kept(m, -limit - 0.2 * deg));
    EXPECT_FALSE(kept(m, 180 * deg));
    EXPECT_TRUE(kept(m, 180 * deg, unfiltered()));
  }
  // Two triangles both running along edge (0, 1) (an inconsistent mesh): SOFA's list puts the
  // later one first (MeshTopology::createTrianglesAroundEdgeArray inserts such triangles in
  // front), so LocalMinDistance takes triangle 1 as left and triangle 0 as right.
  const Mesh folded({V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(0.5, -1, 0)}, {{0, 1, 2}, {0, 1, 3}},
                    {{0, 1}, {1, 2}, {2, 0}, {1, 3}, {3, 0}});
  EXPECT_EQ(folded.topology.edge_right_left[0], (std::array<Index, 2>{0, 1}));
  // Both running against it: kept in order, the first is right.
  const Mesh against({V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(0.5, -1, 0)}, {{1, 0, 2}, {1, 0, 3}},
                     {{0, 1}, {1, 2}, {2, 0}, {1, 3}, {3, 0}});
  EXPECT_EQ(against.topology.edge_right_left[0], (std::array<Index, 2>{0, 1}));
  // Flat (h = 0): t = ±y and no widening, so only v exactly along the normal is kept.
  const Mesh flat = ridge(0, true);
  EXPECT_TRUE(kept(flat, 0));
  EXPECT_FALSE(kept(flat, 1e-3));
  EXPECT_FALSE(kept(flat, -1e-3));
  // A boundary edge (one triangle): any side, as long as |u·v̂| ≤ 1e-4.
  const Mesh boundary({V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0)}, {{0, 1, 2}},
                      {{0, 1}, {1, 2}, {2, 0}});
  const LineCone one = boundary.cones.line_cone(0);
  EXPECT_FALSE(one.two_triangles);
  EXPECT_TRUE(
      local_min_distance_line_validity(boundary.x[0], boundary.x[1], one, V(0, 0, -1), kSofa));
  EXPECT_TRUE(
      local_min_distance_line_validity(boundary.x[0], boundary.x[1], one, V(0.99e-4, 0, 1), kSofa));
  EXPECT_FALSE(
      local_min_distance_line_validity(boundary.x[0], boundary.x[1], one, V(1.01e-4, 0, 1), kSofa));
  // Through Line–Point: a point below the ridge is rejected by the segment's cone; bothSide skips
  // only the nMean test, so below a ridge the tangents still reject it (t·(−z) = −0.447 < −0.224),
  // below a flat edge (t·(−z) = 0) it is kept.
  const Mesh m = ridge(0.5, true);
  const auto line_point = [](const Mesh& mesh, bool both_side, double z) {
    return local_min_distance_line_point(mesh.x[0], mesh.x[1], mesh.cones.line_cone(0, both_side),
                                         V(0.5, 0, z), nullptr, kWide, kSofa)
        .has_value();
  };
  EXPECT_TRUE(line_point(m, false, 0.3));
  EXPECT_FALSE(line_point(m, false, -0.3));
  EXPECT_FALSE(line_point(m, true, -0.3));
  EXPECT_FALSE(line_point(flat, false, -0.3));
  EXPECT_TRUE(line_point(flat, true, -0.3));
}

}  // namespace
}  // namespace fastcorot
