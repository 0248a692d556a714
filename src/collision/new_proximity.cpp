#include "fastcorot/collision/new_proximity.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/packed.h"

#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace fastcorot {

namespace {

void check_vertex(Index v, std::size_t point_count, const char* element, std::size_t i) {
  if (v < 0 || static_cast<std::size_t>(v) >= point_count)
    throw make_error(element, " ", i, " has vertex ", v, " but there are ", point_count, " points");
}

}  // namespace

std::vector<int> triangle_flags(std::span<const Triangle> triangles, std::size_t point_count, std::span<const Edge> edges) {
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (const Index v : triangles[i]) check_vertex(v, point_count, "triangle", i);
  // The stored edges: given, or derived in the direction of the first triangle that has each one
  // (MeshTopology::EdgeUpdate::updateFromSurface, TriangleSetTopologyContainer::createEdgeSetArray).
  std::vector<Edge> derived;
  std::map<std::pair<Index, Index>, std::size_t> index_of;  // unordered pair -> first edge with it
  const auto key = [](Index a, Index b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); };
  if (edges.empty()) {
    for (const Triangle& t : triangles)
      for (int j = 0; j < 3; ++j) {
        const Index a = t[(j + 1) % 3], b = t[(j + 2) % 3];
        if (index_of.emplace(key(a, b), derived.size()).second) derived.push_back({a, b});
      }
    edges = derived;
  } else {
    for (std::size_t e = 0; e < edges.size(); ++e) {
      check_vertex(edges[e][0], point_count, "edge", e);
      check_vertex(edges[e][1], point_count, "edge", e);
      index_of.emplace(key(edges[e][0], edges[e][1]), e);
    }
  }
  // First of the triangles around each vertex (filled in index order) and around each edge (a
  // triangle along the edge's stored direction goes to the front, any other to the back).
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> vertex_owner(point_count, none), edge_owner(edges.size(), none);
  std::vector<int> edge_triangles(edges.size(), 0);
  std::vector<std::array<std::size_t, 3>> edges_in_triangle(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    for (int j = 0; j < 3; ++j) {
      if (vertex_owner[t[j]] == none) vertex_owner[t[j]] = i;
      const auto found = index_of.find(key(t[(j + 1) % 3], t[(j + 2) % 3]));
      if (found == index_of.end())
        throw make_error("triangle ", i, " has edge (", t[(j + 1) % 3], ", ", t[(j + 2) % 3], ") that the edge list lacks");
      const std::size_t e = found->second;
      edges_in_triangle[i][j] = e;
      if (edges[e][0] == t[(j + 1) % 3] || edge_triangles[e] == 0) edge_owner[e] = i;
      ++edge_triangles[e];
    }
  }
  std::vector<int> flags(triangles.size(), 0);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int j = 0; j < 3; ++j) {
      if (vertex_owner[triangles[i][j]] == i) flags[i] |= TriangleFlag::P1 << j;
      const std::size_t e = edges_in_triangle[i][j];
      if (edge_owner[e] == i) flags[i] |= TriangleFlag::E23 << j;
      if (edge_triangles[e] == 1) flags[i] |= TriangleFlag::BE23 << j;
    }
  return flags;
}

std::vector<int> line_flags(std::span<const Edge> edges, std::size_t point_count) {
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> owner(point_count, none);
  std::vector<int> count(point_count, 0);
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (const Index v : edges[e]) {
      check_vertex(v, point_count, "edge", e);
      if (owner[v] == none) owner[v] = e;
      ++count[v];
    }
  std::vector<int> flags(edges.size(), 0);
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (int j = 0; j < 2; ++j) {
      if (owner[edges[e][j]] == e) flags[e] |= LineFlag::P1 << j;
      if (count[edges[e][j]] == 1) flags[e] |= LineFlag::BP1 << j;
    }
  return flags;
}

namespace {

// The output from p (on the rule's first element) to q, distance² norm2, as SOFA fills it: value
// = √norm2, normal = (q − p)/value; swapped, q is point[0] and the normal −(q − p)/value. Then C
// is subtracted, as SOFA's callers do. A zero distance: (1, 0, 0), flagged (SOFA: NaN).
template <class Real>
ProximityOutput<Real> output(const Vec3<Real>& p, const Vec3<Real>& q, Real norm2, Real contact, bool swap) {
  ProximityOutput<Real> out;
  const Vec3<Real> pq = q - p;
  out.value = std::sqrt(norm2);
  out.point[0] = swap ? q : p;
  out.point[1] = swap ? p : q;
  if (out.value > 0) {
    out.normal = swap ? Vec3<Real>(-pq / out.value) : Vec3<Real>(pq / out.value);
  } else {
    out.normal = Vec3<Real>::UnitX();
    out.null_distance = true;
  }
  out.value -= contact;
  return out;
}

// The closest point of segment (a, b) to q, SOFA's way; nullopt for a segment of no length.
template <class Real>
std::optional<Vec3<Real>> clamped_line_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& q) {
  const Vec3<Real> ab = b - a, aq = q - a;
  const Real length2 = ab.dot(ab);
  if (!(length2 > 0)) return std::nullopt;
  Real alpha = aq.dot(ab) / length2;
  if (alpha < 0) alpha = 0;
  else if (alpha > 1) alpha = 1;
  return Vec3<Real>(a + ab * alpha);
}

template <class Real>
ProximityDistances<Real> with_radius(ProximityDistances<Real> d, Real radius) {
  d.alarm += radius;
  d.contact += radius;
  return d;
}

// A sphere's contact point for a normal pointing toward it (getContactPointByNormal).
template <class Real>
Vec3<Real> sphere_point(const ProximitySphere<Real>& s, const Vec3<Real>& toward_sphere) {
  return s.rigid ? Vec3<Real>(s.center - toward_sphere * s.radius) : s.center;
}

}  // namespace

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_point_point(const Vec3<Real>& p, const Vec3<Real>& q,
                                                               const ProximityDistances<Real>& d) {
  const Real norm2 = (q - p).squaredNorm();
  if (!(norm2 < d.alarm * d.alarm)) return std::nullopt;
  return output(p, q, norm2, d.contact, false);
}

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_line_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& q,
                                                              const ProximityDistances<Real>& d, bool swap_elements) {
  const auto p = clamped_line_point(a, b, q);
  if (!p) return std::nullopt;
  const Real norm2 = (q - *p).squaredNorm();
  if (!(norm2 < d.alarm * d.alarm)) return std::nullopt;
  return output(*p, q, norm2, d.contact, swap_elements);
}

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_line_line(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                             const Vec3<Real>& e, const ProximityDistances<Real>& d) {
  const Vec3<Real> ab = b - a, ce = e - c, ac = c - a;
  const Real a00 = ab.dot(ab), a11 = ce.dot(ce), a01 = -ce.dot(ab);
  const Real b0 = ab.dot(ac), b1 = -ce.dot(ac);
  const Real det = a00 * a11 - a01 * a01;
  Real alpha = 0.5, beta = 0.5;
  if (det < -1e-12 || det > 1e-12) {
    alpha = (b0 * a11 - b1 * a01) / det;
    beta = (b1 * a00 - b0 * a01) / det;
    if (alpha < 1e-6 || alpha > 0.999999 || beta < 1e-6 || beta > 0.999999) return std::nullopt;
  }
  const Vec3<Real> p = a + ab * alpha, q = c + ce * beta;
  const Real norm2 = (q - p).squaredNorm();
  if (!(norm2 < d.alarm * d.alarm)) return std::nullopt;
  return output(p, q, norm2, d.contact, false);
}

namespace {

template <class Real>
std::optional<ProximityOutput<Real>> triangle_point(const TrianglePlane<Real>& t, const Vec3<Real>& q, int flags,
                                                    const ProximityDistances<Real>& d, bool swap_elements) {
  const Vec3<Real>&a = t.a, &ab = t.ab, &ac = t.ac;
  const Real a00 = t.a00, a11 = t.a11, a01 = t.a01, det = t.det;
  if (!(det > 0)) return std::nullopt;  // beyond SOFA: no plane, no output
  // For speed only (the same outputs), two lower bounds of q's distance to the triangle: its gap to
  // the triangle's box along each axis, then its distance to the triangle's plane, |aq · n| / |n|.
  // A point farther than the alarm distance by either (by more than rounding: the margins) is no
  // output. Most pairs the tree hands over end here.
  // The box test runs on the three axes at once, each lane as the scalar formula.
  using P = Packed<Real>;
  const P pq = packed_point(q), low = packed_point(t.low), high = packed_point(t.high);
  const P reach = broadcast(d.alarm * Real(1 + 1e-6));
  const P slack =
      broadcast(8 * std::numeric_limits<Real>::epsilon()) * ((packed_abs<Real>(pq) + packed_abs<Real>(low)) + packed_abs<Real>(high));
  const auto far = ((low - pq) > (reach + slack)) | ((pq - high) > (reach + slack));
  if (far[0] | far[1] | far[2]) return std::nullopt;
  const Vec3<Real> aq = q - a;
  const Real height = aq.dot(t.normal);
  if (height * height > d.alarm * d.alarm * t.normal2 * Real(1 + 1e-6)) return std::nullopt;
  const Real b0 = aq.dot(ab), b1 = aq.dot(ac);
  Real alpha = (b0 * a11 - b1 * a01) / det;
  Real beta = (b1 * a00 - b0 * a01) / det;
  const Real eps = std::numeric_limits<Real>::epsilon();
  if (alpha < eps || beta < eps || alpha + beta > 1 - eps) {
    const Real p_ab = b0 / a00, p_ac = b1 / a11;
    if (p_ab < eps && p_ac < eps) {
      if (!(flags & TriangleFlag::P1)) return std::nullopt;
      alpha = 0;
      beta = 0;
    } else if (p_ab < 1 - eps && p_ab >= eps && beta < eps) {
      if (!(flags & TriangleFlag::E12)) return std::nullopt;
      alpha = p_ab;
      beta = 0;
    } else if (p_ac < 1 - eps && p_ac >= eps && alpha < eps) {
      if (!(flags & TriangleFlag::E31)) return std::nullopt;
      alpha = 0;
      beta = p_ac;
    } else {
      const Real p_bc = (b1 - b0 + a00 - a01) / (a00 + a11 - 2 * a01);
      if (p_bc < eps) {
        if (!(flags & TriangleFlag::P2)) return std::nullopt;
        alpha = 1;
        beta = 0;
      } else if (p_bc > 1 - eps) {
        if (!(flags & TriangleFlag::P3)) return std::nullopt;
        alpha = 0;
        beta = 1;
      } else {
        if (!(flags & TriangleFlag::E23)) return std::nullopt;
        alpha = 1 - p_bc;
        beta = p_bc;
      }
    }
  }
  const Vec3<Real> p = a + ab * alpha + ac * beta;
  if (!p.allFinite()) return std::nullopt;  // a near-flat triangle whose |BC|² rounds to 0
  const Real norm2 = (q - p).squaredNorm();
  if (!(norm2 < d.alarm * d.alarm)) return std::nullopt;
  return output(p, q, norm2, d.contact, swap_elements);
}

}  // namespace

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_triangle_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                  const Vec3<Real>& q, int flags, const ProximityDistances<Real>& d,
                                                                  bool swap_elements) {
  return triangle_point(TrianglePlane<Real>(a, b, c), q, flags, d, swap_elements);
}

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_sphere_sphere(const ProximitySphere<Real>& s, const ProximitySphere<Real>& t,
                                                                 ProximityDistances<Real> d) {
  d = with_radius(with_radius(d, s.radius), t.radius);
  return new_proximity_point_point(s.center, t.center, d);
}

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_sphere_point(const ProximitySphere<Real>& s, const Vec3<Real>& p,
                                                                ProximityDistances<Real> d) {
  return new_proximity_point_point(s.center, p, with_radius(d, s.radius));
}

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_line_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const ProximitySphere<Real>& s,
                                                               ProximityDistances<Real> d) {
  return new_proximity_line_point(a, b, s.center, with_radius(d, s.radius));
}

template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_triangle_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                   const ProximitySphere<Real>& s, int flags, ProximityDistances<Real> d) {
  d = with_radius(d, s.radius);
  const Vec3<Real> ab = b - a, ac = c - a, aq = s.center - a;
  const Real a00 = ab.dot(ab), a11 = ac.dot(ac), a01 = ab.dot(ac);
  const Real b0 = aq.dot(ab), b1 = aq.dot(ac);
  const Real det = a00 * a11 - a01 * a01;
  if (!(det > 0)) return std::nullopt;  // beyond SOFA
  Real alpha = (b0 * a11 - b1 * a01) / det;
  Real beta = (b1 * a00 - b0 * a01) / det;
  if (alpha < 1e-6 || beta < 1e-6 || alpha + beta > 0.999999) {
    const Real p_ab = b0 / a00, p_ac = b1 / a11;
    if (p_ab < 1e-6 && p_ac < 1e-7) {  // SOFA's 1e-7 on AC
      if (!(flags & TriangleFlag::P1)) return std::nullopt;
      alpha = 0;
      beta = 0;
    } else if (p_ab < 0.999999 && beta < 1e-6) {
      if (!(flags & TriangleFlag::E12)) return std::nullopt;
      alpha = p_ab;
      beta = 0;
    } else if (p_ac < 0.999999 && alpha < 1e-6) {
      if (!(flags & TriangleFlag::E12)) return std::nullopt;  // SOFA's flag for AC
      alpha = 0;
      beta = p_ac;
    } else {
      const Real p_bc = (b1 - b0 + a00 - a01) / (a00 + a11 - 2 * a01);
      if (p_bc < 1e-6) {
        if (!(flags & TriangleFlag::P2)) return std::nullopt;
        alpha = 1;
        beta = 0;
      } else if (p_bc > 0.999999) {
        if (!(flags & TriangleFlag::P3)) return std::nullopt;
        alpha = 0;
        beta = 1;
      } else {
        if (!(flags & TriangleFlag::E31)) return std::nullopt;  // SOFA's flag for BC
        alpha = 1 - p_bc;
        beta = p_bc;
      }
    }
  }
  const Vec3<Real> p = a + ab * alpha + ac * beta;
  if (!p.allFinite()) return std::nullopt;
  const Vec3<Real> pq = s.center - p;
  const Real norm2 = pq.squaredNorm();
  if (!(norm2 < d.alarm * d.alarm)) return std::nullopt;
  ProximityOutput<Real> out;
  out.value = std::sqrt(norm2);
  if (out.value > Real(1e-15)) {
    out.normal = pq / out.value;
  } else {
    out.normal = Vec3<Real>::UnitX();
    out.null_distance = true;
  }
  out.value -= d.contact;
  out.point[0] = p;
  out.point[1] = sphere_point(s, out.normal);
  return out;
}

namespace {

// Appends a rule's output with its id.
template <class Real>
int append(const std::optional<ProximityOutput<Real>>& out, std::int64_t id, std::vector<DetectionOutput<Real>>& outputs) {
  if (!out) return 0;
  DetectionOutput<Real> detection;
  static_cast<ProximityOutput<Real>&>(detection) = *out;
  detection.id = id;
  outputs.push_back(detection);
  return 1;
}

// The id of the pairs SOFA numbers by the larger model.
template <class Real>
std::int64_t larger_model_index(Index i1, Index i2, const NewProximityPair<Real>& pair) {
  return pair.size1 > pair.size2 ? i1 : i2;
}

}  // namespace

template <class Real>
int new_proximity_intersection(const PointElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_point_point(e1.p, e2.p, pair.distances), larger_model_index(e1.index, e2.index, pair), outputs);
}

template <class Real>
int new_proximity_intersection(const LineElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_line_point(e1.p1, e1.p2, e2.p, pair.distances), e2.index, outputs);
}

template <class Real>
int new_proximity_intersection(const LineElement<Real>& e1, const LineElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_line_line(e1.p1, e1.p2, e2.p1, e2.p2, pair.distances), larger_model_index(e1.index, e2.index, pair),
                outputs);
}

template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_triangle_point(e1.p1, e1.p2, e1.p3, e2.p, e1.flags, pair.distances), e2.index, outputs);
}

template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const LineElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  const auto& d = pair.distances;
  const std::int64_t id = e2.index;
  const int f = e1.flags;
  int n = 0;
  if (f & TriangleFlag::P1) n += append(new_proximity_line_point(e2.p1, e2.p2, e1.p1, d, true), id, outputs);
  if (f & TriangleFlag::P2) n += append(new_proximity_line_point(e2.p1, e2.p2, e1.p2, d, true), id, outputs);
  if (f & TriangleFlag::P3) n += append(new_proximity_line_point(e2.p1, e2.p2, e1.p3, d, true), id, outputs);
  n += append(new_proximity_triangle_point(e1.p1, e1.p2, e1.p3, e2.p1, f, d), id, outputs);
  n += append(new_proximity_triangle_point(e1.p1, e1.p2, e1.p3, e2.p2, f, d), id, outputs);
  if (pair.use_line_line) {
    if (f & TriangleFlag::E12) n += append(new_proximity_line_line(e1.p1, e1.p2, e2.p1, e2.p2, d), id, outputs);
    if (f & TriangleFlag::E23) n += append(new_proximity_line_line(e1.p2, e1.p3, e2.p1, e2.p2, d), id, outputs);
    if (f & TriangleFlag::E31) n += append(new_proximity_line_line(e1.p3, e1.p1, e2.p1, e2.p2, d), id, outputs);
  }
  return n;
}

namespace {

// Triangle–Triangle with triangle 2's plane and a way to triangle 1's (made only when needed).
template <class Real, class Plane1>
int triangle_triangle(const TriangleElement<Real>& e1, const Plane1& plane1, const TriangleElement<Real>& e2,
                      const TrianglePlane<Real>& t2, const NewProximityPair<Real>& pair, std::vector<DetectionOutput<Real>>& outputs) {
  if (pair.same_model) {
    for (const Index v : e1.vertices)
      for (const Index w : e2.vertices)
        if (v == w) return 0;  // neighbours of one model
  }
  const auto& d = pair.distances;
  const std::int64_t id1 = std::int64_t(e1.index) * 3;
  const std::int64_t id2 = std::int64_t(pair.size1) * 3 + std::int64_t(e2.index) * 12;
  const int f1 = e1.flags, f2 = e2.flags;
  const Vec3<Real>* p[3] = {&e1.p1, &e1.p2, &e1.p3};
  const Vec3<Real>* q[3] = {&e2.p1, &e2.p2, &e2.p3};
  int n = 0;
  // Triangle 1's vertices against triangle 2, swapped so that they stay point[0]; SOFA tests the
  // first one whatever its flag.
  for (int k = 0; k < 3; ++k)
    if (k == 0 || (f1 & (TriangleFlag::P1 << k)))
      n += append(triangle_point(t2, *p[k], f2, d, true), id1 + k, outputs);
  if (f2 & (TriangleFlag::P1 | TriangleFlag::P2 | TriangleFlag::P3)) {
    const TrianglePlane<Real>& t1 = plane1();
    for (int k = 0; k < 3; ++k)
      if (f2 & (TriangleFlag::P1 << k))
        n += append(triangle_point(t1, *q[k], f1, d, false), id2 + k, outputs);
  }
  if (pair.use_line_line) {
    // Edges in SOFA's order 1-2, 2-3, 3-1: edge m runs from vertex m to vertex m+1.
    constexpr int edge_flag[3] = {TriangleFlag::E12, TriangleFlag::E23, TriangleFlag::E31};
    for (int m = 0; m < 3; ++m) {
      if (!(f1 & edge_flag[m])) continue;
      for (int l = 0; l < 3; ++l)
        if (f2 & edge_flag[l])
          n += append(new_proximity_line_line(*p[m], *p[(m + 1) % 3], *q[l], *q[(l + 1) % 3], d), id2 + 3 + 3 * m + l, outputs);
    }
  }
  return n;
}

}  // namespace

template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const TriangleElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  TrianglePlane<Real> t1;
  const auto plane1 = [&]() -> const TrianglePlane<Real>& { return t1 = TrianglePlane<Real>(e1.p1, e1.p2, e1.p3); };
  return triangle_triangle(e1, plane1, e2, TrianglePlane<Real>(e2.p1, e2.p2, e2.p3), pair, outputs);
}

template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const TrianglePlane<Real>& plane1, const TriangleElement<Real>& e2,
                               const TrianglePlane<Real>& plane2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return triangle_triangle(e1, [&]() -> const TrianglePlane<Real>& { return plane1; }, e2, plane2, pair, outputs);
}

template <class Real>
int new_proximity_intersection(const SphereElement<Real>& e1, const SphereElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_sphere_sphere(e1.sphere, e2.sphere, pair.distances), larger_model_index(e1.index, e2.index, pair),
                outputs);
}

template <class Real>
int new_proximity_intersection(const SphereElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_sphere_point(e1.sphere, e2.p, pair.distances), larger_model_index(e1.index, e2.index, pair), outputs);
}

template <class Real>
int new_proximity_intersection(const LineElement<Real>& e1, const SphereElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_line_sphere(e1.p1, e1.p2, e2.sphere, pair.distances), e2.index, outputs);
}

template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const SphereElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs) {
  return append(new_proximity_triangle_sphere(e1.p1, e1.p2, e1.p3, e2.sphere, e1.flags, pair.distances), e2.index, outputs);
}

#define FASTCOROT_NEW_PROXIMITY_PAIR(Real, First, Second)                                                          \
  template int new_proximity_intersection(const First<Real>&, const Second<Real>&, const NewProximityPair<Real>&, \
                                          std::vector<DetectionOutput<Real>>&);
#define FASTCOROT_NEW_PROXIMITY(Real)                                                                                               \
  template std::optional<ProximityOutput<Real>> new_proximity_point_point(const Vec3<Real>&, const Vec3<Real>&,                    \
                                                                          const ProximityDistances<Real>&);                         \
  template std::optional<ProximityOutput<Real>> new_proximity_line_point(const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&,  \
                                                                         const ProximityDistances<Real>&, bool);                    \
  template std::optional<ProximityOutput<Real>> new_proximity_line_line(const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&,   \
                                                                        const Vec3<Real>&, const ProximityDistances<Real>&);        \
  template std::optional<ProximityOutput<Real>> new_proximity_triangle_point(                                                       \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, int, const ProximityDistances<Real>&, bool);      \
  template std::optional<ProximityOutput<Real>> new_proximity_sphere_sphere(const ProximitySphere<Real>&,                          \
                                                                            const ProximitySphere<Real>&, ProximityDistances<Real>); \
  template std::optional<ProximityOutput<Real>> new_proximity_sphere_point(const ProximitySphere<Real>&, const Vec3<Real>&,        \
                                                                           ProximityDistances<Real>);                               \
  template std::optional<ProximityOutput<Real>> new_proximity_line_sphere(const Vec3<Real>&, const Vec3<Real>&,                    \
                                                                          const ProximitySphere<Real>&, ProximityDistances<Real>);  \
  template std::optional<ProximityOutput<Real>> new_proximity_triangle_sphere(                                                      \
      const Vec3<Real>&, const Vec3<Real>&, const Vec3<Real>&, const ProximitySphere<Real>&, int, ProximityDistances<Real>);        \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, PointElement, PointElement)                                                                    \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, LineElement, PointElement)                                                                     \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, LineElement, LineElement)                                                                      \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, TriangleElement, PointElement)                                                                 \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, TriangleElement, LineElement)                                                                  \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, TriangleElement, TriangleElement)                                                              \
  template int new_proximity_intersection(const TriangleElement<Real>&, const TrianglePlane<Real>&, const TriangleElement<Real>&,    \
                                          const TrianglePlane<Real>&, const NewProximityPair<Real>&,                                \
                                          std::vector<DetectionOutput<Real>>&);                                                     \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, SphereElement, SphereElement)                                                                  \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, SphereElement, PointElement)                                                                   \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, LineElement, SphereElement)                                                                    \
  FASTCOROT_NEW_PROXIMITY_PAIR(Real, TriangleElement, SphereElement)
FASTCOROT_NEW_PROXIMITY(float)
FASTCOROT_NEW_PROXIMITY(double)
#undef FASTCOROT_NEW_PROXIMITY
#undef FASTCOROT_NEW_PROXIMITY_PAIR

}  // namespace fastcorot
