// The intersection methods of SOFA's collision pipeline as the narrow phase calls them on one pair
// of collision elements: MinProximityIntersection (collision/intersections.h),
// NewProximityIntersection (collision/new_proximity.h), LocalMinDistance (collision/
// local_min_distance.h) and DiscreteIntersection (spheres only: SOFA's computeIntersectionSphere,
// overlapping spheres, no alarm or contact distance, the models' contactDistance ignored). Which
// model pairs each method has a rule for, in which order (Triangle, Line, Sphere, Point: the first
// of a pair is the earlier in that list), the distances it uses, and the outputs of one element pair
// with the ids SOFA gives them. Design: docs/collision.md (§2.4).
#pragma once

#include "fastcorot/collision/collision_model.h"
#include "fastcorot/collision/intersections.h"
#include "fastcorot/collision/local_min_distance.h"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace fastcorot {

enum class IntersectionMethod { min_proximity, new_proximity, local_min_distance, discrete };

template <class Real>
struct IntersectionSettings {
  IntersectionMethod method = IntersectionMethod::min_proximity;
  Real alarm_distance = 1;      // alarmDistance (not read by DiscreteIntersection)
  Real contact_distance = 0.5;  // contactDistance (idem)
  // MinProximity's and LocalMinDistance's flags; NewProximity reads use_line_line only (its
  // default false, the others' true).
  bool use_point_point = true, use_line_point = true, use_line_line = true, use_sphere_triangle = true;
  bool use_surface_normals = false;
  LocalMinDistanceSettings<Real> local_min_distance;
};

// One output of an element pair: the elements (of the pair's first and second model), SOFA's id,
// and the rule's points, normal and value.
template <class Real>
struct ElementOutput {
  Index first = 0, second = 0;
  std::int64_t id = 0;
  ProximityOutput<Real> proximity;
};

// The rank that orders a pair's models: a rule takes the higher rank first.
int element_rank(CollisionElements kind);

// Whether `settings.method` has a rule for models of kinds (a, b), a of rank ≥ b's.
template <class Real>
bool has_rule(const IntersectionSettings<Real>& settings, CollisionElements a, CollisionElements b);
// The same for two models, a first: LocalMinDistance has no rule for rigid spheres (SOFA registers
// its sphere rules for Vec3 spheres only).
template <class Real>
bool has_rule(const IntersectionSettings<Real>& settings, const CollisionModel<Real>& a, const CollisionModel<Real>& b);

// The distances of a pair of models (without sphere radii, which the rules add).
template <class Real>
ProximityDistances<Real> pair_distances(const IntersectionSettings<Real>& settings, const CollisionModel<Real>& m1,
                                        const CollisionModel<Real>& m2);

// Appends the outputs of each pair (e1, e2), element e1 of m1 against element e2 of m2 (m1's kind of
// rank ≥ m2's), pair after pair.
template <class Real>
void intersect_elements(const IntersectionSettings<Real>& settings, const CollisionModel<Real>& m1, const CollisionModel<Real>& m2,
                        std::span<const std::pair<Index, Index>> pairs, const ProximityDistances<Real>& d,
                        std::vector<ElementOutput<Real>>& outputs);

}  // namespace fastcorot
