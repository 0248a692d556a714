#include "spring_builders.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/regular_grid_springs.h"
#include "fastcorot/fem/rest_shape_springs_force_field.h"
#include "fastcorot/fem/spring_force_field.h"
#include "fastcorot/mapping/mapped_force_field.h"
#include "fastcorot/sim/mapped_state.h"

#include <cmath>

namespace fastcorot::scene_detail {

namespace {

// Only 3D points: SOFA's Vec3 (Vec3d, Vec3f) template.
void check_template(SceneData& data, Component& c, bool rigid_allowed = false) {
  const std::string name = data.text(c, "template", "Vec3d");
  if (rigid_allowed && is_rigid_template(name)) return;
  if (!name.starts_with("Vec3")) throw make_error("template=\"", name, "\": only Vec3 (3D points) is supported");
}

// A list of SOFA's "one value or one per spring" data: as written, else `fallback`; resized to
// `count` entries by repeating its last one (SOFA's updateSpringsFromTopologyIndices).
Numbers per_spring(SceneData& data, Component& c, const std::string& name, const Numbers& fallback, std::size_t count) {
  Numbers values = c.has(name) ? data.data(c, name) : fallback;
  if (values.empty()) throw make_error(name, " is empty: one value, or one per spring, is needed");
  values.resize(count, values.back());
  return values;
}

Index whole_index(double value, const char* attribute, std::size_t spring) {
  if (!(value >= 0) || value != std::floor(value) || value > 2e9) {
    throw make_error(attribute, ": spring ", spring, " has index ", value, ": must be a whole number >= 0");
  }
  return static_cast<Index>(value);
}

// The springs c lists, indices within object1 (a) and object2 (b): its `spring` data (i j ks kd L
// per spring) when given, else indices1/indices2 with stiffness, damping, lengths, elongationOnly,
// enabled (SOFA's SpringForceField::init).
std::vector<Spring<double>> listed_springs(SceneData& data, Component& c) {
  for (const char* file : {"fileSprings", "filename"}) {
    if (c.has(file)) throw make_error(file, ": springs read from a file are not supported (list them in `spring`)");
  }
  std::vector<Spring<double>> springs;
  if (c.has("spring")) {
    const Numbers& v = data.data(c, "spring");
    if (v.size() % 5 != 0) {
      throw make_error("spring has ", v.size(), " numbers: 5 per spring (index1 index2 stiffness damping restLength)");
    }
    for (std::size_t s = 0; s < v.size() / 5; ++s) {
      Spring<double> spring;
      spring.a = whole_index(v[5 * s], "spring", s);
      spring.b = whole_index(v[5 * s + 1], "spring", s);
      spring.stiffness = v[5 * s + 2];
      spring.damping = v[5 * s + 3];
      spring.rest_length = v[5 * s + 4];
      springs.push_back(spring);
    }
    return springs;
  }
  const auto list = [&](const char* name, const char* alias) {
    return c.has(name) || !c.has(alias) ? data.indices(c, name) : data.indices(c, alias);
  };
  const std::vector<Index> first = list("indices1", "springsIndices1"), second = list("indices2", "springsIndices2");
  if (first.size() != second.size()) {
    throw make_error("indices1 has ", first.size(), " points, indices2 ", second.size(), " (one pair per spring)");
  }
  const std::size_t n = first.size();
  if (n == 0) return springs;
  const Numbers ks = per_spring(data, c, "stiffness", {100}, n), kd = per_spring(data, c, "damping", {5}, n);
  const Numbers lengths = per_spring(data, c, c.has("lengths") || !c.has("length") ? "lengths" : "length", {0}, n);
  const Numbers elongation = per_spring(data, c, "elongationOnly", {0}, n), enabled = per_spring(data, c, "enabled", {1}, n);
  for (std::size_t s = 0; s < n; ++s) {
    if (first[s] < 0 || second[s] < 0) throw make_error("indices1/indices2: spring ", s, " has a negative index");
    springs.push_back({first[s], second[s], ks[s], kd[s], lengths[s], elongation[s] != 0, enabled[s] != 0});
  }
  return springs;
}

// The state a pair link designates; without it, the MechanicalObject of c's own node (SOFA's "@./").
Component& linked_state(SceneData& data, Component& c, const char* name) {
  if (c.has(name)) return data.resolve_state(*c.node, c.object->attributes.at(name), c);
  for (const auto& other : c.node->components) {
    if (other->spec && other->spec->category == "state") return *other;
  }
  throw make_error(name, " is not given and node ", c.node->path,
                   " has no MechanicalObject (SOFA's default is the state of the spring's own node)");
}

void check_ranges(const std::vector<Spring<double>>& springs, Index size1, Index size2, const char* list) {
  for (std::size_t s = 0; s < springs.size(); ++s) {
    if (springs[s].a >= size1) throw make_error(list, ": spring ", s, " index ", springs[s].a, " out of range [0, ", size1, ") of object1");
    if (springs[s].b >= size2) throw make_error(list, ": spring ", s, " index ", springs[s].b, " out of range [0, ", size2, ") of object2");
  }
}

}  // namespace

bool is_interaction_spring(std::string_view type) { return type == "SpringForceField"; }

void refuse_spring_without_solver(const Component& c, const std::string& node_path) {
  throw make_error(c.where(), ": no ODE solver at or above node ", node_path,
                   ": the objects it joins must be integrated by one solver at or above this node "
                   "(springs between objects of different solvers are not supported)");
}

namespace {

// One end of an interaction spring: an object the solver integrates (its index in `states`), or a
// mapped state that follows them (a MechanicalObject under a mapping, with no mechanics of its own).
struct SpringSide {
  std::size_t state = 0;
  const MappedState* mapped = nullptr;
};

}  // namespace

void add_interaction_springs(SceneData& data, const std::vector<GraphNode*>& nodes, const std::vector<Component*>& states,
                             const std::vector<Index>& offsets, const std::vector<Index>& sizes,
                             SimulatedObject<double>& object) {
  const Index total = object.system.size();
  for (GraphNode* node : nodes) {
    for (const auto& c : node->components) {
      if (!c->spec || !is_interaction_spring(c->type())) continue;
      try {
        check_template(data, *c, true);
        const auto which = [&](const char* name) {
          Component& state = linked_state(data, *c, name);
          for (std::size_t k = 0; k < states.size(); ++k) {
            if (states[k] == &state) return SpringSide{k, nullptr};
          }
          for (const MappedState& mapped : object.mapped_states) {
            if (mapped.node != state.node->path || mapped.name != state.sofa_name()) continue;
            if (mapped.coordinates == 1) {
              throw make_error(name, " ", state.where(), " is a Vec1 state (a DistanceMapping's output): springs join Vec3 points");
            }
            if (mapped.through) {
              throw make_error(name, " ", state.where(), " is below a SubsetMultiMapping or follows several rigid bodies: ",
                               "springs on it are not supported (put them in the mapped node, on its own points)");
            }
            return SpringSide{0, &mapped};
          }
          throw make_error(name, " ", state.where(), " is not integrated by this spring's ODE solver "
                           "(springs between objects of different solvers are not supported)");
        };
        const SpringSide first = which("object1"), second = which("object2");
        // On a rigid state a spring joins rigid centres (SOFA's SpringForceField<Rigid3> reads and
        // pushes the centres): rigid k's centre is block 2k of its object.
        const auto rigid = [&](const SpringSide& side) {
          return !side.mapped && is_rigid_template(data.text(*states[side.state], "template", "Vec3d"));
        };
        // The block of point (or rigid centre) i of an integrated end.
        const auto block_of = [&](const SpringSide& side, Index i) { return offsets[side.state] + (rigid(side) ? 2 * i : i); };
        const auto points = [&](const SpringSide& side) {
          if (side.mapped) return static_cast<Index>(side.mapped->size());
          return rigid(side) ? sizes[side.state] / 2 : sizes[side.state];
        };
        std::vector<Spring<double>> springs = listed_springs(data, *c);
        check_ranges(springs, points(first), points(second), c->has("spring") ? "spring" : "indices1/indices2");
        const double rayleigh = data.real(*c, "rayleighStiffness", 0);
        if (!first.mapped && !second.mapped) {
          for (Spring<double>& s : springs) {
            s.a = block_of(first, s.a);
            s.b = block_of(second, s.b);
          }
          auto mesh = object.mesh && object.mesh->num_points() == total
                          ? std::shared_ptr<const TetMesh>(object.mesh)
                          : std::make_shared<const TetMesh>(total, std::vector<Tetrahedron>{});
          object.system.force_fields.push_back(
              std::make_shared<SpringForceField<double>>(std::move(mesh), std::move(springs), rayleigh, "SpringForceField"));
          object.force_field_drawing.push_back({});
          continue;
        }
        // A mapped end: the spring acts on both ends' points side by side, brought up through each
        // end's own mapping (a StackedMapping under a MappedForceField).
        std::vector<std::unique_ptr<MechanicalMapping<double>>> parts;
        for (const SpringSide& side : {first, second}) {
          if (side.mapped) {
            parts.push_back(mechanical_mapping(side.mapped->map, side.mapped->rigid));
          } else {
            std::vector<Index> picked;
            for (Index i = 0; i < points(side); ++i) picked.push_back(block_of(side, i));
            parts.push_back(std::make_unique<LinearMapping<double>>(PointMapping<double>::subset(picked)));
          }
        }
        const Index ends = points(first) + points(second);
        for (Spring<double>& s : springs) s.b += points(first);
        auto field = std::make_shared<SpringForceField<double>>(std::make_shared<const TetMesh>(ends, std::vector<Tetrahedron>{}),
                                                                std::move(springs), rayleigh, "SpringForceField");
        object.system.force_fields.push_back(
            std::make_shared<MappedForceField<double>>(field, std::make_unique<StackedMapping<double>>(std::move(parts)), total));
        object.force_field_drawing.push_back({});
      } catch (const Error& error) {
        throw error_at(c->where(), error);
      }
    }
  }
}

std::shared_ptr<ForceField<double>> build_regular_grid_springs(SceneData& data, Component& c, Index size) {
  try {
    check_template(data, c);
    for (const char* link : {"object1", "object2"}) {
      if (c.has(link) && &linked_state(data, c, link) != &linked_state(data, c, "")) {
        throw make_error(link, ": springs between two objects are not supported for RegularGridSpringForceField");
      }
    }
    std::vector<Spring<double>> springs = listed_springs(data, c);
    check_ranges(springs, size, size, c.has("spring") ? "spring" : "indices1/indices2");
    const std::size_t listed = springs.size();
    Component* topology = data.topology_of(c);
    if (topology && topology->type() == "RegularGridTopology") {
      // SOFA's aliases: `stiffness` and `damping` set the three kinds at once; the per-kind names win here.
      const auto value = [&](const std::string& kind, const char* what, double fallback) {
        const std::string name = kind + what;
        const char* alias = std::string_view(what) == "Stiffness" ? "stiffness" : "damping";
        if (c.has(name)) return data.real(c, name, fallback);
        if (c.has(alias)) {
          const Numbers& v = data.data(c, alias);
          if (v.size() != 1) throw make_error(alias, " has ", v.size(), " values: one is needed (it sets ", kind, what, ")");
          return v.front();
        }
        return fallback;
      };
      RegularGridSpringParameters<double> p;
      p.lines_stiffness = value("lines", "Stiffness", 100);
      p.lines_damping = value("lines", "Damping", 5);
      p.quads_stiffness = value("quads", "Stiffness", 100);
      p.quads_damping = value("quads", "Damping", 5);
      p.cubes_stiffness = value("cubes", "Stiffness", 100);
      p.cubes_damping = value("cubes", "Damping", 5);
      const RegularGrid grid = data.grid(*topology);
      if (grid.num_points() != size) {
        throw make_error("its grid ", topology->where(), " has ", grid.num_points(), " points, the state ", size);
      }
      for (Spring<double>& s : regular_grid_springs<double>(grid, p)) springs.push_back(s);
    }
    auto field = std::make_shared<SpringForceField<double>>(std::make_shared<const TetMesh>(size, std::vector<Tetrahedron>{}),
                                                            std::move(springs), data.real(c, "rayleighStiffness", 0),
                                                            "RegularGridSpringForceField");
    field->set_assembled_springs(listed);
    return field;
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

std::shared_ptr<ForceField<double>> build_rest_shape_springs(SceneData& data, Component& c, Component& state,
                                                             std::span<const Vec3<double>> rest,
                                                             std::shared_ptr<const TetMesh> mesh) {
  try {
    check_template(data, c);
    const auto size = static_cast<Index>(rest.size());
    RestShapeSpringsForceField<double>::Parameters p;
    p.points = data.indices(c, "points");
    if (p.points.empty()) {
      for (Index i = 0; i < size; ++i) p.points.push_back(i);
    }
    for (Index i : p.points) {
      if (i < 0 || i >= size) throw make_error("points: index ", i, " out of range [0, ", size, ") of ", state.where());
    }
    if (c.has("stiffness")) p.stiffness = data.data(c, "stiffness");
    if (p.stiffness.empty()) p.stiffness = {100};  // SOFA's default when none is given
    for (double k : p.stiffness) {
      if (!(k >= 0) || !std::isfinite(k)) throw make_error("stiffness = ", k, ": must be finite and >= 0");
    }
    if (c.has("activeDirections")) {
      const Numbers& active = data.data(c, "activeDirections");
      if (active.size() != 3) throw make_error("activeDirections has ", active.size(), " values: 3 (x y z) for Vec3");
      for (std::size_t axis = 0; axis < 3; ++axis) p.active_directions[axis] = active[axis] != 0;
    }
    p.rayleigh_stiffness = data.real(c, "rayleighStiffness", 0);
    if (c.has("external_rest_shape")) {
      Component& external = data.resolve_state(*c.node, c.object->attributes.at("external_rest_shape"), c);
      for (const GraphNode* scope = external.node; scope; scope = scope->parent) {
        for (const auto& other : scope->components) {
          if (other->spec && other->spec->category == "odesolver") {
            throw make_error("external_rest_shape ", external.where(), " is simulated (an ODE solver at or above it): "
                             "only a state that does not move (in a node without solver) is supported");
          }
        }
      }
      const std::vector<Vec3<double>> positions = data.points(external, "position");
      std::vector<Index> external_points = data.indices(c, "external_points");
      if (external_points.empty()) {
        for (Index i = 0; i < static_cast<Index>(positions.size()); ++i) external_points.push_back(i);
      }
      if (external_points.size() != p.points.size()) {
        throw make_error("external_points: ", external_points.size(), " points of ", external.where(), " for ", p.points.size(),
                         " points (one each)");
      }
      for (Index i : external_points) {
        if (i < 0 || i >= static_cast<Index>(positions.size())) {
          throw make_error("external_points: index ", i, " out of range [0, ", positions.size(), ") of ", external.where());
        }
        p.anchors.push_back(positions[static_cast<std::size_t>(i)]);
      }
    } else {
      // Without an external state, external_points must match points in number (SOFA deactivates the
      // field otherwise) and is not used: each point is pulled to its own rest position.
      const std::vector<Index> external_points = data.indices(c, "external_points");
      if (!external_points.empty() && external_points.size() != p.points.size()) {
        throw make_error("external_points has ", external_points.size(), " points for ", p.points.size(), " points");
      }
      for (Index i : p.points) p.anchors.push_back(rest[static_cast<std::size_t>(i)]);
      p.anchors_follow_rest = true;
    }
    return std::make_shared<RestShapeSpringsForceField<double>>(std::move(mesh), std::move(p));
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

bool is_point_spring(std::string_view type) {
  return type == "RegularGridSpringForceField" || type == "RestShapeSpringsForceField";
}

std::shared_ptr<ForceField<double>> build_point_springs(SceneData& data, Component& c, Component& state,
                                                        std::span<const Vec3<double>> rest, std::shared_ptr<const TetMesh> mesh) {
  const auto size = static_cast<Index>(rest.size());
  if (c.type() == "RegularGridSpringForceField") return build_regular_grid_springs(data, c, size);
  if (!mesh || mesh->num_points() != size) mesh = std::make_shared<const TetMesh>(size, std::vector<Tetrahedron>{});
  return build_rest_shape_springs(data, c, state, rest, std::move(mesh));
}

}  // namespace fastcorot::scene_detail
