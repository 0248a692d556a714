#include "fastcorot/collision/local_min_distance.h"

#include "fastcorot/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace fastcorot {

namespace {

// Dot products, norms and normalisation summed in SOFA's order (type::Vec: x, then + y, then + z),
// so that the filters' signs near zero fall as SOFA's do.
template <class Real>
Real dot3(const Vec3<Real>& u, const Vec3<Real>& v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

template <class Real>
Real norm3(const Vec3<Real>& v) {
  return std::sqrt(dot3(v, v));
}

// SOFA's Vec::normalize: divide by the norm when it exceeds machine epsilon, else leave as is.
template <class Real>
Vec3<Real> sofa_normalized(Vec3<Real> v) {
  const Real n = norm3(v);
  if (n > std::numeric_limits<Real>::epsilon()) v /= n;
  return v;
}

// The output from p (first element) to q (second); a zero distance takes `fallback`.
template <class Real>
ProximityOutput<Real> output(const Vec3<Real>& p, const Vec3<Real>& q, Real contact, const Vec3<Real>& fallback) {
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
std::optional<Vec3<Real>> triangle_foot(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c, const Vec3<Real>& p) {
  const Vec3<Real> ab = b - a, ac = c - a, ap = p - a;
  const Real a00 = dot3(ab, ab), a11 = dot3(ac, ac), a01 = dot3(ab, ac);
  const Real b0 = dot3(ap, ab), b1 = dot3(ap, ac);
  const Real det = a00 * a11 - a01 * a01;
  if (!(det > 0)) return std::nullopt;
  const Real alpha = (b0 * a11 - b1 * a01) / det;
  const Real beta = (b1 * a00 - b0 * a01) / det;
  if (alpha < Real(0.000001) || beta < Real(0.000001) || alpha + beta > Real(0.999999)) return std::nullopt;
  return Vec3<Real>(a + ab * alpha + ac * beta);
}

// The foot of p on segment AB with α in [1e-6, 0.999999], after SOFA's guard |AB| < 1e-12 |AP|.
template <class Real>
std::optional<Vec3<Real>> segment_foot(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& p) {
  const Vec3<Real> ab = b - a, ap = p - a;
  const Real length2 = dot3(ab, ab);
  if (!(length2 > 0) || norm3(ab) < Real(0.000000000001) * norm3(ap)) return std::nullopt;
  const Real alpha = dot3(ap, ab) / length2;
  if (alpha < Real(0.000001) || alpha > Real(0.999999)) return std::nullopt;
  return Vec3<Real>(a + ab * alpha);
}

template <class Real>
Vec3<Real> unit_triangle_normal(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c) {
  return sofa_normalized(Vec3<Real>((b - a).cross(c - a)));
}

template <class Real>
void check_vec3_sphere(const ProximitySphere<Real>& sphere) {
  if (sphere.rigid) throw make_error("LocalMinDistance: a rigid sphere has no rule (SOFA registers Vec3 spheres only)");
}

// max(0, coneFactor × n·t) + angleCone: the cone's widening along t.
template <class Real>
Real widened_cone(const Vec3<Real>& n, const Vec3<Real>& t, const LocalMinDistanceSettings<Real>& s) {
  Real cone = dot3(n, t) * s.cone_factor;
  if (cone < 0) cone = 0;
  return cone + s.angle_cone;
}

}  // namespace

template <class Real>
bool local_min_distance_point_validity(const LocalMinDistancePointCone<std::type_identity_t<Real>>* cone, const Vec3<Real>& v,
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
bool local_min_distance_line_validity(const Vec3<Real>& a, const Vec3<Real>& b, const LocalMinDistanceLineCone<Real>& cone,
                                      const Vec3<Real>& v, const LocalMinDistanceSettings<Real>& s) {
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
bool local_min_distance_triangle_validity(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c, bool both_side,
                                          const Vec3<Real>& v, const LocalMinDistanceSettings<Real>& s) {
  if (!s.filter_intersection || both_side) return true;
  return dot3(Vec3<Real>((b - a).cross(c - a)), v) >= 0;
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_point_point(const Vec3<Real>& p, const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
                                                                    const Vec3<Real>& q, const LocalMinDistancePointCone<std::type_identity_t<Real>>* q_cone,
                                                                    const ProximityDistances<Real>& d,
                                                                    const LocalMinDistanceSettings<Real>& s) {
  const Vec3<Real> pq = q - p;
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters &&
      (!local_min_distance_point_validity(p_cone, pq, s) || !local_min_distance_point_validity(q_cone, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(p, q, d.contact, Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_point(const Vec3<Real>& a, const Vec3<Real>& b,
                                                                   const LocalMinDistanceLineCone<Real>& line_cone, const Vec3<Real>& p,
                                                                   const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
                                                                   const ProximityDistances<Real>& d,
                                                                   const LocalMinDistanceSettings<Real>& s) {
  const auto q = segment_foot(a, b, p);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - p;  // from the point toward the segment
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters &&
      (!local_min_distance_point_validity(p_cone, pq, s) || !local_min_distance_line_validity(a, b, line_cone, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(*q, p, d.contact, Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_line(const Vec3<Real>& a, const Vec3<Real>& b,
                                                                  const LocalMinDistanceLineCone<Real>& ab_cone, const Vec3<Real>& c,
                                                                  const Vec3<Real>& e, const LocalMinDistanceLineCone<Real>& ce_cone,
                                                                  const ProximityDistances<Real>& d,
                                                                  const LocalMinDistanceSettings<Real>& s) {
  const Vec3<Real> ab = b - a, ce = e - c, ac = c - a;
  const Real a00 = dot3(ab, ab), a11 = dot3(ce, ce), a01 = -dot3(ce, ab);
  if (!(a00 > 0) || !(a11 > 0)) return std::nullopt;  // beyond SOFA: a segment of no length
  const Real b0 = dot3(ab, ac), b1 = -dot3(ce, ac);
  const Real det = a00 * a11 - a01 * a01;
  Real alpha = 0.5, beta = 0.5;
  if (det < Real(-1.0e-30) || det > Real(1.0e-30)) {
    alpha = (b0 * a11 - b1 * a01) / det;
    beta = (b1 * a00 - b0 * a01) / det;
    if (alpha < Real(1e-15) || alpha > Real(1.0 - 1e-15) || beta < Real(1e-15) || beta > Real(1.0 - 1e-15)) return std::nullopt;
  }
  const Vec3<Real> p = a + ab * alpha, q = c + ce * beta;
  const Vec3<Real> pq = q - p;
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters &&
      (!local_min_distance_line_validity(a, b, ab_cone, pq, s) || !local_min_distance_line_validity(c, e, ce_cone, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(p, q, d.contact, Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_triangle_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                       bool triangle_both_side, const Vec3<Real>& p,
                                                                       const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
                                                                       const ProximityDistances<Real>& d,
                                                                       const LocalMinDistanceSettings<Real>& s) {
  const auto q = triangle_foot(a, b, c, p);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - p;  // from the point toward the triangle
  if (!within(pq, d.alarm)) return std::nullopt;
  if (!s.use_lmd_filters && (!local_min_distance_point_validity(p_cone, pq, s) ||
                             !local_min_distance_triangle_validity(a, b, c, triangle_both_side, Vec3<Real>(-pq), s))) {
    return std::nullopt;
  }
  return output(*q, p, d.contact, unit_triangle_normal(a, b, c));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_sphere_point(const ProximitySphere<Real>& sphere, const Vec3<Real>& p,
                                                                     const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
                                                                     ProximityDistances<Real> d, const LocalMinDistanceSettings<Real>& s) {
  check_vec3_sphere(sphere);
  const Vec3<Real> pq = p - sphere.center;
  if (!within(pq, Real(d.alarm + sphere.radius))) return std::nullopt;
  // The sphere's own filter accepts every direction.
  if (!s.use_lmd_filters && !local_min_distance_point_validity(p_cone, Vec3<Real>(-pq), s)) return std::nullopt;
  return output(sphere.center, p, Real(d.contact + sphere.radius), Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_sphere(const Vec3<Real>& a, const Vec3<Real>& b,
                                                                    const LocalMinDistanceLineCone<Real>& line_cone,
                                                                    const ProximitySphere<Real>& sphere, ProximityDistances<Real> d,
                                                                    const LocalMinDistanceSettings<Real>& s) {
  check_vec3_sphere(sphere);
  const auto q = segment_foot(a, b, sphere.center);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - sphere.center;
  if (!within(pq, Real(d.alarm + sphere.radius))) return std::nullopt;
  if (!s.use_lmd_filters && !local_min_distance_line_validity(a, b, line_cone, Vec3<Real>(-pq), s)) return std::nullopt;
  return output(*q, sphere.center, Real(d.contact + sphere.radius), Vec3<Real>(Vec3<Real>::UnitX()));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_triangle_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                        bool triangle_both_side, const ProximitySphere<Real>& sphere,
                                                                        ProximityDistances<Real> d,
                                                                        const LocalMinDistanceSettings<Real>& s) {
  check_vec3_sphere(sphere);
  const auto q = triangle_foot(a, b, c, sphere.center);
  if (!q) return std::nullopt;
  const Vec3<Real> pq = *q - sphere.center;
  if (!within(pq, Real(d.alarm + sphere.radius))) return std::nullopt;
  if (!s.use_lmd_filters && !local_min_distance_triangle_validity(a, b, c, triangle_both_side, Vec3<Real>(-pq), s)) return std::nullopt;
  return output(*q, sphere.center, Real(d.contact + sphere.radius), unit_triangle_normal(a, b, c));
}

template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_sphere_sphere(const ProximitySphere<Real>& sphere1,
                                                                      const ProximitySphere<Real>& sphere2, ProximityDistances<Real> d) {
  check_vec3_sphere(sphere1);
  check_vec3_sphere(sphere2);
  const Vec3<Real> pq = sphere2.center - sphere1.center;
  const Real radii = sphere1.radius + sphere2.radius;
  if (!within(pq, Real(d.alarm + radii))) return std::nullopt;
  return output(sphere1.center, sphere2.center, Real(d.contact + radii), Vec3<Real>(Vec3<Real>::UnitX()));
}

LocalMinDistanceTopology local_min_distance_topology(Index point_count, std::span<const Triangle> triangles,
                                                     std::span<const Edge> edges) {
  if (point_count < 0) throw make_error("LocalMinDistance: negative point count ", point_count);
  const auto check = [&](Index v, const char* what, std::size_t i) {
    if (v < 0 || v >= point_count) throw make_error("LocalMinDistance: ", what, " ", i, " names point ", v, " of ", point_count);
  };
  LocalMinDistanceTopology t;
  t.point_count = point_count;
  t.triangles.assign(triangles.begin(), triangles.end());
  t.edges.assign(edges.begin(), edges.end());
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (Index v : triangles[i]) check(v, "triangle", i);
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (Index v : edges[i]) check(v, "edge", i);

  // Shells by counting sort: each list in ascending element order, as SOFA's topologies build them.
  const auto build = [&](auto&& each_corner, std::size_t count, std::vector<Index>& offsets, std::vector<Index>& items, auto&& item) {
    offsets.assign(point_count + 1, 0);
    for (std::size_t i = 0; i < count; ++i) each_corner(i, [&](Index v, std::size_t) { ++offsets[v + 1]; });
    for (Index v = 0; v < point_count; ++v) offsets[v + 1] += offsets[v];
    items.resize(offsets[point_count]);
    std::vector<Index> next(offsets.begin(), offsets.end() - 1);
    for (std::size_t i = 0; i < count; ++i) each_corner(i, [&](Index v, std::size_t k) { items[next[v]++] = item(i, k); });
  };
  build([&](std::size_t i, auto&& f) { for (std::size_t k = 0; k < 3; ++k) f(triangles[i][k], k); }, triangles.size(),
        t.vertex_triangle_offsets, t.vertex_triangles, [](std::size_t i, std::size_t) { return Index(i); });
  build([&](std::size_t i, auto&& f) { for (std::size_t k = 0; k < 2; ++k) f(edges[i][k], k); }, edges.size(), t.vertex_edge_offsets,
        t.vertex_edge_other, [&](std::size_t i, std::size_t k) { return edges[i][1 - k]; });

  // Triangles around each edge in SOFA's order (MeshTopology and TriangleSetTopologyContainer
  // createTrianglesAroundEdgeArray): triangle i's edge j is (t[j+1], t[j+2]); a triangle listing it
  // in the edge's stored direction goes in front, any other at the back.
  std::map<std::pair<Index, Index>, Index> edge_of;
  const auto key = [](Index u, Index v) { return std::make_pair(std::min(u, v), std::max(u, v)); };
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto [it, fresh] = edge_of.emplace(key(edges[i][0], edges[i][1]), Index(i));
    if (!fresh) throw make_error("LocalMinDistance: edge ", i, " (", edges[i][0], ", ", edges[i][1], ") repeats edge ", it->second);
  }
  std::vector<std::vector<Index>> around(edges.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      const Index from = triangles[i][(j + 1) % 3], to = triangles[i][(j + 2) % 3];
      const auto it = edge_of.find(key(from, to));
      if (it == edge_of.end()) continue;  // an edge the list lacks (SOFA's topologies derive them all)
      auto& list = around[it->second];
      if (edges[it->second][0] == from) list.insert(list.begin(), Index(i));
      else list.push_back(Index(i));
    }
  }
  // LocalMinDistance's left: the list's first triangle when it lists the edge as stored, else the
  // second (unchecked); right: the other.
  t.edge_right_left.assign(edges.size(), {-1, -1});
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (around[i].size() != 2) continue;
    const Triangle& first = triangles[around[i][0]];
    const Edge& e = edges[i];
    const bool first_is_left = (e[0] == first[0] && e[1] == first[1]) || (e[0] == first[1] && e[1] == first[2]) ||
                               (e[0] == first[2] && e[1] == first[0]);
    t.edge_right_left[i] = first_is_left ? std::array<Index, 2>{around[i][1], around[i][0]}
                                         : std::array<Index, 2>{around[i][0], around[i][1]};
  }
  return t;
}

template <class Real>
LocalMinDistancePointCone<Real> LocalMinDistanceNeighbourhood<Real>::point_cone(Index vertex, bool both_side) const {
  LocalMinDistancePointCone<Real> cone;
  cone.normal_sum = normal_sum.at(vertex);
  cone.edge_directions = std::span<const Vec3<Real>>(edge_directions).subspan(edge_offsets[vertex], edge_offsets[vertex + 1] - edge_offsets[vertex]);
  cone.both_side = both_side;
  return cone;
}

template <class Real>
LocalMinDistanceLineCone<Real> LocalMinDistanceNeighbourhood<Real>::line_cone(Index edge, bool both_side) const {
  LocalMinDistanceLineCone<Real> cone = line_cones.at(edge);
  cone.both_side = both_side;
  return cone;
}

template <class Real>
void compute_local_min_distance_neighbourhood(const LocalMinDistanceTopology& topology, std::span<const Vec3<Real>> x,
                                              LocalMinDistanceNeighbourhood<Real>& out) {
  if (x.size() != std::size_t(topology.point_count)) {
    throw make_error("LocalMinDistance: ", x.size(), " positions for a topology of ", topology.point_count, " points");
  }
  const auto normal = [&](Index t) {
    const Triangle& tri = topology.triangles[t];
    return unit_triangle_normal(x[tri[0]], x[tri[1]], x[tri[2]]);
  };
  const Index n = topology.point_count;
  out.normal_sum.assign(n, Vec3<Real>::Zero());
  out.edge_offsets = topology.vertex_edge_offsets;
  out.edge_directions.resize(topology.vertex_edge_other.size());
  for (Index v = 0; v < n; ++v) {
    const Index e0 = topology.vertex_edge_offsets[v], e1 = topology.vertex_edge_offsets[v + 1];
    for (Index k = e0; k < e1; ++k) out.edge_directions[k] = sofa_normalized(Vec3<Real>(x[v] - x[topology.vertex_edge_other[k]]));
    Vec3<Real>& sum = out.normal_sum[v];
    const Index t0 = topology.vertex_triangle_offsets[v], t1 = topology.vertex_triangle_offsets[v + 1];
    for (Index k = t0; k < t1; ++k) sum += normal(topology.vertex_triangles[k]);
    if (t0 == t1) {
      for (Index k = e0; k < e1; ++k) sum += out.edge_directions[k];
    }
  }
  out.line_cones.assign(topology.edges.size(), LocalMinDistanceLineCone<Real>{});
  for (std::size_t i = 0; i < topology.edges.size(); ++i) {
    const auto [right, left] = topology.edge_right_left[i];
    if (right < 0) continue;
    out.line_cones[i].two_triangles = true;
    out.line_cones[i].right_normal = normal(right);
    out.line_cones[i].left_normal = normal(left);
  }
}

#define FASTCOROT_LOCAL_MIN_DISTANCE(Real)                                                                                          \
  template bool local_min_distance_point_validity(const LocalMinDistancePointCone<Real>*, const Vec3<Real>&,                       \
                                                  const LocalMinDistanceSettings<Real>&);                                           \
  template bool local_min_distance_line_validity(const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&,      \
                                                 const Vec3<Real>&, const LocalMinDistanceSettings<Real>&);                         \
  template bool local_min_distance_triangle_validity(const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, bool,                \
                                                     const Vec3<Real>&, const LocalMinDistanceSettings<Real>&);                     \
  template std::optional<ProximityOutput<Real>> local_min_distance_point_point(                                                    \
      const Vec3<Real>&, const LocalMinDistancePointCone<Real>*, const Vec3<Real>&, const LocalMinDistancePointCone<Real>*,        \
      const ProximityDistances<Real>&, const LocalMinDistanceSettings<Real>&);                                                     \
  template std::optional<ProximityOutput<Real>> local_min_distance_line_point(                                                     \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&, const Vec3<Real>&,                              \
      const LocalMinDistancePointCone<Real>*, const ProximityDistances<Real>&, const LocalMinDistanceSettings<Real>&);             \
  template std::optional<ProximityOutput<Real>> local_min_distance_line_line(                                                      \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&, const Vec3<Real>&, const Vec3<Real>&,           \
      const LocalMinDistanceLineCone<Real>&, const ProximityDistances<Real>&, const LocalMinDistanceSettings<Real>&);              \
  template std::optional<ProximityOutput<Real>> local_min_distance_triangle_point(                                                 \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, bool, const Vec3<Real>&, const LocalMinDistancePointCone<Real>*,    \
      const ProximityDistances<Real>&, const LocalMinDistanceSettings<Real>&);                                                     \
  template std::optional<ProximityOutput<Real>> local_min_distance_sphere_point(                                                   \
      const ProximitySphere<Real>&, const Vec3<Real>&, const LocalMinDistancePointCone<Real>*, ProximityDistances<Real>,           \
      const LocalMinDistanceSettings<Real>&);                                                                                      \
  template std::optional<ProximityOutput<Real>> local_min_distance_line_sphere(                                                    \
      const Vec3<Real>&, const Vec3<Real>&, const LocalMinDistanceLineCone<Real>&, const ProximitySphere<Real>&,                   \
      ProximityDistances<Real>, const LocalMinDistanceSettings<Real>&);                                                            \
  template std::optional<ProximityOutput<Real>> local_min_distance_triangle_sphere(                                                \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, bool, const ProximitySphere<Real>&, ProximityDistances<Real>,       \
      const LocalMinDistanceSettings<Real>&);                                                                                      \
  template std::optional<ProximityOutput<Real>> local_min_distance_sphere_sphere(const ProximitySphere<Real>&,                    \
                                                                                 const ProximitySphere<Real>&,                    \
                                                                                 ProximityDistances<Real>);                       \
  template struct LocalMinDistanceNeighbourhood<Real>;                                                                             \
  template void compute_local_min_distance_neighbourhood(const LocalMinDistanceTopology&, std::span<const Vec3<Real>>,             \
                                                         LocalMinDistanceNeighbourhood<Real>&);
FASTCOROT_LOCAL_MIN_DISTANCE(float)
FASTCOROT_LOCAL_MIN_DISTANCE(double)
#undef FASTCOROT_LOCAL_MIN_DISTANCE

}  // namespace fastcorot
