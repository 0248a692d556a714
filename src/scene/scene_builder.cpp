#include "fastcorot/scene/scene_builder.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"
#include "fastcorot/sim/merged_objects.h"
#include "fastcorot/topology/hexahedron_faces.h"
#include "fastcorot/topology/regular_grid.h"
#include "force_field_builders.h"
#include "element_fem_builders.h"
#include "hexahedron_builders.h"
#include "hexahedron_mass_builder.h"
#include "lagrangian_builder.h"
#include "mass_builders.h"
#include "projective_constraints.h"
#include "scene_data.h"
#include "solver_builder.h"
#include "spring_builders.h"
#include "topology_change_processor.h"
#include "mapped_mechanics.h"
#include "subset_multi_mapping_builder.h"
#include "distance_mapping_builder.h"
#include "collision_builder.h"
#include "rigid_builder.h"
#include "visual_surface_builder.h"

#include <cmath>
#include <map>
#include <set>
#include <optional>
#include <sstream>

namespace fastcorot {

using scene_detail::build_solvers;
using scene_detail::Component;
using scene_detail::GraphNode;
using scene_detail::is_rigid_template;
using scene_detail::Numbers;
using scene_detail::SceneData;
using scene_detail::transformed;

namespace {

bool is_integrator(const Component& c) {
  return c.spec && c.spec->category == "odesolver" && c.type() != "NewtonRaphsonSolver";
}

// A node whose state is mapped from its parent's (visual or collision models): it does not take
// part in the mechanics here.
bool is_mapped_node(const GraphNode& node) {
  for (const auto& c : node.components) {
    const std::string& type = c->object->type;
    if (type.ends_with("Mapping") && !type.ends_with("TopologicalMapping")) {
      return true;
    }
  }
  return false;
}

// A node whose state is a SubsetMultiMapping's child: its inputs may be several states.
bool is_multi_mapped_node(const GraphNode& node) {
  for (const auto& c : node.components) {
    if (scene_detail::is_subset_multi_mapping(c->object->type)) return true;
  }
  return false;
}

// A node with a state and no mapping: the state is integrated by the solver above it, even below
// a mapped node (SOFA's MeshSplittingEngine.scn, STLIB's rigidified objects).
bool is_independent_node(const GraphNode& node) { return !node.of_category("state").empty() && !is_mapped_node(node); }

Vec3<double> node_vec3(const SceneNode& node, const std::string& name, const Vec3<double>& fallback) {
  const auto it = node.attributes.find(name);
  if (it == node.attributes.end()) return fallback;
  std::istringstream in(it->second);
  Vec3<double> v;
  if (!(in >> v.x() >> v.y() >> v.z()) || !v.allFinite()) {
    throw make_error(node.location.to_string(), ": Node '", node.name, "': ", name, " = \"", it->second,
                     "\": expected 3 finite numbers");
  }
  return v;
}

class Builder {
 public:
  Builder(const SceneNode& root, const SceneOptions& options)
      : repositories_(add_repositories(root)), data_(root, info_, options.strict ? nullptr : &warnings_), allow_empty_(options.allow_empty) {
    for (const auto& line : repositories_) (options.strict ? info_ : warnings_).push_back(line);
  }

  LoadedScene build() {
    const SceneNode& root = *data_.root().scene;
    simulation_.gravity = node_vec3(root, "gravity", {0, -9.81, 0});
    if (const auto dt = root.attributes.find("dt"); dt != root.attributes.end()) {
      char* end = nullptr;
      simulation_.dt = std::strtod(dt->second.c_str(), &end);
      if (end == dt->second.c_str() || *end != '\0' || !(simulation_.dt > 0) || !std::isfinite(simulation_.dt)) {
        throw make_error(root.location.to_string(), ": Node '", root.name, "': dt = \"", dt->second,
                         "\": must be a finite number > 0");
      }
    }
    visit(data_.root(), false);
    build_constraints();
    // SOFA's init ends with the projective constraints' projectPosition and projectVelocity at time
    // 0 (Simulation.cpp, initNode): a LinearMovement records x0 there and starts its movement.
    for (auto& object : simulation_.objects) object.system.apply_placements(0.0);
    if (simulation_.objects.empty() && !allow_empty_) {
      throw make_error(root.location.file.string(), ": the scene has no node with an ODE solver "
                       "(EulerImplicitSolver, StaticSolver, ...) and a MechanicalObject: nothing to simulate");
    }
    std::map<const SceneObject*, std::size_t> rank;
    rank_objects(root, rank);
    std::vector<std::size_t> state_objects;
    for (const SceneObject* state : states_) state_objects.push_back(rank.at(state));
    std::vector<LoadedScene::StatePart> parts;
    for (const auto& [state, part] : parts_) parts.push_back({rank.at(state), part.object, part.offset, part.size});
    LoadedScene loaded{std::move(simulation_), std::move(info_),         std::move(warnings_),
                       std::move(state_objects), std::move(state_counts_), std::move(parts)};
    for (const SceneObject* c : lagrangian_.constraints) loaded.constraint_objects.push_back(rank.at(c));
    if (lagrangian_.solver) loaded.constraint_solver_object = static_cast<long>(rank.at(lagrangian_.solver));
    return loaded;
  }

 private:
  void visit(GraphNode& node, bool under_solver) {
    std::vector<Component*> integrators;
    for (const auto& c : node.components) {
      if (is_integrator(*c)) integrators.push_back(c.get());
    }
    if (integrators.size() > 1) {
      throw make_error(integrators[1]->where(), ": a second ODE solver in node ", node.path, " (one per node)");
    }
    if (!integrators.empty() && !under_solver) {
      build_object(node, *integrators.front());
      return;
    }
    if (!under_solver) {
      for (const auto& c : node.components) {
        if (scene_detail::is_interaction_spring(c->type())) scene_detail::refuse_spring_without_solver(*c, node.path);
        if (c->type() == "AttachProjectiveConstraint") {
          throw make_error(c->where(), ": no ODE solver at or above node ", node.path,
                           ": the objects it ties must be integrated by one solver above them (not supported otherwise)");
        }
      }
    }
    if (!under_solver && !node.of_category("state").empty()) {
      info_.push_back(node.scene->location.to_string() + ": node " + node.path +
                      " has no ODE solver above it: it is not simulated (as in SOFA)");
    }
    for (auto& child : node.children) visit(*child, under_solver);
  }

  // FreeMotionAnimationLoop and the Lagrangian components, on the objects built.
  void build_constraints() {
    const scene_detail::LocateState locate = [this](const Component& state) { return locate_state(state); };
    lagrangian_ = scene_detail::build_free_motion_loop(data_, info_, simulation_, solver_nodes_, locate);
    scene_detail::build_collision_pipeline(data_, info_, simulation_, locate, solver_nodes_);
  }

  // Where a MechanicalObject's points are in the simulation: a simulated object's range, or one of
  // its mapped states; nullopt for a state nothing simulates.
  std::optional<scene_detail::StateLocation> locate_state(const Component& state) const {
    for (const auto& [object, part] : parts_) {
      if (object != state.object) continue;
      const auto& ranges = simulation_.objects[part.object].states;
      bool rigid = false;
      for (const StateRange& range : ranges) rigid = rigid || (range.offset == part.offset && range.rigid);
      return scene_detail::StateLocation{part.object, part.offset, part.size, rigid, nullptr};
    }
    for (std::size_t o = 0; o < simulation_.objects.size(); ++o) {
      for (const MappedState& mapped : simulation_.objects[o].mapped_states) {
        if (mapped.node == state.node->path && mapped.name == state.sofa_name()) {
          return scene_detail::StateLocation{o, 0, static_cast<Index>(mapped.size()), false, &mapped};
        }
      }
    }
    return std::nullopt;
  }

  static void rank_objects(const SceneNode& node, std::map<const SceneObject*, std::size_t>& rank) {
    for (const auto& object : node.objects) rank.emplace(&object, rank.size());
    for (const auto& child : node.children) rank_objects(child, rank);
  }

  // Nodes taking part in the mechanics under a solver node: the node and its descendants, minus
  // mapped subtrees, which go to `mapped` (visual and collision models, mapped states, and mapped
  // nodes with mechanics of their own: add_mapped_mechanics).
  // `solver_scope`: collecting for the solver's node (independent states below mapped nodes and
  // multi-mapped nodes are gathered), else for a mapped node (they are left to the solver's pass).
  void collect(GraphNode& node, std::vector<GraphNode*>& nodes, std::vector<GraphNode*>& mapped, bool solver_scope = true) {
    if (node.is_unloaded_point_set()) {
      // SOFA integrates this state with no mass and no force: its points stay where the mapping put them.
      info_.push_back(node.scene->location.to_string() + ": node " + node.path + ": the points of its " +
                      "Mesh2PointTopologicalMapping have no mass and no force: they stay put, as in SOFA (not simulated)");
      return;
    }
    if (is_multi_mapped_node(node)) {
      if (solver_scope) collect_below_mapped(node, nodes, mapped);
      return;
    }
    if (!solver_scope && is_independent_node(node)) return;
    if (is_mapped_node(node)) {
      if (!node.of_category("constraint").empty()) {
        throw make_error(node.of_category("constraint").front()->where(),
                         ": projective constraints in a mapped node are not supported (node ", node.path,
                         "): put them on the simulated object");
      }
      if (node.of_category("visual").empty() && node.of_category("state").empty()) {
        info_.push_back(node.scene->location.to_string() + ": mapped node " + node.path +
                        " ignored (visual or collision only)");
      } else {
        mapped.push_back(&node);
      }
      if (solver_scope) {
        for (auto& child : node.children) collect_below_mapped(*child, nodes, mapped);
      }
      return;
    }
    nodes.push_back(&node);
    for (auto& child : node.children) collect(*child, nodes, mapped, solver_scope);
  }

  // Below a mapped node, what the solver integrates beside it: states with no mapping of their own
  // (SOFA's solver integrates every independent state below it, wherever it sits) and the nodes of
  // SubsetMultiMappings (their inputs may be anywhere in the solver's subtree).
  void collect_below_mapped(GraphNode& node, std::vector<GraphNode*>& nodes, std::vector<GraphNode*>& mapped) {
    if (is_multi_mapped_node(node)) {
      multi_mapped_.push_back(&node);
      for (auto& child : node.children) collect_below_mapped(*child, nodes, mapped);
      return;
    }
    if (is_independent_node(node)) {
      collect(node, nodes, mapped);
      return;
    }
    for (auto& child : node.children) collect_below_mapped(*child, nodes, mapped);
  }

  // Force fields or a mass in the node or below it (a chain of mappings carries them up).
  static bool has_mechanics(const GraphNode& node) {
    if (!node.of_category("forcefield").empty() || !node.of_category("mass").empty()) return true;
    for (const auto& child : node.children) {
      if (is_independent_node(*child) || is_multi_mapped_node(*child)) continue;
      if (has_mechanics(*child)) return true;
    }
    return false;
  }

  // A mapped node with force fields or a mass (SOFA's mechanical mapping): its MechanicalObject is
  // built as an object of its own with the nodes below it, then folded into `object`: its forces
  // come up through Jᵀ, its stiffness as Jᵀ K J, its mass as Jᵀ M J (scene_detail::fold_mapped_object).
  void add_mapped_mechanics(GraphNode& node, SimulatedObject<double>& object) {
    const auto states = node.of_category("state");
    const std::string where = node.scene->location.to_string() + ": mapped node " + node.path;
    if (states.size() != 1) {
      throw make_error(where, " has ", states.size(), " MechanicalObjects: the mechanics in it or below need exactly one to act on");
    }
    const std::size_t known = object.mapped_states.size();
    scene_detail::add_mapped_states(data_, info_, node, object);
    if (object.mapped_states.size() == known) {
      throw make_error(where, ": its mapping is not one fastcorot carries forces through ",
                       "(IdentityMapping, SubsetMapping, BarycentricMapping, RigidMapping)");
    }
    const MappedState mapped_state = object.mapped_states.back();
    scene_detail::check_mapped_points_inside(mapped_state, where);
    SimulatedObject<double> mapped_object =
        build_mapped_part(node, *states.front(), *mechanical_mapping(mapped_state.map, mapped_state.rigid), object);
    if (mapped_state.rigid) {
      scene_detail::fold_rigid_mapped_object(mapped_object, *mapped_state.rigid, object, where);
    } else {
      scene_detail::fold_mapped_object(mapped_object, mapped_state.map, object, where);
    }
  }

  // The object of mapped node `node` (its state `state` and the nodes below it), placed where
  // `mapping` puts it from `parent`'s positions and velocities (as SOFA's mapping sets them at
  // init), with the springs of its nodes (object1 and object2 its own points); not yet folded.
  SimulatedObject<double> build_mapped_part(GraphNode& node, Component& state, const MechanicalMapping<double>& mapping,
                                            const SimulatedObject<double>& parent) {
    const auto& from = parent.system.state;
    MechanicalState<double> placed;
    placed.position.resize(mapping.size());
    placed.velocity.resize(mapping.size());
    mapping.positions(from.position, placed.position);
    mapping.velocities(from.position, from.velocity, placed.velocity);
    // SOFA's applyRestPosition: the mapping also maps the parent's rest positions.
    for (Component* m : node.of_category("visualmapping")) {
      if (!data_.boolean(*m, "applyRestPosition", false)) continue;
      placed.rest_position.resize(mapping.size());
      mapping.positions(from.rest_position, placed.rest_position);
    }
    std::vector<GraphNode*> nodes{&node}, mapped;
    for (auto& child : node.children) collect(*child, nodes, mapped, false);
    SimulatedObject<double> object = build_part(state, nodes, mapped, &placed);
    scene_detail::add_interaction_springs(data_, nodes, {&state}, {0}, {object.system.size()}, object);
    return object;
  }

  // A SubsetMultiMapping's node, once the solver's objects are merged: its state is built on the
  // points the mapping gives it and folded into `object` (through a linear mapping, the rigid
  // bodies' points, or the SubsetMultiMapping itself when its inputs mix both).
  void add_multi_mapped_mechanics(GraphNode& node, const std::vector<Component*>& states, const std::vector<Index>& offsets,
                                  const std::vector<Index>& sizes, SimulatedObject<double>& object) {
    const std::string where = node.scene->location.to_string() + ": mapped node " + node.path;
    const auto node_states = node.of_category("state");
    if (node_states.size() != 1) {
      throw make_error(where, " has ", node_states.size(), " MechanicalObjects: its SubsetMultiMapping needs exactly one to map to");
    }
    Component* multi = nullptr;
    for (const auto& c : node.components) {
      if (scene_detail::is_subset_multi_mapping(c->type())) multi = c.get();
    }
    const auto inputs = scene_detail::read_subset_multi_mapping(data_, node, *multi, states, offsets, sizes, object);
    const auto mapping = inputs.mapping();
    Component& state = *node_states.front();
    SimulatedObject<double> child = build_mapped_part(node, state, *mapping, object);
    MappedState shown{node.path, state.sofa_name(), "SubsetMultiMapping", {}, {}, {}};
    if (auto linear = inputs.linear()) {
      shown.map = *linear;
      object.mapped_states.push_back(std::move(shown));
      scene_detail::fold_mapped_object(child, *linear, object, where);
    } else if (auto carried = inputs.carried()) {
      shown.rigid = *carried;
      object.mapped_states.push_back(std::move(shown));
      scene_detail::fold_rigid_mapped_object(child, *carried, object, where);
    } else {
      shown.map = PointMapping<double>::identity(mapping->size());
      shown.through = inputs.mapping();
      object.mapped_states.push_back(std::move(shown));
      scene_detail::fold_multi_mapped_mass(child, inputs, object, where);
      child.system.mass = Mass<double>();
      scene_detail::fold_multi_mapped_object(child, [&] { return inputs.mapping(); }, object, where);
    }
    try {
      object.system.finalize();
    } catch (const Error& error) {
      throw error_at(where, error);
    }
  }

  // The nearest state at or above `node` among `states` (nullptr when none is).
  static Component* owner(const GraphNode& node, const std::vector<Component*>& states) {
    for (const GraphNode* scope = &node; scope; scope = scope->parent) {
      for (Component* state : states) {
        if (state->node == scope) return state;
      }
    }
    return nullptr;
  }

  // A part of a solver's objects that nothing acts on (a static obstacle's surface in the solver's
  // node: SOFA's FrictionContact scenes): no mass, no force, no constraint of its own, and no spring
  // or attachment among the solver's nodes names it. SOFA's solve leaves it where it is (its rows
  // are zero); here its points are held, which merge_objects accepts beside massive parts.
  void hold_if_still(Component& state, SimulatedObject<double>& part) {
    const auto& s = part.system;
    if (s.mass.size() != 0 || !s.force_fields.empty() || !s.constant_forces.empty() || s.rigids || !s.fixed.empty() ||
        !s.projections.empty() || !s.couplings.empty() || !s.placements.empty() || !s.motions.empty() || !s.linear_movements.empty()) {
      return;
    }
    if (acted_on(data_.root(), state)) return;
    auto& held = part.system.fixed;
    held.resize(static_cast<std::size_t>(part.system.size()));
    for (Index i = 0; i < part.system.size(); ++i) held[static_cast<std::size_t>(i)] = i;
    info_.push_back(state.where() + ": no mass, force or constraint acts on it: it stays where it is (as in SOFA's solve)");
  }

  // Whether a spring, an attachment or a Lagrangian constraint anywhere below `node` names `state`
  // (object1 / object2, each by default the state of the component's own node, as SOFA reads them).
  bool acted_on(GraphNode& node, const Component& state) {
    for (const auto& c : node.components) {
      if (!c->spec) continue;
      if (!scene_detail::is_interaction_spring(c->type()) && c->type() != "AttachProjectiveConstraint" && c->spec->category != "lagrangian") {
        continue;
      }
      for (const char* link : {"object1", "object2"}) {
        const Component* named = nullptr;
        if (c->has(link)) {
          named = &data_.resolve_state(*c->node, c->object->attributes.at(link), *c);
        } else if (const auto own = c->node->of_category("state"); !own.empty()) {
          named = own.front();
        }
        if (named == &state) return true;
      }
    }
    for (const auto& child : node.children) {
      if (acted_on(*child, state)) return true;
    }
    return false;
  }

  // One object: `state` with the components of `nodes` and the visual models of `visuals`.
  // `placed` (a mapped state's object): the positions and velocities its mapping gives it, as SOFA's
  // mapping sets them at init; its rest positions are its own (SOFA's, zero where it had none).
  SimulatedObject<double> build_part(Component& state, const std::vector<GraphNode*>& nodes,
                                     const std::vector<GraphNode*>& visuals, const MechanicalState<double>* placed = nullptr) {
    SimulatedObject<double> object;
    object.path = state.node->path;
    auto& system = object.system;
    // SOFA's gravity is the root's: a node's context is copied from its parent's
    // (Node::updateContext), so a gravity written on any other node is overwritten (SOFA's
    // regression reference of Benchmark/Analysis/Pendulum.scn falls along the root's gravity).
    system.gravity = simulation_.gravity;
    for (const GraphNode* scope = state.node; scope && scope->parent; scope = scope->parent) {
      if (scope->scene->attributes.count("gravity") && node_vec3(*scope->scene, "gravity", simulation_.gravity) != simulation_.gravity &&
          warned_gravity_.insert(scope).second) {
        data_.warn("node " + scope->path + ": gravity " + scope->scene->attributes.at("gravity") +
                   " is not used: SOFA gives every node the root's gravity (it copies the parent's context into each child node)");
      }
    }
    if (scene_detail::is_vec1_template(data_.text(state, "template", "Vec3d"))) {
      throw make_error(state.where(), ": a Vec1 state with its own mechanics (an ODE solver, force fields or a mass on it) is ",
                       "not supported: Vec1 states are the outputs of a DistanceMapping here, with Lagrangian constraints on them");
    }
    if (is_rigid_template(data_.text(state, "template", "Vec3d"))) {
      if (placed) throw make_error(state.where(), ": a Rigid3 state in a mapped node is not supported");
      object = scene_detail::build_rigid_object(data_, info_, state, nodes, system.gravity);
      finish_part(state, visuals, object);
      return object;
    }
    system.state.position = data_.points(state, "position");
    system.state.rest_position = data_.points(state, "rest_position");
    if (placed) {
      // SOFA's MechanicalObject stores its rest positions at its own init, before the mapping
      // resizes it (new points at zero) and applies: a mapped state keeps the rest positions it
      // had of its own (written, or its topology's), zero for the points it did not have.
      if (!placed->rest_position.empty()) {
        system.state.rest_position = placed->rest_position;  // the mapping's applyRestPosition
      } else if (system.state.rest_position.size() != placed->position.size()) {
        if (system.state.rest_position.size() < placed->position.size()) {
          info_.push_back(state.where() + ": " + std::to_string(placed->position.size() - system.state.rest_position.size()) +
                          " of its points have no rest position of their own: zero, as SOFA leaves them (its mapping sets "
                          "positions only); force fields there rest on them");
        }
        system.state.rest_position.resize(placed->position.size(), Vec3<double>::Zero());
      }
      system.state.position = placed->position;
    }
    const Index n = system.size();
    if (n == 0) throw make_error(state.where(), ": the state has no points");
    if (system.state.rest_position.size() != system.state.position.size()) {
      throw make_error(state.where(), ": rest_position has ", system.state.rest_position.size(),
                       " points, position has ", n);
    }
    auto velocity = data_.points(state, "velocity");
    if (velocity.size() == 1) velocity.assign(static_cast<std::size_t>(n), velocity.front());
    if (!velocity.empty() && velocity.size() != static_cast<std::size_t>(n)) {
      throw make_error(state.where(), ": velocity has ", velocity.size(), " entries, position has ", n);
    }
    system.state.velocity = velocity.empty() ? Points<double>(static_cast<std::size_t>(n), Vec3<double>::Zero()) : velocity;
    if (placed) system.state.velocity = placed->velocity;
    object.states.push_back({state.node->path, state.sofa_name(), 0, n});

    for (GraphNode* node : nodes) {
      for (const auto& c : node->components) {
        if (!c->spec && c->object->type == "ReadState") {
          throw make_error(c->where(), ": ReadState would drive the simulated object ", object.path,
                           " from a recorded file: not supported (it is accepted in nodes without a solver, for replay display)");
        }
        if (!c->spec) continue;
        const std::string_view type = c->type();
        if (type == "FastTetrahedralCorotationalForceField") add_force_field(*c, object);
        if (type == "TetrahedronFEMForceField" || type == "TetrahedralCorotationalFEMForceField") add_tetrahedron_fem(*c, object);
        if (type == "HexahedronFEMForceField" || type == "HexahedronFEMForceFieldAndMass") {
          auto field = scene_detail::build_hexahedron_fem(data_, *c, system.state.rest_position);
          add_field(field, field->drawn_mesh(), *c, object);
          if (type == "HexahedronFEMForceFieldAndMass") {
            if (system.mass.size() != 0) throw make_error(c->where(), ": a second mass for ", object.path);
            system.mass = scene_detail::build_hexahedron_fem_mass(data_, *c, *field, system.state.rest_position);
          }
        }
        if (scene_detail::is_point_spring(type)) {
          object.system.force_fields.push_back(scene_detail::build_point_springs(data_, *c, state, system.state.rest_position, object.mesh));
          object.force_field_drawing.push_back({});
        }
        if (scene_detail::is_element_fem(type)) {
          std::shared_ptr<TetMesh> drawn;
          auto field = scene_detail::build_element_fem(data_, *c, system.state.rest_position,
                                                       [&] { return mesh_of(*c, system.size()); }, drawn);
          add_field(field, drawn, *c, object);
        }
        if (scene_detail::is_penalty_force_field(type)) {
          // Points, not elements: the object's mesh (for output), or a mesh of its points alone.
          auto mesh = object.mesh ? object.mesh : std::make_shared<TetMesh>(system.size(), std::vector<Tetrahedron>{});
          object.system.force_fields.push_back(scene_detail::build_penalty_force_field(data_, *c, mesh));
          object.force_field_drawing.push_back({});
        }
        if (type == "MeshSpringForceField" && !scene_detail::makes_mesh_springs(data_, *c)) {
          info_.push_back(c->where() + ": no per-kind stiffness or damping (linesStiffness, tetrahedraStiffness, ...): no springs, as in SOFA");
        } else if (type == "MeshSpringForceField") {
          add_mesh_springs(*c, object);
        }
        if (type == "ConstantForceField") system.constant_forces.push_back(scene_detail::build_constant_force(data_, info_, *c, system.size()));
        if (type == "QuadPressureForceField") {
          system.constant_forces.push_back(scene_detail::build_quad_pressure(data_, *c, system.state.rest_position));
        }
        if (type == "TrianglePressureForceField") {
          system.constant_forces.push_back(scene_detail::build_triangle_pressure(data_, *c, system.state.rest_position));
        }
        if (type == "FixedProjectiveConstraint") scene_detail::add_fixed_constraint(data_, *c, system);
        if (scene_detail::is_partial_projective_constraint(type)) scene_detail::add_projective_constraint(data_, *c, system);
        if (type == "LinearMovementProjectiveConstraint") {
          system.linear_movements.push_back(scene_detail::build_linear_movement(data_, *c, system.size(), false));
        }
        if (type == "BoxROI") add_boxes(*c, object);
        if (type == "TopologicalChangeProcessor") {
          object.topology_scripts.push_back(build_topology_script(data_, *c, mesh_of(*c, system.size())));
        }
        if (c->spec->category == "mass") {
          if (system.mass.size() != 0) throw make_error(c->where(), ": a second mass for ", object.path);
          system.mass = build_mass(*c, system.state.rest_position);
        }
      }
    }
    finish_part(state, visuals, object);
    return object;
  }

  // The mapped nodes of a part: their mechanics folded in, then the part checked, then their
  // visual models and mapped states.
  void finish_part(Component& state, const std::vector<GraphNode*>& visuals, SimulatedObject<double>& object) {
    for (GraphNode* mapped_node : visuals) {
      if (has_mechanics(*mapped_node)) add_mapped_mechanics(*mapped_node, object);
    }
    try {
      object.system.finalize();
    } catch (const Error& error) {
      throw error_at(state.where(), error);
    }
    for (GraphNode* mapped_node : visuals) {
      scene_detail::add_visual_surfaces(data_, info_, *mapped_node, object);
      if (!has_mechanics(*mapped_node)) scene_detail::add_mapped_states(data_, info_, *mapped_node, object);
    }
  }

  void build_object(GraphNode& solver_node, Component& integrator) {
    std::vector<GraphNode*> nodes;
    mapped_.clear();
    multi_mapped_.clear();
    collect(solver_node, nodes, mapped_);
    std::vector<Component*> states;
    for (GraphNode* node : nodes) {
      for (Component* c : node->of_category("state")) states.push_back(c);
    }
    if (states.empty()) {
      // SOFA's solver then has nothing to integrate and does nothing (STLIB's Scene makes its
      // Simulation node so before a model is added).
      data_.warn(integrator.where() + ": no MechanicalObject in node " + solver_node.path + " or below: it integrates nothing");
      return;
    }
    if (states.size() == 1 && data_.data(*states.front(), "position").empty()) {
      // SOFA steps an empty state without effect.
      info_.push_back(states.front()->where() + ": the state has no points: node " + solver_node.path +
                      " has nothing to simulate");
      return;
    }
    SimulatedObject<double> object;
    std::vector<Index> offsets, sizes;
    if (states.size() == 1) {
      object = build_part(*states.front(), nodes, mapped_);
      offsets = {0};
      sizes = {object.system.size()};
    } else {
      // SOFA's solver integrates every object below it as one system: each object is built from the
      // nodes whose nearest state is its own, then they are merged.
      std::vector<SimulatedObject<double>> parts;
      for (Component* state : states) {
        std::vector<GraphNode*> own, visuals;
        for (GraphNode* node : nodes) {
          if (owner(*node, states) == state) own.push_back(node);
        }
        for (GraphNode* node : mapped_) {
          if (owner(*node->parent, states) == state) visuals.push_back(node);
        }
        parts.push_back(build_part(*state, own, visuals));
        hold_if_still(*state, parts.back());
        offsets.push_back(sizes.empty() ? 0 : offsets.back() + sizes.back());
        sizes.push_back(parts.back().system.size());
      }
      for (GraphNode* node : nodes) {
        if (owner(*node, states)) continue;
        for (const auto& c : node->components) {
          if (c->spec && c->type() != "AttachProjectiveConstraint" && !scene_detail::is_interaction_spring(c->type()) &&
              (c->spec->category == "forcefield" || c->spec->category == "mass" || c->spec->category == "constraint")) {
            throw make_error(c->where(), ": it is in node ", node->path, ", above the objects of the solver of node ",
                             solver_node.path, ": which object it acts on is not defined");
          }
        }
      }
      // A mass on a SubsetMultiMapping's node (STLIB's Rigidify keeps the body's UniformMass there)
      // gives its inputs their mass once folded: until then they weigh nothing.
      bool mass_below = false;
      for (GraphNode* node : multi_mapped_) mass_below = mass_below || !node->of_category("mass").empty();
      for (auto& part : parts) {
        if (mass_below && part.system.mass.size() == 0) {
          part.system.mass = Mass<double>::lumped(std::vector<double>(static_cast<std::size_t>(part.system.size()), 0.0));
        }
      }
      try {
        object = merge_objects(std::move(parts), solver_node.path);
      } catch (const Error& error) {
        throw error_at(integrator.where(), error);
      }
    }
    for (GraphNode* node : multi_mapped_) add_multi_mapped_mechanics(*node, states, offsets, sizes, object);
    add_attach_constraints(nodes, states, offsets, sizes, object.system);
    scene_detail::add_interaction_springs(data_, nodes, states, offsets, sizes, object);
    const Index n = object.system.size();
    auto solvers = build_solvers(data_, info_, integrator, nodes, n);
    if (object.system.rigids && integrator.type() != "EulerImplicitSolver" && integrator.type() != "EulerExplicitSolver") {
      throw make_error(integrator.where(), ": ", integrator.type(), " does not integrate Rigid3 states here ",
                       "(EulerImplicitSolver and EulerExplicitSolver do)");
    }
    object.ode_solver = std::move(solvers.ode);
    object.linear_solver = std::move(solvers.linear);
    simulation_.objects.push_back(std::move(object));
    solver_nodes_.push_back(&solver_node);
    states_.push_back(states.front()->object);
    state_counts_.push_back(states.size());
    for (std::size_t s = 0; s < states.size(); ++s) {
      parts_.push_back({states[s]->object, {0, simulation_.objects.size() - 1, offsets[s], sizes[s]}});
    }
  }

  // The pair constraints of the solver's nodes, which tie points of its objects (in any node:
  // they name their objects).
  void add_attach_constraints(const std::vector<GraphNode*>& nodes, const std::vector<Component*>& states,
                              const std::vector<Index>& offsets, const std::vector<Index>& sizes,
                              MechanicalSystem<double>& system) {
    bool added = false;
    for (GraphNode* node : nodes) {
      for (const auto& c : node->components) {
        if (c->type() != "AttachProjectiveConstraint") continue;
        scene_detail::add_attach_constraint(data_, *c, states, offsets, sizes, system);
        added = true;
      }
    }
    if (!added) return;
    try {
      system.finalize();
    } catch (const Error& error) {
      throw error_at(states.front()->where(), error);
    }
  }


  // MeshSpringForceField on its topology: an edge set's edges, a grid's or hexahedral container's
  // lines, quads and hexahedra, else a tetrahedral mesh's edges, triangles and tetrahedra.
  void add_mesh_springs(Component& c, SimulatedObject<double>& object) {
    const auto& rest = object.system.state.rest_position;
    Component* topology = data_.topology_of(c);
    if (!topology) throw make_error(c.where(), ": no topology in its node or above");
    const std::string_view kind = topology->type();
    if (kind == "EdgeSetTopologyContainer") {
      SpringTopology elements;
      const std::vector<Index> flat = data_.indices(*topology, "edges");
      if (flat.size() % 2 != 0) throw make_error(topology->where(), ": edges needs 2 indices per edge");
      for (std::size_t e = 0; e + 1 < flat.size(); e += 2) {
        for (Index v : {flat[e], flat[e + 1]}) {
          if (v < 0 || v >= object.system.size()) {
            throw make_error(topology->where(), ": edges: point ", v, " is out of range [0, ", object.system.size(), ")");
          }
        }
        elements.lines.push_back({flat[e], flat[e + 1]});
      }
      object.system.force_fields.push_back(scene_detail::build_mesh_springs(data_, c, std::move(elements), rest));
      object.force_field_drawing.push_back({});
      return;
    }
    if (scene_detail::is_grid_topology(kind) || kind == "HexahedronSetTopologyContainer") {
      SpringTopology elements;
      elements.hexahedra = scene_detail::topology_hexahedra(data_, *topology);
      if (kind == "HexahedronSetTopologyContainer") {
        elements.lines = hexahedron_set_edges(elements.hexahedra);
        elements.quads = hexahedron_set_quads(elements.hexahedra);
      } else {
        // Every grid (regular, cylinder, sphere) numbers its points and lines alike: only n matters.
        const RegularGrid grid = data_.grid(*topology);
        elements.lines = grid_edges(grid);
        elements.quads = grid_quads(grid);
      }
      auto field = scene_detail::build_mesh_springs(data_, c, std::move(elements), rest);
      object.system.force_fields.push_back(field);
      object.force_field_drawing.push_back({});
      return;
    }
    auto mesh = mesh_of(c, object.system.size());
    add_field(scene_detail::build_mesh_springs(data_, c, mesh, rest), mesh, c, object);
  }

  std::shared_ptr<TetMesh> mesh_of(Component& user, Index num_points) {
    Component* topology = data_.topology_of(user);
    if (!topology) throw make_error(user.where(), ": no topology in its node or above");
    if (const auto it = meshes_.find(topology); it != meshes_.end()) return it->second;
    std::vector<Index> flat = data_.indices(*topology, "tetrahedra");
    const bool grid = scene_detail::is_grid_topology(topology->type()) || topology->type() == "HexahedronSetTopologyContainer";
    if (flat.empty() && grid && user.type() == "TetrahedronFEMForceField") {
      // TetrahedronFEMForceField tessellates a topology's hexahedra itself, as SOFA's init does (the
      // split depends on the grid's point counts only).
      for (const Tetrahedron& t : scene_detail::tetrahedron_fem_tetrahedra(data_, *topology)) flat.insert(flat.end(), t.begin(), t.end());
    }
    if (flat.empty()) {
      throw make_error(user.where(), ": its topology ", topology->where(), " has no tetrahedra",
                       grid
                           ? " (a grid gives hexahedra: add a TetrahedronSetTopologyContainer filled by a "
                             "Hexa2TetraTopologicalMapping after it)"
                           : "");
    }
    if (flat.size() % 4 != 0) throw make_error(topology->where(), ": tetrahedra needs 4 indices per tetrahedron");
    std::vector<Tetrahedron> tetrahedra(flat.size() / 4);
    for (std::size_t t = 0; t < tetrahedra.size(); ++t) {
      for (int j = 0; j < 4; ++j) tetrahedra[t][j] = flat[4 * t + j];
    }
    const std::vector<Index> edge_list = data_.indices(*topology, "edges");
    try {
      std::shared_ptr<TetMesh> mesh;
      if (edge_list.empty()) {
        mesh = std::make_shared<TetMesh>(num_points, std::move(tetrahedra));
      } else {
        std::vector<Edge> edges(edge_list.size() / 2);
        for (std::size_t e = 0; e < edges.size(); ++e) edges[e] = {edge_list[2 * e], edge_list[2 * e + 1]};
        mesh = std::make_shared<TetMesh>(num_points, std::move(tetrahedra), std::move(edges));
      }
      return meshes_[topology] = mesh;
    } catch (const Error& error) {
      throw error_at(topology->where(), error);
    }
  }

  void add_force_field(Component& c, SimulatedObject<double>& object) {
    auto& system = object.system;
    CorotationalForceField<double>::Parameters parameters;
    if (c.has("youngModulus")) parameters.young_modulus = data_.data(c, "youngModulus");
    if (c.has("poissonRatio")) parameters.poisson_ratio = data_.data(c, "poissonRatio");
    parameters.rayleigh_stiffness = data_.real(c, "rayleighStiffness", 0.0);
    try {
      if (parameters.young_modulus.empty()) throw make_error("youngModulus is empty");
      if (parameters.poisson_ratio.empty()) throw make_error("poissonRatio is empty");
      parameters.method = parse_rotation_method(data_.text(c, "method", "qr"));
      auto mesh = mesh_of(c, system.size());
      ForceFieldDrawing drawing;
      drawing.drawing = data_.boolean(c, "drawing", false);
      for (int k = 0; k < 4; ++k) {
        const std::string name = "drawColor" + std::to_string(k + 1);
        if (c.has(name)) drawing.colors[static_cast<std::size_t>(k)] = scene_detail::parse_color(name, data_.text(c, name, ""));
      }
      system.force_fields.push_back(
          std::make_shared<CorotationalForceField<double>>(mesh, system.state.rest_position, parameters));
      object.force_field_drawing.push_back(drawing);
      if (!object.mesh) object.mesh = mesh;
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
  }

  // A force field with no drawing of its own; the object's mesh (for output) is its mesh if it has none.
  void add_field(std::shared_ptr<ForceField<double>> field, const std::shared_ptr<TetMesh>& mesh, Component& c,
                 SimulatedObject<double>& object) {
    object.system.force_fields.push_back(std::move(field));
    ForceFieldDrawing drawing;
    drawing.drawing = data_.boolean(c, "drawing", false);
    object.force_field_drawing.push_back(drawing);
    if (!object.mesh) object.mesh = mesh;
  }

  void add_tetrahedron_fem(Component& c, SimulatedObject<double>& object) {
    auto& system = object.system;
    TetrahedronFEMForceField<double>::Parameters parameters;
    if (c.has("youngModulus")) parameters.young_modulus = data_.data(c, "youngModulus");
    if (c.has("poissonRatio")) parameters.poisson_ratio = data_.data(c, "poissonRatio");
    parameters.rayleigh_stiffness = data_.real(c, "rayleighStiffness", 0.0);
    if (c.has("localStiffnessFactor")) parameters.local_stiffness_factor = data_.data(c, "localStiffnessFactor");
    parameters.von_mises = data_.whole_number(c, "computeVonMisesStress", 0);
    try {
      if (parameters.young_modulus.empty()) throw make_error("youngModulus is empty");
      if (parameters.poisson_ratio.empty()) throw make_error("poissonRatio is empty");
      if (c.type() == "TetrahedralCorotationalFEMForceField") {
        // SOFA's older corotational tetrahedron: small, polar, and large for any other name.
        parameters.component = "TetrahedralCorotationalFEMForceField";
        const std::string method = data_.text(c, "method", "large");
        parameters.method = method == "small" ? TetrahedronFEMMethod::small
                            : method == "polar" ? TetrahedronFEMMethod::polar : TetrahedronFEMMethod::large;
        if (method != "small" && method != "polar" && method != "large") {
          info_.push_back(c.where() + ": method \"" + method + "\" is not small, large or polar: large is used, as SOFA does");
        }
        if (data_.boolean(c, "computeVonMisesStress", false)) {
          info_.push_back(c.where() + ": computeVonMisesStress: not computed for TetrahedralCorotationalFEMForceField (display only)");
        }
        parameters.von_mises = 0;
      } else {
        parameters.method = parse_tetrahedron_fem_method(data_.text(c, "method", "large"));
      }
      const bool assembling = data_.boolean(c, "computeGlobalMatrix", false) || data_.boolean(c, "assembling", false);
      if (assembling && (parameters.method == TetrahedronFEMMethod::polar || parameters.method == TetrahedronFEMMethod::svd)) {
        throw make_error("computeGlobalMatrix=\"true\" with method ", to_string(parameters.method),
                         ": SOFA computes no elastic force in that combination (its accumulateForce",
                         parameters.method == TetrahedronFEMMethod::polar ? "Polar" : "SVD",
                         " only reports an error); use computeGlobalMatrix=\"false\"");
      }
      if (data_.boolean(c, "updateStiffnessMatrix", false)) {
        if (c.type() != "TetrahedronFEMForceField") {
          throw make_error("updateStiffnessMatrix=\"true\" is not supported (J is taken from the rest shape)");
        }
        parameters.update_stiffness_matrix = parameters.method != TetrahedronFEMMethod::small;  // SOFA: no effect for small
      }
      parameters.plastic_max_threshold = data_.real(c, "plasticMaxThreshold", 0.0);
      if (c.has("plasticYieldThreshold")) parameters.plastic_yield_threshold = data_.real(c, "plasticYieldThreshold", 0.0);
      if (c.has("plasticCreep")) parameters.plastic_creep = data_.real(c, "plasticCreep", 0.0);
      if (parameters.plastic_max_threshold > 0 && assembling) {
        throw make_error("plasticity with computeGlobalMatrix=\"true\": SOFA does not support it either (its force is not computed)");
      }
      if (parameters.von_mises == 1 && parameters.method == TetrahedronFEMMethod::small) {
        info_.push_back(c.where() + ": computeVonMisesStress=\"1\" with method small: SOFA marks the component invalid and "
             "computes no von Mises stress (it still simulates); use 2 for the Green strain");
      }
      auto mesh = mesh_of(c, system.size());
      ForceFieldDrawing drawing;
      drawing.drawing = data_.boolean(c, "drawing", false);
      system.force_fields.push_back(
          std::make_shared<TetrahedronFEMForceField<double>>(mesh, system.state.rest_position, parameters));
      object.force_field_drawing.push_back(drawing);
      if (!object.mesh) object.mesh = mesh;
    } catch (const Error& error) {
      throw error_at(c.where(), error);
    }
  }

  Mass<double> build_mass(Component& c, const Points<double>& rest) {
    return scene_detail::build_mass(data_, c, rest, [&] { return mesh_of(c, static_cast<Index>(rest.size())); });
  }

  // The boxes are kept for drawing only; the selection itself is BoxROI's `indices` data.
  void add_boxes(Component& c, SimulatedObject<double>& object) {
    const Numbers& box = data_.data(c, "box");
    if (box.empty() && c.has("orientedBox")) return;  // oriented boxes only: nothing aligned to draw
    if (box.empty() || box.size() % 6 != 0) {
      throw make_error(c.where(), ": box needs 6 numbers per box (xmin ymin zmin xmax ymax zmax), got ", box.size());
    }
    for (std::size_t b = 0; b < box.size(); b += 6) {
      const Vec3<double> a(box[b], box[b + 1], box[b + 2]), z(box[b + 3], box[b + 4], box[b + 5]);
      object.boxes.push_back({a.cwiseMin(z), a.cwiseMax(z)});
    }
  }

  // SOFA's AddDataRepository and AddResourceRepository add their folder (absolute, or relative to
  // the scene file's folder, which SOFA makes the current one while it loads a scene) to where
  // files are found, before any file is read; returns a warning per folder that does not exist.
  static std::vector<std::string> add_repositories(const SceneNode& node) {
    std::vector<std::string> problems;
    for (const auto& object : node.objects) {
      if (object.type != "AddDataRepository" && object.type != "AddResourceRepository") continue;
      const auto path = object.attributes.find("path");
      if (path == object.attributes.end()) continue;
      std::filesystem::path folder(path->second);
      if (folder.is_relative()) folder = object.location.file.parent_path() / folder;
      std::error_code ec;
      if (!std::filesystem::is_directory(folder, ec)) {
        problems.push_back(object.location.to_string() + ": " + object.type + ": path " + folder.string() + " is not a folder (ignored, as SOFA does)");
        continue;
      }
      add_data_repository(folder.lexically_normal());
    }
    for (const auto& child : node.children) {
      auto more = add_repositories(child);
      problems.insert(problems.end(), more.begin(), more.end());
    }
    return problems;
  }

  std::vector<std::string> info_;
  std::vector<std::string> warnings_;
  std::vector<std::string> repositories_;  // add_repositories' warnings (before data_, which reads files)
  std::vector<GraphNode*> mapped_;  // the mapped child nodes with visual models of the object being built
  std::vector<GraphNode*> multi_mapped_;  // the nodes of its SubsetMultiMappings, in scene order
  SceneData data_;
  Simulation<double> simulation_;
  std::vector<const SceneObject*> states_;  // the (first) MechanicalObject of each simulated object
  std::vector<const GraphNode*> solver_nodes_;  // the node of each simulated object's ODE solver
  scene_detail::LagrangianParts lagrangian_;
  std::vector<std::size_t> state_counts_;   // how many MechanicalObjects each simulated object holds
  std::vector<std::pair<const SceneObject*, LoadedScene::StatePart>> parts_;  // every state, rank to be filled
  std::map<const Component*, std::shared_ptr<TetMesh>> meshes_;
  std::set<const GraphNode*> warned_gravity_;  // nodes whose own gravity was warned unused
  bool allow_empty_ = false;
};

}  // namespace

LoadedScene build_scene(const SceneNode& root, const SceneOptions& options) { return Builder(root, options).build(); }

LoadedScene load_scene_file(const std::filesystem::path& path, const SceneOptions& options) {
  return build_scene(parse_scene_file(path), options);
}

}  // namespace fastcorot
