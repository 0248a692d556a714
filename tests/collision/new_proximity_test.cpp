// NewProximityIntersection's rules and SOFA's ownership flags. References written differently, in
// long double: a triangle's closest point as the best of the in-plane projection (inside by
// sub-triangle areas) and the three edges' clamped closest points, a segment's by golden-section
// search, two lines' by cross products. Flags against hand-worked meshes and "each vertex and edge
// owned once" on closed and open meshes; element pairs against outputs worked out by hand; SOFA's
// MeshNewProximityIntersection_test configurations.
#include "fastcorot/collision/new_proximity.h"
#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <map>
#include <cmath>
#include <random>

namespace fastcorot {
namespace {

using V = Vec3<double>;
using L = Eigen::Matrix<long double, 3, 1>;
using F = TriangleFlag;

L wide(const V& v) { return v.cast<long double>(); }

V random_point(std::mt19937& rng, double scale = 1) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return V(u(rng), u(rng), u(rng));
}

// ---- Flags --------------------------------------------------------------------------------------

// How many triangles own each vertex and each (unordered) edge.
void expect_each_owned_once(const std::vector<Triangle>& triangles, std::size_t points, const std::vector<int>& flags) {
  std::vector<int> vertex(points, 0);
  std::map<std::pair<Index, Index>, int> edge;
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int j = 0; j < 3; ++j) {
      const Index a = triangles[i][(j + 1) % 3], b = triangles[i][(j + 2) % 3];
      int& owners = edge[{std::min(a, b), std::max(a, b)}];
      if (flags[i] & (F::P1 << j)) ++vertex[triangles[i][j]];
      if (flags[i] & (F::E23 << j)) ++owners;
    }
  for (std::size_t v = 0; v < points; ++v) EXPECT_EQ(vertex[v], 1) << "vertex " << v;
  for (const auto& [e, owners] : edge) EXPECT_EQ(owners, 1) << "edge " << e.first << "-" << e.second;
}

// A tetrahedron's four faces, outward: (0,1,2), (0,3,1), (1,3,2), (0,2,3).
const std::vector<Triangle> kTetrahedron = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {0, 2, 3}};

TEST(NewProximityFlags, TetrahedronFacesOwnEachVertexAndEdgeOnce) {
  const auto flags = triangle_flags(kTetrahedron, 4);
  // By hand: edges derived in the direction of their first face, so each belongs to the first face
  // that has it. Face 0 owns all; face 1 vertex 3 (its 2nd) and edges 3-1 (2-3) and 0-3 (1-2);
  // face 2 edge 3-2 (2-3); face 3 nothing. No edge has a single face.
  EXPECT_EQ(flags, (std::vector<int>{F::points | F::edges, F::P2 | F::E23 | F::E12, F::E23, 0}));
  expect_each_owned_once(kTetrahedron, 4, flags);
}

TEST(NewProximityFlags, StoredEdgeDirectionsDecideEdgeOwners) {
  // The same faces with edges stored (min, max), as a MeshTopology over tetrahedra stores them: a
  // face along the stored direction goes to the front of the edge's list. By hand: 0-1 → face 0,
  // 1-2 → 0, 0-2 → 3 (runs 0→2; face 0 runs 2→0), 0-3 → 1, 1-3 → 2, 2-3 → 3.
  const std::vector<Edge> sorted = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  const auto flags = triangle_flags(kTetrahedron, 4, sorted);
  EXPECT_EQ(flags, (std::vector<int>{F::points | F::E12 | F::E23, F::P2 | F::E12, F::E12, F::E23 | F::E12}));
  expect_each_owned_once(kTetrahedron, 4, flags);
}

TEST(NewProximityFlags, InconsistentOrientationGivesTheEdgeToTheLaterTriangle) {
  // Both triangles run 0→1: the second goes to the front of that edge's list and owns it.
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 1, 3}};
  const auto flags = triangle_flags(triangles, 4);
  EXPECT_EQ(flags[0], F::points | F::E23 | F::E31 | F::BE23 | F::BE31);
  EXPECT_EQ(flags[1], F::P3 | F::edges | F::BE23 | F::BE31);
}

TEST(NewProximityFlags, QuadGridOwnsOnceAndMarksItsBoundary) {
  // A 2×2 grid of quads on 3×3 points, each quad (a, b, c, d) split into (a, b, c) and (a, c, d).
  std::vector<Triangle> triangles;
  for (Index y = 0; y < 2; ++y)
    for (Index x = 0; x < 2; ++x) {
      const Index a = 3 * y + x, b = a + 1, c = a + 4, d = a + 3;
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    }
  const auto flags = triangle_flags(triangles, 9);
  expect_each_owned_once(triangles, 9, flags);
  int boundary = 0;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    boundary += std::popcount(unsigned(flags[i] & F::boundary_edges));
    // A consistently oriented mesh: the owner of a vertex or an edge is its first triangle.
    for (int j = 0; j < 3; ++j) {
      std::size_t first = triangles.size();
      for (std::size_t k = 0; k < triangles.size() && first == triangles.size(); ++k)
        if (std::count(triangles[k].begin(), triangles[k].end(), triangles[i][j])) first = k;
      EXPECT_EQ(bool(flags[i] & (F::P1 << j)), first == i) << i << " " << j;
    }
  }
  EXPECT_EQ(boundary, 8);  // the grid's outline
}

TEST(NewProximityFlags, LinesOwnTheirVerticesInEdgeOrder) {
  // 0-1-2 with a branch 1-3: edge 0 owns 0 and 1; edges 1 and 2 only their far ends.
  const std::vector<Edge> edges = {{0, 1}, {1, 2}, {1, 3}};
  EXPECT_EQ(line_flags(edges, 4), (std::vector<int>{LineFlag::P1 | LineFlag::P2 | LineFlag::BP1, LineFlag::P2 | LineFlag::BP2,
                                                     LineFlag::P2 | LineFlag::BP2}));
}

TEST(NewProximityFlags, BadTopologiesAreErrors) {
  EXPECT_THROW(triangle_flags(std::vector<Triangle>{{0, 1, 4}}, 4), Error);
  EXPECT_THROW(triangle_flags(std::vector<Triangle>{{0, 1, 2}}, 3, std::vector<Edge>{{0, 1}, {1, 2}}), Error);
  EXPECT_THROW(line_flags(std::vector<Edge>{{0, 3}}, 3), Error);
}

// ---- Elementary rules ------------------------------------------------------------------------------

// Feature of a triangle's closest point: interior, a corner or an edge.
enum Feature { kInterior, kA, kB, kC, kAB, kAC, kBC };

struct Closest {
  L point;
  Feature feature;
  long double margin;  // distance to the nearest boundary between features, in barycentric units
};

// The closest point of triangle (a, b, c) to q: the in-plane projection when its sub-triangle
// areas are all positive, else the nearest of the three edges' clamped closest points.
Closest closest_on_triangle(const L& a, const L& b, const L& c, const L& q) {
  const L n = (b - a).cross(c - a);
  const L unit = n / n.norm();
  const L r = q - unit * (q - a).dot(unit);
  const long double u = (b - r).cross(c - r).dot(unit) / n.norm(), v = (c - r).cross(a - r).dot(unit) / n.norm(),
                    w = (a - r).cross(b - r).dot(unit) / n.norm();
  long double margin = std::min({std::abs(u), std::abs(v), std::abs(w)});
  if (std::min({u, v, w}) > 0) return {r, kInterior, margin};
  const L ends[3][2] = {{a, b}, {a, c}, {b, c}};
  const Feature edge[3] = {kAB, kAC, kBC}, start[3] = {kA, kA, kB}, finish[3] = {kB, kC, kC};
  Closest best{L::Zero(), kInterior, 0};
  long double best_distance = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const L d = ends[k][1] - ends[k][0];
    const long double s = (q - ends[k][0]).dot(d) / d.squaredNorm();
    margin = std::min({margin, std::abs(s), std::abs(1 - s)});
    const long double t = std::clamp(s, 0.0L, 1.0L);
    const L p = ends[k][0] + d * t;
    if ((q - p).norm() < best_distance) {
      best_distance = (q - p).norm();
      best = {p, t == 0 ? start[k] : t == 1 ? finish[k] : edge[k], 0};
    }
  }
  best.margin = margin;
  return best;
}

// Which flag SOFA's triangle–point rule needs for each feature (interior: none).
int needed_flag(Feature f) {
  constexpr int flag[] = {0, F::P1, F::P2, F::P3, F::E12, F::E31, F::E23};
  return flag[f];
}

// A point near a random feature of triangle (a, b, c), or anywhere.
V near_triangle(std::mt19937& rng, const V& a, const V& b, const V& c) {
  std::uniform_real_distribution<double> u(0, 1);
  const V corners[3] = {a, b, c};
  switch (rng() % 4) {
    case 0: return random_point(rng, 1.5);
    case 1: return corners[rng() % 3] + random_point(rng, 0.1);
    case 2: {
      const int k = rng() % 3;
      return corners[k] + (corners[(k + 1) % 3] - corners[k]) * u(rng) + random_point(rng, 0.1);
    }
    default: {
      const double s = u(rng), t = u(rng) * (1 - s);
      return a + (b - a) * s + (c - a) * t + (b - a).cross(c - a).normalized() * (u(rng) - 0.5);
    }
  }
}

bool well_shaped(const V& a, const V& b, const V& c) {
  return (b - a).cross(c - a).squaredNorm() > 1e-2 * (b - a).squaredNorm() * (c - a).squaredNorm();
}

TEST(NewProximityRules, TrianglePointIsTheClosestPointWhereTheTriangleOwnsIt) {
  std::mt19937 rng(11);
  const ProximityDistances<double> d{0.8, 0.05};
  int found = 0, refused = 0, far = 0;
  for (int k = 0; k < 6000; ++k) {
    const V a = random_point(rng), b = random_point(rng), c = random_point(rng);
    if (!well_shaped(a, b, c)) continue;
    const V q = near_triangle(rng, a, b, c);
    const int flags = int(rng() % 64);
    const Closest ref = closest_on_triangle(wide(a), wide(b), wide(c), wide(q));
    const long double distance = (wide(q) - ref.point).norm();
    if (ref.margin < 1e-7L || std::abs(distance - 0.8L) < 1e-9L) continue;  // too near a boundary to tell
    const bool owned = (flags & needed_flag(ref.feature)) == needed_flag(ref.feature);
    const auto out = new_proximity_triangle_point(a, b, c, q, flags, d);
    ASSERT_EQ(out.has_value(), owned && distance < 0.8L) << k << " feature " << ref.feature;
    if (!out) {
      refused += !owned;
      far += owned;
      continue;
    }
    ++found;
    EXPECT_LT((wide(out->point[0]) - ref.point).norm(), 1e-9L) << k << " feature " << ref.feature;
    EXPECT_EQ(out->point[1], q);
    EXPECT_NEAR(out->value, double(distance) - 0.05, 1e-9);
    EXPECT_LT((wide(out->normal) - (wide(q) - ref.point) / distance).norm(), 1e-7L);
    // Swapped (SOFA's swapElems): the point first, the normal reversed, the same value.
    const auto swapped = new_proximity_triangle_point(a, b, c, q, flags, d, true);
    ASSERT_TRUE(swapped);
    EXPECT_EQ(swapped->point[0], q);
    EXPECT_EQ(swapped->point[1], out->point[0]);
    EXPECT_EQ(swapped->normal, V(-out->normal));
    EXPECT_EQ(swapped->value, out->value);
  }
  EXPECT_GT(found, 1000);
  EXPECT_GT(refused, 500);
  EXPECT_GT(far, 200);
}

TEST(NewProximityRules, TrianglePointReproducesSofasUnitTest) {
  // MeshNewProximityIntersection_test (pointTriangle): random triangles in [0,1)³, all flags set,
  // dist2 = 0.1 (A = √0.1); points up to 0.1 off the face, a corner or an edge's middle are found.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0, 1);
  const ProximityDistances<double> d{std::sqrt(0.1), 0};
  for (int i = 0; i < 1000; ++i) {
    const V p[3] = {V(u(rng), u(rng), u(rng)), V(u(rng), u(rng), u(rng)), V(u(rng), u(rng), u(rng))};
    if (degenerate_triangle(p[0], p[1], p[2])) continue;
    const V n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    double s = u(rng), t = u(rng);
    const double sum = s + t;
    s /= sum;
    t /= sum;
    const double dist = (2 * u(rng) - 1) * 0.1;
    const V pc = p[0] + (p[1] - p[0]) * s + (p[2] - p[0]) * t;
    const auto inside = new_proximity_triangle_point(p[0], p[1], p[2], V(pc + n * dist), 0xffff, d, true);
    ASSERT_TRUE(inside) << i;
    EXPECT_LT((inside->point[1] - pc).norm(), 1e-6);
    const V n2 = V(u(rng), u(rng), u(rng)).normalized();
    for (int j = 0; j < 3; ++j) {
      EXPECT_TRUE(new_proximity_triangle_point(p[0], p[1], p[2], V(p[j] + n2 * dist), 0xffff, d)) << i;
      const V middle = (p[j] + p[(j + 1) % 3]) * 0.5;
      EXPECT_TRUE(new_proximity_triangle_point(p[0], p[1], p[2], V(middle + n2 * dist), 0xffff, d)) << i;
    }
  }
  // Its triangle with an angle over 90°: points at barycentric (−2, 0) and (0, −2) are not found.
  const V a(0, 0, 0), b(-0.1, 1, 0), c(1, 0, 0);
  EXPECT_FALSE(new_proximity_triangle_point(a, b, c, V(a - 2 * (b - a)), 0xffff, d));
  EXPECT_FALSE(new_proximity_triangle_point(a, b, c, V(a - 2 * (c - a)), 0xffff, d));
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

TEST(NewProximityRules, LinePointIsClampedToTheEnds) {
  std::mt19937 rng(13);
  const ProximityDistances<double> d{0.9, 0.1};
  int found = 0;
  for (int k = 0; k < 3000; ++k) {
    const V a = random_point(rng), b = random_point(rng);
    const V p = k % 2 ? random_point(rng, 1.5) : V((k % 4 ? a : b) + random_point(rng, 0.2));
    const long double t = segment_parameter(wide(a), wide(b), wide(p));
    const L q = wide(a) + (wide(b) - wide(a)) * t;
    const long double distance = (wide(p) - q).norm();
    if (std::abs(distance - 0.9L) < 1e-9L) continue;
    const auto out = new_proximity_line_point(a, b, p, d);
    ASSERT_EQ(out.has_value(), distance < 0.9L) << k;
    if (!out) continue;
    ++found;
    EXPECT_LT((wide(out->point[0]) - q).norm(), 1e-9L) << k;
    EXPECT_EQ(out->point[1], p);
    EXPECT_NEAR(out->value, double(distance) - 0.1, 1e-9);
    const auto swapped = new_proximity_line_point(a, b, p, d, true);
    ASSERT_TRUE(swapped);
    EXPECT_EQ(swapped->point[0], p);
    EXPECT_EQ(swapped->normal, V(-out->normal));
  }
  EXPECT_GT(found, 1000);
  // A segment of no length: no output (SOFA divides by zero).
  EXPECT_FALSE(new_proximity_line_point(V(1, 1, 1), V(1, 1, 1), V(1, 1, 1.5), d));
}

TEST(NewProximityRules, LineLineKeepsInteriorClosestPointsOnly) {
  std::mt19937 rng(14);
  const ProximityDistances<double> d{10.0, 0.25};
  int found = 0;
  for (int k = 0; k < 3000; ++k) {
    const V a = random_point(rng), b = random_point(rng), c = random_point(rng), e = random_point(rng);
    const L d1 = wide(b) - wide(a), d2 = wide(e) - wide(c), w = wide(c) - wide(a), n = d1.cross(d2);
    const long double s = w.cross(d2).dot(n) / n.squaredNorm(), t = w.cross(d1).dot(n) / n.squaredNorm();
    if (std::min({std::abs(s - 1e-6L), std::abs(t - 1e-6L), std::abs(s - 0.999999L), std::abs(t - 0.999999L)}) < 1e-9L) continue;
    const auto out = new_proximity_line_line(a, b, c, e, d);
    ASSERT_EQ(out.has_value(), s >= 1e-6L && s <= 0.999999L && t >= 1e-6L && t <= 0.999999L) << k;
    if (!out) continue;
    ++found;
    EXPECT_LT((wide(out->point[0]) - (wide(a) + d1 * s)).norm(), 1e-9L);
    EXPECT_LT((wide(out->point[1]) - (wide(c) + d2 * t)).norm(), 1e-9L);
    EXPECT_NEAR(out->value, double((wide(c) + d2 * t - wide(a) - d1 * s).norm()) - 0.25, 1e-9);
  }
  EXPECT_GT(found, 100);
  // Parallel (|det| ≤ 1e-12), and a segment of no length: both middles.
  const auto parallel = new_proximity_line_line(V(0, 0, 0), V(1, 0, 0), V(5, 0.5, 0), V(7, 0.5, 0), d);
  ASSERT_TRUE(parallel);
  EXPECT_EQ(parallel->point[0], V(0.5, 0, 0));
  EXPECT_EQ(parallel->point[1], V(6, 0.5, 0));
  const auto collapsed = new_proximity_line_line(V(0, 0, 0), V(1, 0, 0), V(3, 1, 0), V(3, 1, 0), d);
  ASSERT_TRUE(collapsed);
  EXPECT_EQ(collapsed->point[0], V(0.5, 0, 0));
}

TEST(NewProximityRules, AlarmIsExclusiveAndZeroDistancesGiveNoNaN) {
  const ProximityDistances<double> d{0.5, 0.25};
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_FALSE(new_proximity_triangle_point(a, b, c, V(0.25, 0.25, 0.5), 0, d));
  EXPECT_TRUE(new_proximity_triangle_point(a, b, c, V(0.25, 0.25, 0.4999999), 0, d));
  EXPECT_FALSE(new_proximity_point_point(V(0, 0, 0), V(0, 0.5, 0), d));
  EXPECT_TRUE(new_proximity_point_point(V(0, 0, 0), V(0, 0.4999999, 0), d));
  for (const auto& out : {new_proximity_point_point(a, a, d), new_proximity_triangle_point(a, b, c, V(0.25, 0.25, 0), 0, d),
                          new_proximity_line_point(a, b, V(0.5, 0, 0), d)}) {
    ASSERT_TRUE(out);
    EXPECT_TRUE(out->null_distance);
    EXPECT_EQ(out->normal, V(1, 0, 0));
    EXPECT_EQ(out->value, -0.25);
  }
  // Degenerate triangles: nothing (SOFA: NaN points).
  EXPECT_FALSE(new_proximity_triangle_point(a, b, V(2, 0, 0), V(1, 0.1, 0), F::points | F::edges, d));
  EXPECT_FALSE(new_proximity_triangle_point(a, a, a, V(0, 0.1, 0), F::points | F::edges, d));
  EXPECT_FALSE(new_proximity_triangle_sphere(a, b, V(2, 0, 0), {V(1, 0.1, 0), 0.1, false}, F::points | F::edges, d));
  // Float works alike.
  const auto single = new_proximity_triangle_point<float>(Vec3<float>(0, 0, 0), Vec3<float>(1, 0, 0), Vec3<float>(0, 1, 0),
                                                          Vec3<float>(2, 0, 0.1f), F::P2, {2.0f, 0.0f});
  ASSERT_TRUE(single);
  EXPECT_EQ(single->point[0], Vec3<float>(1, 0, 0));
}

TEST(NewProximityRules, SpheresUseTheirCentresAndAddTheirRadii) {
  const ProximityDistances<double> d{0.5, 0.1};
  // Radii 1 and 0.5 grow A to 2: exclusive here (MinProximity's sphere rule includes it).
  EXPECT_FALSE(new_proximity_sphere_sphere({V(0, 0, 0), 1, false}, {V(2, 0, 0), 0.5, false}, d));
  const auto pair = new_proximity_sphere_sphere({V(0, 0, 0), 1, true}, {V(1.75, 0, 0), 0.5, true}, d);
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->point[0], V(0, 0, 0));  // centres, rigid spheres too
  EXPECT_EQ(pair->point[1], V(1.75, 0, 0));
  EXPECT_NEAR(pair->value, 1.75 - 1.6, 1e-15);
  const auto point = new_proximity_sphere_point({V(0, 0, 0), 1, true}, V(0, 1.25, 0), d);
  ASSERT_TRUE(point);
  EXPECT_NEAR(point->value, 1.25 - 1.1, 1e-15);
  // Line–Sphere: the clamped closest point (not MinProximity's mirrored one), the centre second.
  const auto line = new_proximity_line_sphere(V(0, 0, 0), V(4, 0, 0), {V(1, 1, 0), 0.6, true}, d);
  ASSERT_TRUE(line);
  EXPECT_EQ(line->point[0], V(1, 0, 0));
  EXPECT_EQ(line->point[1], V(1, 1, 0));
  EXPECT_NEAR(line->value, 1 - 0.7, 1e-15);
}

TEST(NewProximityRules, TriangleSphereHasSofasOwnThresholdsAndFlags) {
  // SOFA's Triangle_test: a rigid sphere of radius 2 at (0, 0, 2.01) over the face.
  const V a(-1, -1, 0), b(1, -1, 0), c(0, 1, 0);
  const auto rigid = new_proximity_triangle_sphere(a, b, c, {V(0, 0, 2.01), 2, true}, 0, {1.0, 0.0});
  ASSERT_TRUE(rigid);
  EXPECT_LT((rigid->point[0] - V(0, 0, 0)).norm(), 1e-15);
  EXPECT_LT((rigid->point[1] - V(0, 0, 0.01)).norm(), 1e-15);
  EXPECT_LT((rigid->normal - V(0, 0, 1)).norm(), 1e-15);
  EXPECT_NEAR(rigid->value, 0.01, 1e-15);
  const auto vec3 = new_proximity_triangle_sphere(a, b, c, {V(0, 0, 2.01), 2, false}, 0, {1.0, 0.0});
  ASSERT_TRUE(vec3);
  EXPECT_EQ(vec3->point[1], V(0, 0, 2.01));
  // Edge AC is checked with E12, edge BC with E31 (the triangle–point rule: E31, E23).
  const V o(0, 0, 0), x(1, 0, 0), y(0, 1, 0);
  const ProximityDistances<double> d{1.0, 0.0};
  const ProximitySphere<double> by_ac{V(-0.5, 0.5, 0), 0.1, false}, by_bc{V(0.6, 0.6, 0), 0.1, false};
  EXPECT_FALSE(new_proximity_triangle_sphere(o, x, y, by_ac, F::E31, d));
  EXPECT_TRUE(new_proximity_triangle_sphere(o, x, y, by_ac, F::E12, d));
  EXPECT_TRUE(new_proximity_triangle_point(o, x, y, by_ac.center, F::E31, d));
  EXPECT_FALSE(new_proximity_triangle_sphere(o, x, y, by_bc, F::E23, d));
  EXPECT_TRUE(new_proximity_triangle_sphere(o, x, y, by_bc, F::E31, d));
  // At an obtuse corner A, a centre behind A: pAB = −0.1, pAC = 0.025, β = −0.05. SOFA's copy
  // takes the point at parameter −0.1 on line AB, outside the triangle; the triangle–point rule
  // finds the true closest point on AC, (−0.025, 0.025, 0).
  const V wide_c(-1, 1, 0), behind(-0.1, -0.05, 0);
  const auto quirk = new_proximity_triangle_sphere(o, x, wide_c, {behind, 0, false}, F::E12, d);
  ASSERT_TRUE(quirk);
  EXPECT_LT((quirk->point[0] - V(-0.1, 0, 0)).norm(), 1e-15);
  const auto right = new_proximity_triangle_point(o, x, wide_c, behind, F::E31, d);
  ASSERT_TRUE(right);
  EXPECT_LT((right->point[0] - V(-0.025, 0.025, 0)).norm(), 1e-15);
  // Elsewhere (an acute corner A), the closest point, with those flags.
  std::mt19937 rng(15);
  constexpr int sphere_flag[] = {0, F::P1, F::P2, F::P3, F::E12, F::E12, F::E31};
  int found = 0;
  for (int k = 0; k < 3000; ++k) {
    const V p1 = random_point(rng), p2 = random_point(rng), p3 = random_point(rng);
    if (!well_shaped(p1, p2, p3) || (p2 - p1).dot(p3 - p1) <= 0) continue;
    const ProximitySphere<double> s{near_triangle(rng, p1, p2, p3), 0.25, k % 2 == 0};
    const int flags = int(rng() % 64);
    const Closest ref = closest_on_triangle(wide(p1), wide(p2), wide(p3), wide(s.center));
    const long double distance = (wide(s.center) - ref.point).norm();
    if (ref.margin < 1e-5L || std::abs(distance - 1.25L) < 1e-9L || distance < 1e-9L) continue;
    const bool owned = (flags & sphere_flag[ref.feature]) == sphere_flag[ref.feature];
    const auto out = new_proximity_triangle_sphere(p1, p2, p3, s, flags, d);
    ASSERT_EQ(out.has_value(), owned && distance < 1.25L) << k;
    if (!out) continue;
    ++found;
    EXPECT_LT((wide(out->point[0]) - ref.point).norm(), 1e-9L) << k;
    EXPECT_NEAR(out->value, double(distance) - 0.25, 1e-9);
    EXPECT_LT((out->point[1] - (s.rigid ? V(s.center - out->normal * 0.25) : s.center)).norm(), 1e-15);
  }
  EXPECT_GT(found, 300);
}

// ---- Element pairs -------------------------------------------------------------------------------

using Outputs = std::vector<DetectionOutput<double>>;
const int kAll = F::points | F::edges;

void expect_output(const DetectionOutput<double>& o, std::int64_t id, const V& p0, const V& p1, double value) {
  EXPECT_EQ(o.id, id);
  EXPECT_LT((o.point[0] - p0).norm(), 1e-15) << o.point[0].transpose();
  EXPECT_LT((o.point[1] - p1).norm(), 1e-15) << o.point[1].transpose();
  EXPECT_LT((o.normal - (p1 - p0).normalized()).norm(), 1e-15);
  EXPECT_NEAR(o.value, value, 1e-15);
}

TEST(NewProximityPairs, TriangleTriangleListsVerticesBothWaysWithSofasIds) {
  // Triangle 1 (index 2 of 5) in z = 0; triangle 2 (index 4) a small one 0.1 above its inside.
  // By hand: vertex 1 of triangle 1 is 0.3 from corner 1 of triangle 2; its vertices 2 and 3 are
  // √0.3 > A from it; the three vertices of triangle 2 are 0.1 above triangle 1's inside.
  TriangleElement<double> t1{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), {0, 1, 2}, 0, 2};
  TriangleElement<double> t2{V(0.2, 0.2, 0.1), V(0.5, 0.2, 0.1), V(0.2, 0.5, 0.1), {3, 4, 5}, kAll, 4};
  NewProximityPair<double> pair{{0.5, 0.05}, 5, 7, false, false};
  Outputs out;
  // Triangle 1 owns nothing, yet its first vertex is tested (SOFA skips that flag).
  ASSERT_EQ(new_proximity_intersection(t1, t2, pair, out), 4);
  ASSERT_EQ(out.size(), 4u);
  const std::int64_t id2 = 3 * 5 + 12 * 4;
  expect_output(out[0], 3 * 2 + 0, t1.p1, t2.p1, 0.3 - 0.05);
  expect_output(out[1], id2 + 0, V(0.2, 0.2, 0), t2.p1, 0.1 - 0.05);
  expect_output(out[2], id2 + 1, V(0.5, 0.2, 0), t2.p2, 0.1 - 0.05);
  expect_output(out[3], id2 + 2, V(0.2, 0.5, 0), t2.p3, 0.1 - 0.05);
  // Triangle 2 not owning its corner 1: vertex 1 of triangle 1 finds an unowned corner, and
  // triangle 2's vertex 1 is not tested.
  t2.flags = F::P2 | F::P3 | F::edges;
  out.clear();
  ASSERT_EQ(new_proximity_intersection(t1, t2, pair, out), 2);
  EXPECT_EQ(out[0].id, id2 + 1);
  EXPECT_EQ(out[1].id, id2 + 2);
  // One model, a shared point: neighbours, nothing. Not sharing: as before.
  pair.same_model = true;
  t2.vertices = {3, 4, 1};
  EXPECT_EQ(new_proximity_intersection(t1, t2, pair, out), 0);
  t2.vertices = {3, 4, 5};
  EXPECT_EQ(new_proximity_intersection(t1, t2, pair, out), 2);
  // Degenerate: the flat triangle's vertices are still tested against the other one, nothing
  // against the flat one; two flat triangles give nothing.
  TriangleElement<double> flat{V(0.2, 0.2, 0.1), V(0.4, 0.2, 0.1), V(0.6, 0.2, 0.1), {6, 7, 8}, kAll, 0};
  out.clear();
  pair.same_model = false;
  ASSERT_EQ(new_proximity_intersection(t1, flat, pair, out), 3);
  for (const auto& o : out) EXPECT_EQ(o.normal, V(0, 0, 1));
  TriangleElement<double> flat1{V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), {0, 1, 2}, kAll, 0};
  EXPECT_EQ(new_proximity_intersection(flat1, flat, pair, out), 0);
}

TEST(NewProximityPairs, TriangleTriangleWithPlanesMadeBeforehandGivesTheSameOutputs) {
  // Random triangle pairs close to one another, every flag combination: the rule that takes both
  // triangles' planes (made once per triangle for a list of pairs) lists the same outputs, bit for bit.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto random_point = [&] { return V(u(rng), u(rng), u(rng)); };
  int listed = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const V shift = 0.3 * random_point();
    const TriangleElement<double> t1{random_point(), random_point(), random_point(), {0, 1, 2}, trial % 64, 3};
    const TriangleElement<double> t2{random_point() + shift, random_point() + shift, random_point() + shift, {3, 4, 5}, (trial / 3) % 64, 7};
    const NewProximityPair<double> pair{{0.4, 0.05}, 9, 11, false, trial % 2 == 0};
    Outputs plain, planned;
    const int n = new_proximity_intersection(t1, t2, pair, plain);
    const TrianglePlane<double> plane1(t1.p1, t1.p2, t1.p3), plane2(t2.p1, t2.p2, t2.p3);
    ASSERT_EQ(new_proximity_intersection(t1, plane1, t2, plane2, pair, planned), n);
    ASSERT_EQ(plain.size(), planned.size());
    for (std::size_t i = 0; i < plain.size(); ++i) {
      EXPECT_EQ(plain[i].id, planned[i].id);
      EXPECT_EQ(plain[i].point[0], planned[i].point[0]);
      EXPECT_EQ(plain[i].point[1], planned[i].point[1]);
      EXPECT_EQ(plain[i].value, planned[i].value);
    }
    listed += n;
  }
  EXPECT_GT(listed, 100);  // the pairs do meet
}

TEST(NewProximityPairs, TriangleTriangleEdgesOnlyWithUseLineLine) {
  // Two triangles whose edges 1-2 cross 0.2 apart, in planes y = 0 (below z = 0) and x = 0 (above
  // z = 0.2); every vertex is farther than A = 0.5 from the other triangle.
  const TriangleElement<double> t1{V(-1, 0, 0), V(1, 0, 0), V(0, 0, -3), {0, 1, 2}, kAll, 1};
  const TriangleElement<double> t2{V(0, -1, 0.2), V(0, 1, 0.2), V(0, 0, 3.2), {0, 1, 2}, kAll, 3};
  NewProximityPair<double> pair{{0.5, 0.05}, 2, 4, false, false};
  Outputs out;
  EXPECT_EQ(new_proximity_intersection(t1, t2, pair, out), 0);
  pair.use_line_line = true;
  ASSERT_EQ(new_proximity_intersection(t1, t2, pair, out), 1);
  expect_output(out[0], 3 * 2 + 12 * 3 + 3, V(0, 0, 0), V(0, 0, 0.2), 0.2 - 0.05);
  // Not owned by one of them: nothing.
  TriangleElement<double> unowned = t2;
  unowned.flags = F::points | F::E23 | F::E31;
  EXPECT_EQ(new_proximity_intersection(t1, unowned, pair, out), 0);
}

TEST(NewProximityPairs, TriangleLineListsCornersEndsThenEdges) {
  // By hand: corner 1 is 0.3 from the segment's first end; that end is 0.1 above the inside; the
  // segment passes 0.1 above edge 2-3 at (0.5, 0.5); the rest is farther than A = 0.5.
  const TriangleElement<double> t{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), {0, 1, 2}, kAll, 0};
  const LineElement<double> line{V(0.2, 0.2, 0.1), V(3, 3, 0.1), 6};
  NewProximityPair<double> pair{{0.5, 0.05}, 1, 9, false, false};
  Outputs out;
  ASSERT_EQ(new_proximity_intersection(t, line, pair, out), 2);
  expect_output(out[0], 6, t.p1, line.p1, 0.3 - 0.05);
  expect_output(out[1], 6, V(0.2, 0.2, 0), line.p1, 0.1 - 0.05);
  pair.use_line_line = true;
  out.clear();
  ASSERT_EQ(new_proximity_intersection(t, line, pair, out), 3);
  expect_output(out[2], 6, V(0.5, 0.5, 0), V(0.5, 0.5, 0.1), 0.1 - 0.05);
}

TEST(NewProximityPairs, IdsFollowTheLargerModelOrTheSecondElement) {
  const ProximityDistances<double> d{1.0, 0.0};
  const PointElement<double> p{V(0, 0, 0), 7}, q{V(0.5, 0, 0), 2};
  const LineElement<double> l{V(-1, 0.1, 0), V(1, 0.1, 0), 7}, m{V(0, -1, 0.2), V(0, 1, 0.2), 2};
  const SphereElement<double> s{{V(0, 0, 0.3), 0.1, false}, 7}, u{{V(0.3, 0, 0), 0.1, false}, 2};
  const TriangleElement<double> t{V(-1, -1, 0), V(1, -1, 0), V(0, 1, 0), {0, 1, 2}, kAll, 7};
  for (const bool first_larger : {true, false}) {
    const NewProximityPair<double> pair{d, first_larger ? 10u : 3u, 3, false, false};
    const std::int64_t larger = first_larger ? 7 : 2;
    Outputs out;
    ASSERT_EQ(new_proximity_intersection(p, q, pair, out), 1);
    ASSERT_EQ(new_proximity_intersection(l, m, pair, out), 1);
    ASSERT_EQ(new_proximity_intersection(s, u, pair, out), 1);
    ASSERT_EQ(new_proximity_intersection(s, q, pair, out), 1);
    ASSERT_EQ(new_proximity_intersection(l, q, pair, out), 1);
    ASSERT_EQ(new_proximity_intersection(t, q, pair, out), 1);
    ASSERT_EQ(new_proximity_intersection(l, u, pair, out), 1);
    ASSERT_EQ(new_proximity_intersection(t, u, pair, out), 1);
    const std::vector<std::int64_t> expected = {larger, larger, larger, larger, 2, 2, 2, 2};
    for (std::size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i].id, expected[i]) << i;
  }
}

}  // namespace
}  // namespace fastcorot
