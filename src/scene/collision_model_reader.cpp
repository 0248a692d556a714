#include "collision_model_reader.h"
#include "hexahedron_builders.h"
#include "index_tuples.h"
#include "unsimulated_points.h"

#include "fastcorot/collision/new_proximity.h"
#include "fastcorot/collision/self_collision.h"
#include "fastcorot/core/error.h"
#include "fastcorot/topology/tetrahedron_faces.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <set>

namespace fastcorot::scene_detail {

namespace {

// SOFA's MeshTopology edges from its surface: each triangle's (t[j+1], t[j+2]) as oriented, then
// each quad's sorted, the first occurrence of each pair kept.
std::vector<Edge> surface_edges(const std::vector<Triangle>& triangles, const std::vector<std::array<Index, 4>>& quads) {
  std::vector<Edge> edges;
  std::set<std::pair<Index, Index>> seen;
  const auto add = [&](Index a, Index b, bool sorted) {
    if (!seen.insert({std::min(a, b), std::max(a, b)}).second) return;
    edges.push_back(sorted ? Edge{std::min(a, b), std::max(a, b)} : Edge{a, b});
  };
  for (const auto& t : triangles) {
    for (int j = 0; j < 3; ++j) add(t[static_cast<std::size_t>((j + 1) % 3)], t[static_cast<std::size_t>((j + 2) % 3)], false);
  }
  for (const auto& q : quads) {
    for (int j = 0; j < 4; ++j) add(q[static_cast<std::size_t>((j + 1) % 4)], q[static_cast<std::size_t>((j + 2) % 4)], true);
  }
  return edges;
}

}  // namespace

CollisionModelReader::CollisionModelReader(SceneData& data, Simulation<double>& simulation, const LocateState& locate,
                                           IntersectionMethod method)
    : data_(data), simulation_(simulation), locate_(locate), method_(method) {}

CollisionModel<double> CollisionModelReader::model(Component& c) {
  CollisionModel<double> m;
  m.where = c.where();
  // Node identity (two sibling nodes may share a name).
  m.node = c.node->path + "#" + std::to_string(reinterpret_cast<std::uintptr_t>(c.node));
  const std::string_view type = c.type();
  m.kind = type == "TriangleCollisionModel" ? CollisionElements::triangles
           : type == "LineCollisionModel"   ? CollisionElements::lines
           : type == "SphereCollisionModel" ? CollisionElements::spheres
                                            : CollisionElements::points;
  m.both_side = data_.boolean(c, "bothSide", false);
  m.simulated = data_.boolean(c, "simulated", true);
  m.moving = data_.boolean(c, "moving", true);
  m.self_collision = data_.boolean(c, "selfCollision", false);
  m.contact_distance = data_.real(c, c.has("proximity") && !c.has("contactDistance") ? "proximity" : "contactDistance", 0.0);
  m.contact_stiffness = data_.real(c, "contactStiffness", 10.0);
  m.contact_friction = data_.real(c, "contactFriction", 0.0);
  if (!(m.contact_distance >= 0) || !(m.contact_stiffness >= 0) || !(m.contact_friction >= 0)) {
    throw error_at(c.where(), make_error("contactDistance, contactStiffness and contactFriction must be ≥ 0"));
  }
  for (const double g : data_.data(c, "group")) m.groups.push_back(static_cast<int>(g));
  Component& state = state_of(c);
  m.points = points_of(state, c);
  if (m.kind == CollisionElements::spheres) {
    // SOFA's radii: listRadius where it has one, radius (1) for the points beyond it.
    Numbers listed;
    try {
      listed = data_.data(c, "listRadius");
    } catch (const Error& error) {
      // SOFA leaves a data whose link it cannot resolve at its default (SOFA's own
      // StickContactForceField.scn links listRadius to a loader that is not there).
      data_.warn(std::string(error.what()) + ": listRadius left empty, as SOFA leaves it: every sphere takes radius");
    }
    const double fallback = data_.real(c, "radius", 1.0);
    for (std::size_t i = 0; i < m.points->size(); ++i) {
      const double r = i < listed.size() ? listed[i] : fallback;
      if (!(r >= 0) || !std::isfinite(r)) throw error_at(c.where(), make_error("the radius of sphere ", i, " is ", r, ": it must be finite and ≥ 0"));
      m.radii.push_back(r);
    }
    return m;
  }
  Component* topology = topology_of(c);
  if (m.kind == CollisionElements::points) {
    if (method_ == IntersectionMethod::local_min_distance && topology) cone_topology(c, *topology, m);
    if (m.self_collision && topology) {
      // SOFA's VerticesAroundVertex: along the topology's edges (made from its cells without a list).
      m.self_topology = std::make_shared<const SelfCollisionTopology>(
          self_collision_topology(static_cast<Index>(m.points->size()), elements(*topology).edges));
    }
    return m;
  }
  if (!topology) throw error_at(c.where(), make_error("no topology in its node or above to take its elements from"));
  // SOFA takes a grid's faces, and a MeshTopology's or hexahedra's edges and faces, from their cells
  // in orders of their own: not made here. (A surface container's tetrahedra, those of a container
  // its src links to, are not its own.)
  const std::string_view topology_type = topology->object->type;  // as written (MeshTopology is an alias here)
  const bool surface_container = topology_type == "TriangleSetTopologyContainer" ||
                                 topology_type == "QuadSetTopologyContainer" || topology_type == "EdgeSetTopologyContainer";
  if (is_grid_topology(topology_type) || topology_type == "HexahedronSetTopologyContainer" ||
      (!surface_container && topology_type != "TetrahedronSetTopologyContainer" &&
       !data_.indices(*topology, "tetrahedra").empty())) {
    throw NotSimulated{c.where() + ": its topology " + topology->where() + " is a grid or a volume, whose surface elements SOFA "
                       "derives from its cells: not made here yet (give it a surface topology)"};
  }
  if (topology_type == "TetrahedronSetTopologyContainer") {
    // Tried with SOFA 2a278d891f: docs/collision.md §9, quirk 20.
    data_.warn(c.where() + " takes every triangle and edge of the tetrahedra of " + topology->where() +
               ", inner ones included, as SOFA does; SOFA's contact mappers do not follow such a model (its "
               "LineCollisionModel crashes SOFA, its TriangleCollisionModel throws the body away): fastcorot's "
               "contacts act on the elements' own points, so results differ from SOFA's. A surface topology "
               "(a Tetra2TriangleTopologicalMapping below the volume) gives the same contacts in both");
  }
  TopologyElements given = elements(*topology);
  std::vector<Triangle>& triangles = given.triangles;
  const auto& quads = given.quads;
  if (m.kind == CollisionElements::triangles && !quads.empty() && !m.points->is_still()) {
    throw NotSimulated{c.where() + ": quads on a moving surface (SOFA maps their contact points bilinearly over the quad) are not "
                       "simulated yet"};
  }
  if (m.kind == CollisionElements::triangles) {
    // SOFA's TriangleCollisionModel: the triangles, then each quad as (1, 2, 0) and (3, 0, 2).
    for (const auto& q : quads) {
      triangles.push_back({q[1], q[2], q[0]});
      triangles.push_back({q[3], q[0], q[2]});
    }
    m.triangles = std::move(triangles);
  } else {
    m.edges = std::move(given.edges);
  }
  const auto n = static_cast<Index>(m.points->size());
  const auto check = [&](const auto& elements, const char* what) {
    for (std::size_t e = 0; e < elements.size(); ++e) {
      for (Index v : elements[e]) {
        if (v < 0 || v >= n) {
          throw error_at(c.where(), make_error(what, " ", e, " of ", topology->where(), " names point ", v, ", outside the ", n,
                                               " points of its MechanicalObject"));
        }
      }
    }
  };
  check(m.triangles, "triangle");
  check(m.edges, "edge");
  if (m.self_collision && m.kind == CollisionElements::lines) {
    m.self_topology = std::make_shared<const SelfCollisionTopology>(self_collision_topology(n, m.edges));
  }
  if (m.kind == CollisionElements::triangles && method_ == IntersectionMethod::new_proximity) {
    // SOFA's ownership flags come from the topology's own triangles; those made from quads have none.
    const auto listed = index_tuples<2>(data_, *topology, "edges");
    const std::size_t own = m.triangles.size() - 2 * quads.size();
    try {
      m.triangle_flags = triangle_flags(std::span<const Triangle>(m.triangles.data(), own), m.points->size(), listed);
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
    m.triangle_flags.resize(m.triangles.size(), 0);
  }
  if (method_ == IntersectionMethod::local_min_distance) cone_topology(c, *topology, m);
  return m;
}

void CollisionModelReader::cone_topology(Component& c, Component& topology, CollisionModel<double>& m) {
  TopologyElements given = elements(topology);
  if (m.kind == CollisionElements::lines) given.edges = m.edges;
  m.cone_topology = std::make_shared<const LocalMinDistanceTopology>(
      local_min_distance_topology(static_cast<Index>(m.points->size()), given.triangles, given.edges));
  if (m.kind != CollisionElements::points) return;
  for (const GraphNode* node = c.node; node && !m.point_filter; node = node->parent) {
    for (const auto& other : node->components) m.point_filter = m.point_filter || other->type() == "LineCollisionModel";
  }
}

CollisionModelReader::TopologyElements CollisionModelReader::elements(Component& topology) {
  TopologyElements e;
  e.triangles = index_tuples<3>(data_, topology, "triangles");
  e.quads = index_tuples<4>(data_, topology, "quads");
  e.edges = index_tuples<2>(data_, topology, "edges");
  if (e.edges.empty()) {
    // SOFA's containers make their edge array from their largest cells: a TetrahedronSetTopologyContainer
    // from its tetrahedra, the others (and MeshTopology) from their triangles and quads.
    e.edges = topology.object->type == "TetrahedronSetTopologyContainer"
                  ? tetrahedron_set_edges(index_tuples<4>(data_, topology, "tetrahedra"))
                  : surface_edges(e.triangles, e.quads);
  }
  return e;
}

Component* CollisionModelReader::topology_of(Component& c) {
  if (c.has("topology")) return data_.topology_of(c);
  for (const GraphNode* node = c.node; node; node = node->parent) {
    Component* found = nullptr;
    for (const auto& other : node->components) {
      if (other->spec && (other->spec->category == "topology" || other->spec->category == "trianglecontainer")) found = other.get();
    }
    if (found) return found;
  }
  return nullptr;
}

Component& CollisionModelReader::state_of(Component& c) {
  for (const GraphNode* node = c.node; node; node = node->parent) {
    const auto states = node->of_category("state");
    if (!states.empty()) return *states.front();
  }
  throw error_at(c.where(), make_error("no MechanicalObject in its node or above"));
}

std::shared_ptr<CollisionPoints<double>> CollisionModelReader::points_of(Component& state, Component& user) {
  if (const auto it = points_.find(&state); it != points_.end()) {
    if (it->second->is_rigid() && user.type() != "SphereCollisionModel") {
      throw NotSimulated{user.where() + ": a " + std::string(user.type()) + " on a Rigid3 state (put its points under a RigidMapping)"};
    }
    return it->second;
  }
  std::shared_ptr<CollisionPoints<double>> points;
  if (const auto where = locate_(state)) {
    const auto& object = simulation_.objects[where->object];
    if (where->mapped) {
      if (where->mapped->through || where->mapped->coordinates != 3) {
        throw NotSimulated{user.where() + ": its state " + state.where() + " is below a SubsetMultiMapping, several rigid bodies or a DistanceMapping"};
      }
      points = std::make_shared<CollisionPoints<double>>(CollisionPoints<double>::mapped(
          where->object, std::shared_ptr<MechanicalMapping<double>>(mechanical_mapping(where->mapped->map, where->mapped->rigid))));
    } else {
      std::vector<Index> blocks;
      if (where->rigid) {
        // SOFA's RigidSphereModel: a SphereCollisionModel in a Rigid3 state's context.
        if (user.type() != "SphereCollisionModel") {
          throw NotSimulated{user.where() + ": a " + std::string(user.type()) + " on a Rigid3 state (put its points under a RigidMapping)"};
        }
        for (Index i = 0; i < where->size; i += 2) blocks.push_back(where->offset + i);
        points = std::make_shared<CollisionPoints<double>>(CollisionPoints<double>::rigid(where->object, std::move(blocks)));
      } else {
        for (Index i = 0; i < where->size; ++i) blocks.push_back(where->offset + i);
        points = std::make_shared<CollisionPoints<double>>(CollisionPoints<double>::own(where->object, std::move(blocks)));
      }
    }
    static_cast<void>(object);
  } else if (state.node->is_unloaded_point_set()) {
    // Points a Mesh2PointTopologicalMapping placed, which nothing moves (SOFA integrates them with no
    // mass and no force): a still obstacle.
    auto x = data_.points(state, "position");
    if (x.empty()) throw error_at(user.where(), make_error("its MechanicalObject ", state.where(), " has no points"));
    points = std::make_shared<CollisionPoints<double>>(CollisionPoints<double>::still(std::move(x)));
  } else {
    for (const GraphNode* node = state.node; node; node = node->parent) {
      if (!node->of_category("odesolver").empty()) {
        throw NotSimulated{user.where() + ": its state " + state.where() + " is under an ODE solver but not one fastcorot follows"};
      }
    }
    if (!state.node->of_category("visualmapping").empty()) {
      // Under a RigidMapping from a rigid no solver moves (STLIB's Floor and Cube, fixed): an
      // obstacle whose points the rigid's frame places once.
      std::vector<std::string> said;
      std::optional<ConstraintPoints<double>> placed;
      try {
        placed = UnsimulatedPoints(data_, said, locate_).points(state, user);
      } catch (const Error& error) {
        throw NotSimulated{user.where() + ": its still state " + state.where() + ": " + error.what()};
      }
      if (!placed || placed->motion) {
        throw NotSimulated{user.where() + ": its state " + state.where() + " is carried by a moving rigid: moving obstacles are not "
                           "simulated yet"};
      }
      points = std::make_shared<CollisionPoints<double>>(CollisionPoints<double>::still(std::move(placed->position)));
      points_.emplace(&state, points);
      return points;
    }
    for (const auto& c : state.node->components) {
      const std::string_view type = c->type();
      if (type.find("Movement") != std::string_view::npos || type.find("Oscillator") != std::string_view::npos) {
        throw NotSimulated{user.where() + ": its state " + state.where() + " is moved by " + c->where() +
                           " (SOFA projects it every step): moving obstacles are not simulated yet"};
      }
    }
    if (is_rigid_template(data_.text(state, "template", "Vec3d"))) throw NotSimulated{user.where() + ": a collision model on a Rigid3 state"};
    auto x = data_.points(state, "position");  // placed as the state places them
    if (x.empty()) throw error_at(user.where(), make_error("its MechanicalObject ", state.where(), " has no points"));
    points = std::make_shared<CollisionPoints<double>>(CollisionPoints<double>::still(std::move(x)));
  }
  points_.emplace(&state, points);
  return points;
}

}  // namespace fastcorot::scene_detail
