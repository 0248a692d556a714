// The pair rules of SOFA's LocalMinDistance intersection method
// (Sofa/Component/Collision/Detection/ Intersection: LocalMinDistance.{h,cpp}) with its cone
// filters, as pure functions of positions and of the neighbourhood the filters read
// (docs/collision.md §2.4, §8 step 4). The geometry is MinProximity's (collision/intersections.h)
// with other thresholds; each side of a pair then has to "see" the other through its cone, which
// makes the method one-sided: a point that crossed a surface is not found.
//
// Settings (LocalMinDistance's data): filterIntersection true, angleCone 0, coneFactor 0.5,
// useLMDFilters false; the distances are BaseProximityIntersection's (alarmDistance 1.0,
// contactDistance 0.5, plus the models' contactDistance, plus a sphere's radius:
// ProximityDistances).
//
// Rules, first element first; every parameter test below is SOFA's, ends as written ("in [x, y]":
// x and y kept). point[0] lies on the first element, point[1] on the second, normal = unit(point[1]
// − point[0]), value = |point[1] − point[0]| − C; an output needs |point[1] − point[0]| < A.
// - Point–Point: the two points.
// - Line–Point: the foot of the point on segment AB, α = AP·AB / AB·AB in [1e-6, 0.999999]
//   (MinProximity clamps α to [0, 1] instead); skipped when |AB| < 1e-12 |AP|.
// - Line–Line: the closest points of the two lines (Cramer's rule); |det| ≤ 1e-30 is parallel, then
//   α = β = ½; else α, β in [1e-15, 1 − 1e-15] (MinProximity: 1e-15 and [1e-6, 0.999999]).
// - Triangle–Point: the projection on the plane, α ≥ 1e-6, β ≥ 1e-6, α + β ≤ 0.999999 (as
//   MinProximity).
// - Sphere–Point: the sphere's centre and the point, A and C plus the radius.
// - Line–Sphere: as Line–Point with the centre, radius added; the true foot point (MinProximity's
//   Line–Sphere takes the mirror of it about the segment's middle).
// - Triangle–Sphere: as Triangle–Point with the centre, radius added.
// - Sphere–Sphere: the centres, both radii added, A exclusive (MinProximity's, from
//   DiscreteIntersection, keeps a distance equal to A). No filter: a sphere accepts every
//   direction.
// Only Vec3 spheres: LocalMinDistance registers no rigid sphere rule.
// Ids (for the caller): Triangle–Point, Line–Point, Line–Sphere, Triangle–Sphere: the point's or
// sphere's index; Point–Point, Line–Line, Sphere–Point, Sphere–Sphere: the first element's index
// when its model has more elements than the second's, else the second's.
//
// Cone filters (SOFA's testValidity), applied unless useLMDFilters, each side with v = the vector
// from its own point toward the other element's point; filterIntersection=false accepts everything:
// - Triangle (a, b, c): rejects when ((b − a) × (c − a))·v < 0, unless the triangle model's
// bothSide.
// - Point: only when a LineCollisionModel is in the point model's node or above it (SOFA's
//   Node::get, searching up); otherwise, and for a point with no triangle and no edge, it accepts.
//   nMean = the sum of the unit normals of the topology's triangles around the vertex, or, when it
//   has none, of the unit directions from each adjacent edge's other end to the vertex; when
//   |nMean| > 1e-10 it is normalised and v is rejected when nMean·v < −angleCone |v| (unless the
//   point model's bothSide); then, for each adjacent edge with unit direction e (other end →
//   vertex), v is rejected when e·v < −(max(0, coneFactor nMean·e) + angleCone) |v| (bothSide does
//   not skip this, and a tiny nMean is used there unnormalised).
// - Line (segment AB, unit direction u): with exactly two triangles around the edge (the topology's
//   edge of the same index; SOFA's list puts the triangles that run along the edge's stored
//   direction in front, the last of them first, then the others in order), "left" is the list's
//   first when it lists (A, B) in its own cyclic order, else the second; "right" is the other. n₁,
//   n₂ the right's and left's unit normals, nMean = unit(n₁ + n₂), t₁ = unit(n₁ × u), t₂ = unit(u ×
//   n₂) (each points away from its triangle, in its plane). Rejected when nMean·v < 0 (no angleCone
//   here; skipped by the line model's bothSide), or tᵢ·v < −(max(0, coneFactor nMean·tᵢ) +
//   angleCone) |v|. With another number of triangles (a boundary edge, a bare polyline): rejected
//   when |u·unit(v)| > angleCone + 1e-4, i.e. unless v is nearly perpendicular to the segment (it
//   catches the parallel case). With angleCone 0 a flat edge (n₁ = n₂) keeps only v exactly along
//   the normal.
// SOFA normalises with its Vec::normalize: a vector of norm ≤ machine epsilon is left as it is.
//
// Beyond SOFA: a degenerate triangle (Gram determinant not > 0) or a segment of zero length gives
// no output (SOFA divides by zero; its triangle filter happens to reject those NaN); a zero
// distance gives the triangle's unit normal (Triangle–Point, Triangle–Sphere) or (1, 0, 0), with
// `null_distance` set (SOFA divides by it: a NaN normal).
#pragma once

#include "fastcorot/collision/intersections.h"

#include <optional>
#include <span>
#include <type_traits>
#include <vector>

namespace fastcorot {

template <class Real>
struct LocalMinDistanceSettings {
  bool filter_intersection = true;  // filterIntersection
  Real angle_cone = 0;              // angleCone
  Real cone_factor = 0.5;           // coneFactor
  bool use_lmd_filters = false;     // useLMDFilters: true skips every cone test
};

// What the point filter reads around one vertex.
template <class Real>
struct LocalMinDistancePointCone {
  // Σ unit normals ((x₁ − x₀) × (x₂ − x₀)) of the triangles around the vertex in ascending order,
  // or, with none, Σ unit (vertex − other end) over its edges in ascending order.
  Vec3<Real> normal_sum = Vec3<Real>::Zero();
  std::span<const Vec3<Real>> edge_directions;  // unit (vertex − other end), one per adjacent edge
  bool both_side = false;                       // the point model's bothSide
};

// What the line filter reads around one edge.
template <class Real>
struct LocalMinDistanceLineCone {
  bool two_triangles = false;                    // exactly two triangles around the edge
  Vec3<Real> right_normal = Vec3<Real>::Zero();  // unit normals of the right and left triangles
  Vec3<Real> left_normal = Vec3<Real>::Zero();
  bool both_side = false;  // the line model's bothSide
};

// SOFA's testValidity. `v`: from this element's point toward the other element's point.
// Point: `cone` null when no LineCollisionModel is in the point model's node or above it.
template <class Real>
bool local_min_distance_point_validity(
    const LocalMinDistancePointCone<std::type_identity_t<Real>>* cone, const Vec3<Real>& v,
    const LocalMinDistanceSettings<Real>& s);
template <class Real>
bool local_min_distance_line_validity(const Vec3<Real>& a, const Vec3<Real>& b,
                                      const LocalMinDistanceLineCone<Real>& cone,
                                      const Vec3<Real>& v, const LocalMinDistanceSettings<Real>& s);
template <class Real>
bool local_min_distance_triangle_validity(const Vec3<Real>& a, const Vec3<Real>& b,
                                          const Vec3<Real>& c, bool both_side, const Vec3<Real>& v,
                                          const LocalMinDistanceSettings<Real>& s);

// The rules. A point's cone: as above (null: no filter); a segment's and a triangle's cones are
// always tested (a LocalMinDistanceLineCone{} is a segment with no two triangles around it).
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_point_point(
    const Vec3<Real>& p, const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
    const Vec3<Real>& q, const LocalMinDistancePointCone<std::type_identity_t<Real>>* q_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s);
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_point(
    const Vec3<Real>& a, const Vec3<Real>& b, const LocalMinDistanceLineCone<Real>& line_cone,
    const Vec3<Real>& p, const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s);
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_line(
    const Vec3<Real>& a, const Vec3<Real>& b, const LocalMinDistanceLineCone<Real>& ab_cone,
    const Vec3<Real>& c, const Vec3<Real>& e, const LocalMinDistanceLineCone<Real>& ce_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s);
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_triangle_point(
    const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c, bool triangle_both_side,
    const Vec3<Real>& p, const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone,
    const ProximityDistances<Real>& d, const LocalMinDistanceSettings<Real>& s);
// Spheres: `d` without the radius (added here); Vec3 spheres only (`rigid` must be false).
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_sphere_point(
    const ProximitySphere<Real>& sphere, const Vec3<Real>& p,
    const LocalMinDistancePointCone<std::type_identity_t<Real>>* p_cone, ProximityDistances<Real> d,
    const LocalMinDistanceSettings<Real>& s);
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_line_sphere(
    const Vec3<Real>& a, const Vec3<Real>& b, const LocalMinDistanceLineCone<Real>& line_cone,
    const ProximitySphere<Real>& sphere, ProximityDistances<Real> d,
    const LocalMinDistanceSettings<Real>& s);
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_triangle_sphere(
    const Vec3<Real>& a, const Vec3<Real>& b, const Vec3<Real>& c, bool triangle_both_side,
    const ProximitySphere<Real>& sphere, ProximityDistances<Real> d,
    const LocalMinDistanceSettings<Real>& s);
template <class Real>
std::optional<ProximityOutput<Real>> local_min_distance_sphere_sphere(
    const ProximitySphere<Real>& sphere1, const ProximitySphere<Real>& sphere2,
    ProximityDistances<Real> d);

// The shells SOFA's filters read from a model's topology (getTrianglesAroundVertex and
// getEdgesAroundVertex in ascending element order, getTrianglesAroundEdge in SOFA's order above),
// built once. Pass the
// topology the model links to, all of its triangles and edges (a volume topology's triangles
// include inner ones; quads are not read); edge k is the LineCollisionModel's element k.
struct LocalMinDistanceTopology {
  Index point_count = 0;
  std::vector<Triangle> triangles;
  std::vector<Edge> edges;
  std::vector<Index> vertex_triangle_offsets, vertex_triangles;  // CSR, #V + 1 offsets
  std::vector<Index> vertex_edge_offsets, vertex_edge_other;  // CSR: each adjacent edge's other end
  std::vector<std::array<Index, 2>> edge_right_left;          // triangles; −1 unless exactly two
};

// Throws fastcorot::Error for an index outside [0, point_count) or an edge listed twice.
LocalMinDistanceTopology local_min_distance_topology(Index point_count,
                                                     std::span<const Triangle> triangles,
                                                     std::span<const Edge> edges);

// The cones at given positions (recomputed each step, as SOFA reads the current positions).
template <class Real>
struct LocalMinDistanceNeighbourhood {
  std::vector<Vec3<Real>> normal_sum;       // per vertex
  std::vector<Index> edge_offsets;          // per vertex, into edge_directions (#V + 1)
  std::vector<Vec3<Real>> edge_directions;  // per vertex's adjacent edge
  std::vector<LocalMinDistanceLineCone<Real>> line_cones;  // per edge (both_side false)

  LocalMinDistancePointCone<Real> point_cone(Index vertex, bool both_side = false) const;
  LocalMinDistanceLineCone<Real> line_cone(Index edge, bool both_side = false) const;
};

// Throws fastcorot::Error when `x` does not hold the topology's point count.
template <class Real>
void compute_local_min_distance_neighbourhood(const LocalMinDistanceTopology& topology,
                                              std::span<const Vec3<Real>> x,
                                              LocalMinDistanceNeighbourhood<Real>& out);

}  // namespace fastcorot
