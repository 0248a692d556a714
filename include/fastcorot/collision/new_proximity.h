// The pair rules of SOFA's NewProximityIntersection (Sofa/Component/Collision/Detection/Intersection:
// NewProximityIntersection.{h,inl}, MeshNewProximityIntersection.{h,inl,cpp}) as pure functions,
// with the ownership flags of SOFA's triangle and line models (Sofa/Component/Collision/Geometry:
// TriangleCollisionModel.{h,inl} getTriangleFlags, LineCollisionModel.{h,inl} getLineFlags) that
// decide which element reports a shared vertex or edge. docs/collision.md §2.4 and §9.
//
// Ownership. A triangle owns vertex k (bit P1 << k) when it is the first entry of the topology's
// triangles-around-vertex list, which both SOFA triangle containers fill in index order: the
// triangle of lowest index around the vertex. It owns its edge j, the edge (t[j+1], t[j+2]) opposite
// vertex j (bit E23 << j), when it is the first entry of the triangles-around-edge list. That list
// is not in index order: a triangle that runs along the edge in the edge's stored direction (the
// edge's first vertex is t[j+1]) is inserted at the front, any other appended. Edges derived from
// triangles are stored in the direction of the first triangle that has them, so on a consistently
// oriented mesh the owner is the edge's first triangle; where orientations disagree it is the
// *last* triangle running along the stored direction. BE23 << j marks an edge with one triangle. A
// line owns its vertex k (bit P1 << k) when it is the first edge (index order) around the vertex;
// BP1 << k marks a vertex with one edge. NewProximity reads only the triangle bits P1-P3, E12-E31.
//
// Rules (first element first; A, C the alarm and contact distances, spheres adding their radii):
// every rule keeps a pair when its distance² < A² and reports value = distance − C, the normal from
// point[0] to point[1]. Points are clamped onto edges and corners; a clamped closest point is
// reported only when the flags say the triangle owns that edge or corner (interior points always).
// Beyond SOFA: a degenerate triangle (Gram determinant not > 0) or a segment of no length in a
// point rule gives no output (SOFA computes NaN points), and a zero distance gives the normal
// (1, 0, 0) with `null_distance` set (SOFA divides by it: NaN normal; its Triangle–Sphere copy
// already uses (1, 0, 0) below 1e-15).
#pragma once

#include "fastcorot/collision/intersections.h"
#include "fastcorot/core/types.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace fastcorot {

// SOFA's TriangleCollisionModel::TriangleFlag bits (vertices and edges numbered from 1 as SOFA does).
struct TriangleFlag {
  static constexpr int P1 = 1 << 0, P2 = 1 << 1, P3 = 1 << 2;        // owns vertex 1, 2, 3
  static constexpr int E23 = 1 << 3, E31 = 1 << 4, E12 = 1 << 5;     // owns edge 2-3, 3-1, 1-2
  static constexpr int BE23 = 1 << 6, BE31 = 1 << 7, BE12 = 1 << 8;  // that edge has one triangle
  static constexpr int points = P1 | P2 | P3, edges = E12 | E23 | E31, boundary_edges = BE12 | BE23 | BE31;
};

// SOFA's LineCollisionModel::LineFlag bits.
struct LineFlag {
  static constexpr int P1 = 1 << 0, P2 = 1 << 1;    // owns vertex 1, 2
  static constexpr int BP1 = 1 << 2, BP2 = 1 << 3;  // that vertex has one edge
};

// The flags of each triangle of a triangle topology (MeshTopology or TriangleSetTopologyContainer),
// #T. `edges`: the topology's stored edges when it has its own list (a MeshTopology over tetrahedra
// stores them (min, max)); empty: derived from the triangles as both containers do, each in the
// direction of the first triangle that has it. A TriangleCollisionModel's extra triangles, made
// from quads after the topology's triangles, have flags 0 in SOFA: append zeros for them. Errors:
// a vertex not below `point_count`, a triangle edge missing from `edges`.
std::vector<int> triangle_flags(std::span<const Triangle> triangles, std::size_t point_count,
                                std::span<const Edge> edges = {});

// The flags of each edge of a line topology, #E. Errors: a vertex not below `point_count`.
std::vector<int> line_flags(std::span<const Edge> edges, std::size_t point_count);

// ---- Elementary rules: SOFA's static helpers, C already subtracted ---------------------------

// doIntersectionPointPoint: p first, q second.
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_point_point(const Vec3<Real>& p, const Vec3<Real>& q,
                                                               const ProximityDistances<Real>& d);
// doIntersectionLinePoint: segment (a, b), point q; parameter b0/|ab|² clamped to [0, 1], point
// a + ab·α (so the end b is a + ab). `swap_elements` (SOFA's swapElems): q is point[0].
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_line_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& q,
                                                              const ProximityDistances<Real>& d, bool swap_elements = false);
// doIntersectionLineLine: segments (a, b) and (c, e); |det| ≤ 1e-12: both parameters ½ (any
// overlap, also a segment of no length), else both in [1e-6, 0.999999] or nothing. No clamping.
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_line_line(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                             const Vec3<Real>& e, const ProximityDistances<Real>& d);
// doIntersectionTrianglePoint: triangle (a, b, c) with its `flags`, point q. Inside when α, β ≥ ε
// and α + β ≤ 1 − ε (ε = numeric_limits<Real>::epsilon()); else, with pAB = AQ·AB/|AB|² and
// pAC = AQ·AC/|AC|²: corner A (P1) when both < ε; edge AB (E12) when pAB in [ε, 1−ε) and β < ε;
// edge AC (E31) when pAC in [ε, 1−ε) and α < ε; else by pBC = BQ·BC/|BC|²: B (P2) below ε, C (P3)
// above 1 − ε, edge BC (E23) between. SOFA's n and useNormal arguments are unused there (and so
// absent here): bothSide changes no output. `swap_elements`: q is point[0].
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_triangle_point(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                  const Vec3<Real>& q, int flags, const ProximityDistances<Real>& d,
                                                                  bool swap_elements = false);
// Spheres (`d` without the radii, added here). Sphere–Sphere and Sphere–Point: the centres (also for
// rigid spheres), A and C grown by the radii. Line–Sphere: the line–point rule on the centre.
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_sphere_sphere(const ProximitySphere<Real>& s, const ProximitySphere<Real>& t,
                                                                 ProximityDistances<Real> d);
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_sphere_point(const ProximitySphere<Real>& s, const Vec3<Real>& p,
                                                                ProximityDistances<Real> d);
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_line_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const ProximitySphere<Real>& s,
                                                               ProximityDistances<Real> d);
// Triangle–Sphere: SOFA's own copy of the triangle rule, with other thresholds and flags: inside
// when α, β ≥ 1e-6 and α + β ≤ 0.999999; A when pAB < 1e-6 and pAC < 1e-7; edge AB (E12) when
// pAB < 0.999999 and β < 1e-6; edge AC, checked with E12, when pAC < 0.999999 and α < 1e-6; B, C
// by pBC against 1e-6 / 0.999999, edge BC checked with E31. No lower bound on pAB, pAC: at an obtuse
// corner A a centre behind A gets a point on the line AB (or AC) outside the triangle. Distance ≤
// 1e-15: normal (1, 0, 0). point[1] is the sphere's contact point (a rigid sphere's surface point
// c − r n, a Vec3 sphere's centre).
template <class Real>
std::optional<ProximityOutput<Real>> new_proximity_triangle_sphere(const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c,
                                                                   const ProximitySphere<Real>& s, int flags, ProximityDistances<Real> d);

// ---- Element-pair rules: SOFA's computeIntersection of MeshNewProximityIntersection -----------

// An output as SOFA lists it, with its `id` (SOFA's DetectionOutput::id; penalty merges by it).
template <class Real>
struct DetectionOutput : ProximityOutput<Real> {
  std::int64_t id = 0;
};

// The elements: positions and the element's index in its model.
template <class Real>
struct PointElement {
  Vec3<Real> p;
  Index index = 0;
};
template <class Real>
struct LineElement {
  Vec3<Real> p1, p2;
  Index index = 0;
};
template <class Real>
struct TriangleElement {
  Vec3<Real> p1, p2, p3;
  Triangle vertices{};  // its point indices (neighbours share one)
  int flags = 0;        // triangle_flags
  Index index = 0;
};
template <class Real>
struct SphereElement {
  ProximitySphere<Real> sphere;
  Index index = 0;
};

// What the triangle rules compute from a triangle alone (its box, edges and plane), made once for
// all the points tested against it: per element pair, or once per triangle for a list of pairs.
template <class Real>
struct TrianglePlane {
  Vec3<Real> a, ab, ac, normal, low, high;
  Real a00 = 0, a11 = 0, a01 = 0, det = 0, normal2 = 0;
  TrianglePlane() = default;
  TrianglePlane(const Vec3<Real>& pa, const Vec3<Real>& b, const Vec3<Real>& c)
      : a(pa), ab(b - pa), ac(c - pa), normal(ab.cross(ac)), low(pa.cwiseMin(b).cwiseMin(c)), high(pa.cwiseMax(b).cwiseMax(c)) {
    a00 = ab.dot(ab);
    a11 = ac.dot(ac);
    a01 = ab.dot(ac);
    det = a00 * a11 - a01 * a01;
    normal2 = normal.squaredNorm();
  }
};

// What a pair rule needs of the two models.
template <class Real>
struct NewProximityPair {
  ProximityDistances<Real> distances;  // A, C including both models' contactDistance
  std::size_t size1 = 0, size2 = 0;    // the models' element counts
  bool same_model = false;             // a model against itself
  bool use_line_line = false;          // NewProximityIntersection.useLineLine (SOFA's default false)
};

// Each appends SOFA's outputs for the element pair to `outputs`, in SOFA's order, and returns how
// many. ids (i₁, i₂ the elements' indices, n₁, n₂ the model sizes):
// - Point–Point, Line–Line, Sphere–Sphere, Sphere–Point: n₁ > n₂ ? i₁ : i₂.
// - Line–Point, Triangle–Point, Line–Sphere, Triangle–Sphere: i₂.
// - Triangle–Line: i₂ for every output, in order: the triangle's owned corners 1, 2, 3 against the
//   segment (corner first), the segment's ends 1, 2 against the triangle, then with use_line_line
//   its owned edges 1-2, 2-3, 3-1 against the segment. Line–Line model pairs ignore use_line_line.
// - Triangle–Triangle: nothing when same_model and the triangles share a point index. Else
//   3·i₁ + k for vertex k+1 of triangle 1 against triangle 2 (vertex 1 always, SOFA skips its flag;
//   vertices 2, 3 when owned), then 3·n₁ + 12·i₂ + k for vertex k+1 of triangle 2 against
//   triangle 1 (when owned), then with use_line_line 3·n₁ + 12·i₂ + 3 + 3·m + l for edge m of
//   triangle 1 against edge l of triangle 2 (edges in the order 1-2, 2-3, 3-1; both owned).
//   Triangle 1's points are always point[0].
template <class Real>
int new_proximity_intersection(const PointElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const LineElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const LineElement<Real>& e1, const LineElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const LineElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const TriangleElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
// Triangle–Triangle with both triangles' planes made beforehand (the same outputs).
template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const TrianglePlane<Real>& plane1, const TriangleElement<Real>& e2,
                               const TrianglePlane<Real>& plane2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const SphereElement<Real>& e1, const SphereElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const SphereElement<Real>& e1, const PointElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const LineElement<Real>& e1, const SphereElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);
template <class Real>
int new_proximity_intersection(const TriangleElement<Real>& e1, const SphereElement<Real>& e2, const NewProximityPair<Real>& pair,
                               std::vector<DetectionOutput<Real>>& outputs);

}  // namespace fastcorot
