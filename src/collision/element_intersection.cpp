#include "fastcorot/collision/element_intersection.h"

#include "fastcorot/collision/new_proximity.h"

namespace fastcorot {

int element_rank(CollisionElements kind) {
  switch (kind) {
    case CollisionElements::triangles: return 3;
    case CollisionElements::lines: return 2;
    case CollisionElements::spheres: return 1;
    default: return 0;
  }
}

template <class Real>
bool has_rule(const IntersectionSettings<Real>& s, CollisionElements a, CollisionElements b) {
  using E = CollisionElements;
  const auto is = [&](E x, E y) { return a == x && b == y; };
  switch (s.method) {
    case IntersectionMethod::discrete: return is(E::spheres, E::spheres);
    case IntersectionMethod::new_proximity:
      // NewProximityIntersection registers every mesh pair (its Line–Line rule reads useLineLine).
      return is(E::spheres, E::spheres) || is(E::spheres, E::points) || is(E::points, E::points) || is(E::lines, E::points) ||
             is(E::lines, E::lines) || is(E::triangles, E::points) || is(E::triangles, E::lines) || is(E::triangles, E::triangles) ||
             is(E::lines, E::spheres) || is(E::triangles, E::spheres);
    default:
      // MinProximityIntersection and LocalMinDistance: no Triangle–Line, no Triangle–Triangle.
      return is(E::spheres, E::spheres) || (is(E::spheres, E::points) && s.use_point_point) ||
             (is(E::points, E::points) && s.use_point_point) || (is(E::lines, E::points) && s.use_line_point) ||
             (is(E::lines, E::lines) && s.use_line_line) || is(E::triangles, E::points) ||
             (is(E::lines, E::spheres) && s.use_line_point) || (is(E::triangles, E::spheres) && s.use_sphere_triangle);
  }
}

template <class Real>
bool has_rule(const IntersectionSettings<Real>& s, const CollisionModel<Real>& a, const CollisionModel<Real>& b) {
  const auto rigid_sphere = [](const CollisionModel<Real>& m) { return m.kind == CollisionElements::spheres && m.points->is_rigid(); };
  if (s.method == IntersectionMethod::local_min_distance && (rigid_sphere(a) || rigid_sphere(b))) return false;
  return has_rule(s, a.kind, b.kind);
}

template <class Real>
ProximityDistances<Real> pair_distances(const IntersectionSettings<Real>& s, const CollisionModel<Real>& m1, const CollisionModel<Real>& m2) {
  if (s.method == IntersectionMethod::discrete) return {Real(0), Real(0)};
  return {s.alarm_distance + m1.contact_distance + m2.contact_distance, s.contact_distance + m1.contact_distance + m2.contact_distance};
}

namespace {

template <class Real>
struct Elements {
  const CollisionModel<Real>& model;
  const std::vector<Vec3<Real>>& x;
  explicit Elements(const CollisionModel<Real>& m) : model(m), x(m.points->positions()) {}
  const Vec3<Real>& at(Index p) const { return x[static_cast<std::size_t>(p)]; }
  const Edge& edge(Index e) const { return model.edges[static_cast<std::size_t>(e)]; }
  const Triangle& triangle(Index e) const { return model.triangles[static_cast<std::size_t>(e)]; }
  ProximitySphere<Real> sphere(Index e) const { return {at(e), model.radii[static_cast<std::size_t>(e)], model.points->is_rigid()}; }
  int flags(Index e) const { return model.triangle_flags.empty() ? 0 : model.triangle_flags[static_cast<std::size_t>(e)]; }
  PointElement<Real> point_element(Index e) const { return {at(e), e}; }
  LineElement<Real> line_element(Index e) const { return {at(edge(e)[0]), at(edge(e)[1]), e}; }
  TriangleElement<Real> triangle_element(Index e) const {
    const Triangle& t = triangle(e);
    return {at(t[0]), at(t[1]), at(t[2]), t, flags(e), e};
  }
  SphereElement<Real> sphere_element(Index e) const { return {sphere(e), e}; }
  // LocalMinDistance's cones: a point's only when its filter applies.
  std::optional<LocalMinDistancePointCone<Real>> point_cone(Index e) const {
    if (!model.point_filter || !model.cone_topology) return std::nullopt;
    return model.neighbourhood.point_cone(e, model.both_side);
  }
  LocalMinDistanceLineCone<Real> line_cone(Index e) const {
    if (!model.cone_topology) return LocalMinDistanceLineCone<Real>{false, Vec3<Real>::Zero(), Vec3<Real>::Zero(), model.both_side};
    return model.neighbourhood.line_cone(e, model.both_side);
  }
};

template <class Real>
void min_proximity(const IntersectionSettings<Real>& s, const Elements<Real>& a, Index e1, const Elements<Real>& b, Index e2,
                   const ProximityDistances<Real>& d, std::vector<ElementOutput<Real>>& outputs) {
  using E = CollisionElements;
  const bool first_larger = a.model.size() > b.model.size();
  std::optional<ProximityOutput<Real>> found;
  std::int64_t id = first_larger ? e1 : e2;
  const E k1 = a.model.kind, k2 = b.model.kind;
  if (k1 == E::triangles) {
    const Triangle& t = a.triangle(e1);
    Vec3<Real> normal;
    if (s.use_surface_normals) normal = (a.at(t[1]) - a.at(t[0])).cross(a.at(t[2]) - a.at(t[0])).normalized();
    if (k2 == E::points) {
      found = min_proximity_triangle_point(a.at(t[0]), a.at(t[1]), a.at(t[2]), b.at(e2), d, s.use_surface_normals ? &normal : nullptr);
    } else {
      found = min_proximity_triangle_sphere(a.at(t[0]), a.at(t[1]), a.at(t[2]), b.sphere(e2), d);
    }
    id = e2;
  } else if (k1 == E::lines) {
    const Edge& l = a.edge(e1);
    if (k2 == E::points) {
      found = min_proximity_line_point(a.at(l[0]), a.at(l[1]), b.at(e2), d);
      id = e2;
    } else if (k2 == E::spheres) {
      found = min_proximity_line_sphere(a.at(l[0]), a.at(l[1]), b.sphere(e2), d);
      id = e2;
    } else {
      const Edge& r = b.edge(e2);
      found = min_proximity_line_line(a.at(l[0]), a.at(l[1]), b.at(r[0]), b.at(r[1]), d);
    }
  } else if (k1 == E::spheres) {
    found = k2 == E::spheres ? min_proximity_sphere_sphere(a.sphere(e1), b.sphere(e2), d) : min_proximity_sphere_point(a.sphere(e1), b.at(e2), d);
  } else {
    found = min_proximity_point_point(a.at(e1), b.at(e2), d);
  }
  if (found) outputs.push_back({e1, e2, id, *found});
}

template <class Real>
void local_min_distance(const IntersectionSettings<Real>& s, const Elements<Real>& a, Index e1, const Elements<Real>& b, Index e2,
                        const ProximityDistances<Real>& d, std::vector<ElementOutput<Real>>& outputs) {
  using E = CollisionElements;
  const auto& f = s.local_min_distance;
  const bool first_larger = a.model.size() > b.model.size();
  std::optional<ProximityOutput<Real>> found;
  std::int64_t id = first_larger ? e1 : e2;
  const E k1 = a.model.kind, k2 = b.model.kind;
  const auto cone_of = [](const std::optional<LocalMinDistancePointCone<Real>>& c) { return c ? &*c : nullptr; };
  if (k1 == E::triangles) {
    const Triangle& t = a.triangle(e1);
    if (k2 == E::points) {
      const auto cone = b.point_cone(e2);
      found = local_min_distance_triangle_point(a.at(t[0]), a.at(t[1]), a.at(t[2]), a.model.both_side, b.at(e2), cone_of(cone), d, f);
    } else {
      found = local_min_distance_triangle_sphere(a.at(t[0]), a.at(t[1]), a.at(t[2]), a.model.both_side, b.sphere(e2), d, f);
    }
    id = e2;
  } else if (k1 == E::lines) {
    const Edge& l = a.edge(e1);
    if (k2 == E::points) {
      const auto cone = b.point_cone(e2);
      found = local_min_distance_line_point(a.at(l[0]), a.at(l[1]), a.line_cone(e1), b.at(e2), cone_of(cone), d, f);
      id = e2;
    } else if (k2 == E::spheres) {
      found = local_min_distance_line_sphere(a.at(l[0]), a.at(l[1]), a.line_cone(e1), b.sphere(e2), d, f);
      id = e2;
    } else {
      const Edge& r = b.edge(e2);
      found = local_min_distance_line_line(a.at(l[0]), a.at(l[1]), a.line_cone(e1), b.at(r[0]), b.at(r[1]), b.line_cone(e2), d, f);
    }
  } else if (k1 == E::spheres) {
    if (k2 == E::spheres) {
      found = local_min_distance_sphere_sphere(a.sphere(e1), b.sphere(e2), d);
    } else {
      const auto cone = b.point_cone(e2);
      found = local_min_distance_sphere_point(a.sphere(e1), b.at(e2), cone_of(cone), d, f);
    }
  } else {
    const auto c1 = a.point_cone(e1), c2 = b.point_cone(e2);
    found = local_min_distance_point_point(a.at(e1), cone_of(c1), b.at(e2), cone_of(c2), d, f);
  }
  if (found) outputs.push_back({e1, e2, id, *found});
}

// NewProximityIntersection's rules over a list of element pairs of the same two models: what the
// models share (the pair's settings, the rule for their kinds) once for the list.
template <class Real>
void new_proximity(const IntersectionSettings<Real>& s, const Elements<Real>& a, const Elements<Real>& b,
                   std::span<const std::pair<Index, Index>> pairs, const ProximityDistances<Real>& d,
                   std::vector<ElementOutput<Real>>& outputs) {
  using E = CollisionElements;
  NewProximityPair<Real> pair;
  pair.distances = d;
  pair.size1 = a.model.size();
  pair.size2 = b.model.size();
  pair.same_model = &a.model == &b.model;
  pair.use_line_line = s.use_line_line;
  std::vector<DetectionOutput<Real>> found;
  // rule(e1, e2) appends a pair's outputs to `found`; they go to `outputs` with the pair's elements.
  const auto each_pair = [&](const auto& rule) {
    for (const auto& [e1, e2] : pairs) {
      found.clear();
      rule(e1, e2);
      for (const auto& o : found) outputs.push_back({e1, e2, o.id, static_cast<const ProximityOutput<Real>&>(o)});
    }
  };
  const auto each = [&](auto first, auto second) {
    each_pair([&](Index e1, Index e2) { new_proximity_intersection(first(e1), second(e2), pair, found); });
  };
  const auto triangle = [&](const Elements<Real>& m) { return [&m](Index e) { return m.triangle_element(e); }; };
  const auto line = [&](const Elements<Real>& m) { return [&m](Index e) { return m.line_element(e); }; };
  const auto sphere = [&](const Elements<Real>& m) { return [&m](Index e) { return m.sphere_element(e); }; };
  const auto point = [&](const Elements<Real>& m) { return [&m](Index e) { return m.point_element(e); }; };
  const E k1 = a.model.kind, k2 = b.model.kind;
  if (k1 == E::triangles && k2 == E::triangles) {
    // Each triangle's element and plane made once for the list, when the list first meets it.
    struct Made {
      TriangleElement<Real> element;
      TrianglePlane<Real> plane;
    };
    thread_local std::vector<Made> made[2];
    thread_local std::vector<char> done[2];
    const Elements<Real>* models[2] = {&a, &b};
    for (int side = 0; side < 2; ++side) {
      made[side].resize(models[side]->model.size());
      done[side].assign(models[side]->model.size(), 0);
    }
    const auto get = [&](int side, Index e) -> const Made& {
      const auto i = static_cast<std::size_t>(e);
      if (!done[side][i]) {
        const TriangleElement<Real> t = models[side]->triangle_element(e);
        made[side][i] = {t, TrianglePlane<Real>(t.p1, t.p2, t.p3)};
        done[side][i] = 1;
      }
      return made[side][i];
    };
    each_pair([&](Index e1, Index e2) {
      const Made &t1 = get(0, e1), &t2 = get(1, e2);
      new_proximity_intersection(t1.element, t1.plane, t2.element, t2.plane, pair, found);
    });
  } else if (k1 == E::triangles) {
    if (k2 == E::lines) each(triangle(a), line(b));
    if (k2 == E::spheres) each(triangle(a), sphere(b));
    if (k2 == E::points) each(triangle(a), point(b));
  } else if (k1 == E::lines) {
    if (k2 == E::lines) each(line(a), line(b));
    if (k2 == E::spheres) each(line(a), sphere(b));
    if (k2 == E::points) each(line(a), point(b));
  } else if (k1 == E::spheres) {
    if (k2 == E::spheres) each(sphere(a), sphere(b));
    if (k2 == E::points) each(sphere(a), point(b));
  } else {
    each(point(a), point(b));
  }
}

// SOFA's DiscreteIntersection::computeIntersectionSphere for two Vec3 spheres: overlapping (the
// squared centre distance at most (r₁ + r₂)²), points the centres, value = distance − r₁ − r₂.
template <class Real>
void discrete(const Elements<Real>& a, Index e1, const Elements<Real>& b, Index e2, std::vector<ElementOutput<Real>>& outputs) {
  const ProximitySphere<Real> s = a.sphere(e1), t = b.sphere(e2);
  const Real r = s.radius + t.radius;
  const Vec3<Real> gap = t.center - s.center;
  const Real norm2 = gap.squaredNorm();
  if (norm2 > r * r) return;
  ElementOutput<Real> o;
  o.first = e1;
  o.second = e2;
  o.id = a.model.size() > b.model.size() ? e1 : e2;
  const Real distance = std::sqrt(norm2);
  if (distance > Real(1e-15)) {
    o.proximity.normal = gap / distance;
  } else {
    // Beyond SOFA: concentric spheres (SOFA divides by zero) get the normal (1, 0, 0).
    o.proximity.normal = Vec3<Real>::UnitX();
    o.proximity.null_distance = true;
  }
  // SOFA's getContactPointByNormal: a Vec3 sphere's centre, a rigid sphere's surface point.
  const Vec3<Real>& n = o.proximity.normal;
  o.proximity.point[0] = s.rigid ? Vec3<Real>(s.center + n * s.radius) : s.center;
  o.proximity.point[1] = t.rigid ? Vec3<Real>(t.center - n * t.radius) : t.center;
  o.proximity.value = distance - r;
  outputs.push_back(o);
}

}  // namespace

template <class Real>
void intersect_elements(const IntersectionSettings<Real>& s, const CollisionModel<Real>& m1, const CollisionModel<Real>& m2,
                        std::span<const std::pair<Index, Index>> pairs, const ProximityDistances<Real>& d,
                        std::vector<ElementOutput<Real>>& outputs) {
  const Elements<Real> a(m1), b(m2);
  switch (s.method) {
    case IntersectionMethod::min_proximity:
      for (const auto& [e1, e2] : pairs) min_proximity(s, a, e1, b, e2, d, outputs);
      break;
    case IntersectionMethod::local_min_distance:
      for (const auto& [e1, e2] : pairs) local_min_distance(s, a, e1, b, e2, d, outputs);
      break;
    case IntersectionMethod::new_proximity: new_proximity(s, a, b, pairs, d, outputs); break;
    case IntersectionMethod::discrete:
      for (const auto& [e1, e2] : pairs) discrete(a, e1, b, e2, outputs);
      break;
  }
}

template bool has_rule(const IntersectionSettings<double>&, CollisionElements, CollisionElements);
template bool has_rule(const IntersectionSettings<double>&, const CollisionModel<double>&, const CollisionModel<double>&);
template ProximityDistances<double> pair_distances(const IntersectionSettings<double>&, const CollisionModel<double>&,
                                                   const CollisionModel<double>&);
template void intersect_elements(const IntersectionSettings<double>&, const CollisionModel<double>&, const CollisionModel<double>&,
                                 std::span<const std::pair<Index, Index>>, const ProximityDistances<double>&,
                                 std::vector<ElementOutput<double>>&);

}  // namespace fastcorot
