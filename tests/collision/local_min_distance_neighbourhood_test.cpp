// LocalMinDistance's neighbourhood (local_min_distance_topology, compute_local_min_distance_
// neighbourhood) and its cone filters against a scan of a random surface in long double: every
// triangle and edge visited for each vertex and edge (no shells), normals written from another
// corner, tangents as the direction away from each triangle's third corner, cones as angles
// (atan2); SOFA's rules from LocalMinDistance.cpp testValidity. Bad topologies are named.
#include "fastcorot/collision/local_min_distance.h"

#include "fastcorot/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
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
// cos of the angle between a and b, through the angle itself.
long double cos_angle(const L& a, const L& b) {
  return std::cos(std::atan2(a.cross(b).norm(), a.dot(b)));
}
bool near(long double x, long double threshold) {
  return std::abs(x - threshold) < 1e-9L;
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

TEST(LocalMinDistanceNeighbourhood, ConesAndFiltersMatchAScanOfARandomSurface) {
  // A 6×6 height field (consistently oriented, some edges listed backwards), a polyline and a lone
  // point.
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(-1, 1);
  Mesh m;
  const int n = 6;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.x.push_back(V(i + 0.3 * u(rng), j + 0.3 * u(rng), 0.6 * u(rng)));
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const Index v00 = j * n + i, v10 = v00 + 1, v01 = v00 + n, v11 = v01 + 1;
      m.triangles.push_back({v00, v10, v11});
      m.triangles.push_back({v00, v11, v01});
    }
  }
  for (const Triangle& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      Edge e{t[k], t[(k + 1) % 3]};
      bool known = false;
      for (const Edge& f : m.edges)
        known |= (f[0] == e[0] && f[1] == e[1]) || (f[0] == e[1] && f[1] == e[0]);
      if (!known) m.edges.push_back(rng() % 2 ? e : Edge{e[1], e[0]});
    }
  }
  const Index polyline = Index(m.x.size());
  for (int k = 0; k < 4; ++k) m.x.push_back(V(k, -3 + u(rng) * 0.2, u(rng)));
  for (int k = 0; k < 3; ++k) m.edges.push_back({polyline + k, polyline + k + 1});
  m.x.push_back(V(9, 9, 9));
  m.build();

  const auto unit_normal = [&](const Triangle& t) {
    return L(
        (wide(m.x[t[1]]) - wide(m.x[t[0]])).cross(wide(m.x[t[2]]) - wide(m.x[t[1]])).normalized());
  };
  std::vector<L> mean(m.x.size());
  for (std::size_t v = 0; v < m.x.size(); ++v) {
    L sum = L::Zero();
    bool any = false;
    for (const Triangle& t : m.triangles)
      for (Index c : t)
        if (c == Index(v)) sum += unit_normal(t), any = true;
    for (const Edge& e : m.edges)
      if (!any && (e[0] == Index(v) || e[1] == Index(v)))
        sum += (wide(m.x[v]) - wide(m.x[e[0] + e[1] - Index(v)])).normalized();
    EXPECT_LT((wide(m.cones.normal_sum[v]) - sum).norm(), 1e-12L) << v;
    mean[v] = sum.norm() > 1e-10L ? L(sum.normalized()) : sum;
  }
  EXPECT_EQ(m.cones.normal_sum.back(), V::Zero());

  std::uniform_real_distribution<double> setting(0, 1);
  int rejected = 0, accepted = 0;
  for (int k = 0; k < 6000; ++k) {
    Settings s;
    s.angle_cone = k % 3 == 0 ? 0.0 : 0.3 * setting(rng);
    s.cone_factor = setting(rng);
    const bool both_side = k % 5 == 0;
    const V v = random_point(rng, 2);
    bool expected = true, ambiguous = false;
    const auto reject_below = [&](long double value, long double threshold) {
      ambiguous |= near(value, threshold);
      if (value < threshold) expected = false;
    };
    bool got = false, got_unfiltered = false;
    Settings off = s;
    off.filter_intersection = false;
    if (k % 2 == 0) {  // a vertex
      const Index p = Index(rng() % m.x.size());
      if (mean[p].norm() > 1e-10L && !both_side)
        reject_below(cos_angle(mean[p], wide(v)), -s.angle_cone);
      for (const Edge& e : m.edges) {
        if (e[0] != p && e[1] != p) continue;
        const L dir = (wide(m.x[p]) - wide(m.x[e[0] + e[1] - p])).normalized();
        reject_below(cos_angle(dir, wide(v)),
                     -(std::max(0.0L, s.cone_factor * mean[p].dot(dir)) + s.angle_cone));
      }
      const PointCone cone = m.cones.point_cone(p, both_side);
      got = local_min_distance_point_validity(&cone, v, s);
      got_unfiltered = local_min_distance_point_validity(&cone, v, off);
    } else {  // an edge
      const Index i = Index(rng() % m.edges.size());
      const Edge& e = m.edges[i];
      const L a = wide(m.x[e[0]]), b = wide(m.x[e[1]]), ab = b - a;
      std::vector<Triangle> around;
      for (const Triangle& t : m.triangles) {
        int shared = 0;
        for (Index c : t) shared += (c == e[0]) + (c == e[1]);
        if (shared == 2) around.push_back(t);
      }
      if (around.size() == 2) {
        const auto lists_forward = [&](const Triangle& t) {
          for (int c = 0; c < 3; ++c)
            if (t[c] == e[0]) return t[(c + 1) % 3] == e[1];
          return false;
        };
        const Triangle& left = lists_forward(around[0]) ? around[0] : around[1];
        const Triangle& right = lists_forward(around[0]) ? around[1] : around[0];
        // Each tangent points away from its triangle's third corner, across the edge.
        const auto away = [&](const Triangle& t) {
          const L k3 = wide(m.x[t[0] + t[1] + t[2] - e[0] - e[1]]) - a;
          return L(-(k3 - ab * (k3.dot(ab) / ab.squaredNorm())).normalized());
        };
        const L nm = (unit_normal(right) + unit_normal(left)).normalized();
        if (!both_side) reject_below(nm.dot(wide(v)), 0);
        for (const L& t : {away(right), away(left)})
          reject_below(cos_angle(t, wide(v)),
                       -(std::max(0.0L, s.cone_factor * nm.dot(t)) + s.angle_cone));
      } else {
        reject_below(-std::abs(cos_angle(ab, wide(v))), -(s.angle_cone + 1e-4L));
      }
      got = local_min_distance_line_validity(m.x[e[0]], m.x[e[1]], m.cones.line_cone(i, both_side),
                                             v, s);
      got_unfiltered = local_min_distance_line_validity(m.x[e[0]], m.x[e[1]],
                                                        m.cones.line_cone(i, both_side), v, off);
    }
    ASSERT_TRUE(got_unfiltered) << k;  // filterIntersection = false accepts everything
    if (ambiguous) continue;
    ASSERT_EQ(got, expected) << k;
    (expected ? accepted : rejected)++;
  }
  EXPECT_GT(accepted, 500);
  EXPECT_GT(rejected, 500);
}

TEST(LocalMinDistanceNeighbourhood, BadTopologiesAreNamed) {
  const std::vector<Triangle> triangles{{0, 1, 5}};
  EXPECT_THROW(local_min_distance_topology(3, triangles, {}), Error);
  const std::vector<Edge> repeated{{0, 1}, {1, 0}};
  EXPECT_THROW(local_min_distance_topology(3, {}, repeated), Error);
  const auto topology = local_min_distance_topology(3, {}, std::vector<Edge>{{0, 1}});
  LocalMinDistanceNeighbourhood<double> cones;
  const std::vector<V> two{V::Zero(), V::Zero()};
  EXPECT_THROW(compute_local_min_distance_neighbourhood<double>(topology, two, cones), Error);
}

}  // namespace
}  // namespace fastcorot
