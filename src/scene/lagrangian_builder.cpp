#include "lagrangian_builder.h"
#include "precomputed_correction_builder.h"
#include "unsimulated_points.h"
#include "projective_constraints.h"
#include "softrobots_builder.h"

#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/constraint/rigid_lagrangian_constraints.h"
#include "fastcorot/constraint/sliding_lagrangian_constraint.h"
#include "fastcorot/constraint/vec1_lagrangian_constraints.h"
#include "fastcorot/constraint/lcp_constraint_solver.h"
#include "fastcorot/core/error.h"
#include "fastcorot/state/rigid3.h"
#include "fastcorot/mapping/distance_mapping.h"
#include "distance_mapping_builder.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>

namespace fastcorot::scene_detail {

namespace {

constexpr std::array<std::string_view, 7> kSolvers = {"BlockGaussSeidelConstraintSolver", "UnbuiltGaussSeidelConstraintSolver",
                                                      "GenericConstraintSolver", "PreconditionedConjugateResidual",
                                                      "NNCGConstraintSolver", "ImprovedJacobiConstraintSolver",
                                                      "LCPConstraintSolver"};
constexpr std::array<std::string_view, 4> kCorrections = {"LinearSolverConstraintCorrection", "GenericConstraintCorrection",
                                                          "UncoupledConstraintCorrection", "PrecomputedConstraintCorrection"};
constexpr std::array<std::string_view, 5> kConstraints = {"FixedLagrangianConstraint", "BilateralLagrangianConstraint",
                                                          "SlidingLagrangianConstraint", "UniformLagrangianConstraint",
                                                          "StopperLagrangianConstraint"};

template <std::size_t N>
bool among(const std::array<std::string_view, N>& names, std::string_view type) {
  return std::find(names.begin(), names.end(), type) != names.end();
}

// Every component of the graph in SOFA's visiting order: a node's components, then its children.
void collect(GraphNode& node, std::vector<Component*>& out) {
  for (const auto& c : node.components) {
    if (c->spec && is_lagrangian_component(c->type())) out.push_back(c.get());
  }
  for (const auto& child : node.children) collect(*child, out);
}

// SOFA's solver parameters (GenericConstraintSolver's data, maxIt its alias of maxIterations).
ConstraintSolverParameters<double> solver_parameters(SceneData& data, Component& c) {
  ConstraintSolverParameters<double> p;
  p.max_iterations = data.whole_number(c, c.has("maxIterations") ? "maxIterations" : "maxIt", 1000);
  // GenericConstraintSolver's NNCG took its iterations from newtonIterations (SOFA's change list).
  if (c.type() == "GenericConstraintSolver" && data.text(c, "resolutionMethod", "") == "NonsmoothNonlinearConjugateGradient") {
    p.max_iterations = data.whole_number(c, "newtonIterations", 100);
  }
  p.tolerance = data.real(c, "tolerance", 1e-3);
  p.sor = data.real(c, "sor", 1.0);
  p.regularization = data.real(c, "regularizationTerm", 0.0);
  p.scale_tolerance = data.boolean(c, "scaleTolerance", true);
  p.all_verified = data.boolean(c, "allVerified", false);
  p.svd_regularization = data.boolean(c, "useSVDForRegularization", false);
  p.svd_value_factor = data.real(c, "svdSingularValueNullSpaceCriteriaFactor", 0.01);
  p.svd_vector_factor = data.real(c, "svdSingularVectorNullSpaceCriteriaFactor", 0.001);
  return p;
}

// SOFA's LCPConstraintSolver: its own data (tolerance, maxIt, mu, minW, maxF, regularizationTerm).
std::unique_ptr<ConstraintSolver<double>> build_lcp_solver(SceneData& data, std::vector<std::string>& info, Component& c,
                                                           ConstraintSolverParameters<double> p) {
  typename LCPConstraintSolver<double>::Options o;
  o.mu = data.real(c, "mu", 0.6);
  o.min_w = data.real(c, "minW", 0.0);
  o.max_f = data.real(c, "maxF", 0.0);
  if (!data.boolean(c, "build_lcp", true)) {
    info.push_back(c.where() + ": build_lcp=\"0\" (SOFA's unbuilt variant) solves the same problem on the built W here");
  }
  return std::make_unique<LCPConstraintSolver<double>>(p, o);
}

std::unique_ptr<ConstraintSolver<double>> build_solver(SceneData& data, std::vector<std::string>& info, Component& c) {
  try {
    const auto p = solver_parameters(data, c);
    std::string_view type = c.type();
    if (type == "GenericConstraintSolver") {
      // Gone from SOFA master (v25.12); its change list maps it by resolutionMethod.
      const std::string method = data.text(c, "resolutionMethod", "ProjectedGaussSeidel");
      if (method == "ProjectedGaussSeidel") {
        type = "BlockGaussSeidelConstraintSolver";
      } else if (method == "UnbuiltGaussSeidel") {
        type = "UnbuiltGaussSeidelConstraintSolver";
      } else if (method == "NonsmoothNonlinearConjugateGradient") {
        type = "NNCGConstraintSolver";
      } else {
        throw make_error("resolutionMethod = \"", method,
                         "\": not one of ProjectedGaussSeidel, UnbuiltGaussSeidel, NonsmoothNonlinearConjugateGradient");
      }
      data.warn(c.where() + ": GenericConstraintSolver was replaced in SOFA v25.12; run as " + std::string(type) +
                " (resolutionMethod " + method + "), as SOFA's change list maps it");
    }
    if (type == "UnbuiltGaussSeidelConstraintSolver") {
      // Not one of SOFA's built solvers: W's singular values are not looked at there.
      auto unbuilt = p;
      unbuilt.svd_regularization = false;
      return std::make_unique<UnbuiltGaussSeidelSolver<double>>(unbuilt);
    }
    if (type == "PreconditionedConjugateResidual") return std::make_unique<PreconditionedConjugateResidualSolver<double>>(p);
    if (type == "NNCGConstraintSolver") return std::make_unique<NNCGSolver<double>>(p);
    if (type == "ImprovedJacobiConstraintSolver") {
      typename ImprovedJacobiSolver<double>::Options o;
      o.spectral_correction = data.boolean(c, "useSpectralCorrection", false);
      o.spectral_factor = data.real(c, "spectralCorrectionFactor", 1.0);
      o.conjugate_residue = data.boolean(c, "useConjugateResidue", false);
      o.conjugate_residue_speed = data.real(c, "conjugateResidueSpeedFactor", 10.0);
      return std::make_unique<ImprovedJacobiSolver<double>>(p, o);
    }
    if (type == "LCPConstraintSolver") return build_lcp_solver(data, info, c, p);
    static_cast<void>(info);
    return std::make_unique<BlockGaussSeidelSolver<double>>(p);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
}

// The MechanicalObject a single-state component acts on: its node's.
Component& own_state(Component& c) {
  const auto states = c.node->of_category("state");
  if (states.empty()) throw make_error(c.where(), ": node ", c.node->path, " has no MechanicalObject");
  return *states.front();
}

class LoopBuilder {
 public:
  LoopBuilder(SceneData& data, std::vector<std::string>& info, Simulation<double>& simulation,
              const std::vector<const GraphNode*>& solver_nodes, const LocateState& locate)
      : data_(data), info_(info), simulation_(simulation), solver_nodes_(solver_nodes), locate_(locate) {}

  LagrangianParts build(Component& loop_component, const std::vector<Component*>& components) {
    LagrangianParts parts;
    Component* solver_component = nullptr;
    for (Component* c : components) {
      if (!among(kSolvers, c->type())) continue;
      if (solver_component) {
        info_.push_back(c->where() + ": a second constraint solver is ignored (SOFA's loop uses one: " + solver_component->where() + ")");
        continue;
      }
      solver_component = c;
    }
    std::unique_ptr<ConstraintSolver<double>> solver;
    if (solver_component) {
      solver = build_solver(data_, info_, *solver_component);
      parts.solver = solver_component->object;
    } else {
      data_.warn(loop_component.where() + ": no constraint solver in the scene: a BlockGaussSeidelConstraintSolver "
                 "with SOFA's defaults is used, as SOFA adds one");
      solver = std::make_unique<BlockGaussSeidelSolver<double>>(ConstraintSolverParameters<double>{});
    }
    typename FreeMotionAnimationLoop<double>::Parameters parameters;
    parameters.solve_velocity_constraint_first = data_.boolean(loop_component, "solveVelocityConstraintFirst", false);
    if (solver_component && solver_component->type() == "LCPConstraintSolver" && parameters.solve_velocity_constraint_first) {
      // SOFA's LCP solver builds its problem with its own parameters (position violations, both x
      // and v corrected) whatever the loop asks: the two do not combine into one defined step.
      throw error_at(loop_component.where(), make_error("solveVelocityConstraintFirst with ", solver_component->where(),
                                                        ": SOFA's LCPConstraintSolver always solves on positions; use "
                                                        "another constraint solver, or solveVelocityConstraintFirst=\"0\""));
    }
    lcp_ = solver_component && solver_component->type() == "LCPConstraintSolver";
    velocity_first_ = parameters.solve_velocity_constraint_first;
    unbuilt_ = solver->unbuilt();
    loop_ = std::make_shared<FreeMotionAnimationLoop<double>>(parameters, std::move(solver));
    for (Component* c : components) {
      try {
        if (among(kCorrections, c->type())) add_correction(*c);
        if (among(kConstraints, c->type()) || is_softrobots_constraint(c->type())) {
          add_constraint(*c);
          parts.constraints.push_back(c->object);
        }
      } catch (const Error& error) {
        throw error_at(c->where(), error);
      }
    }
    check_corrected();
    if (solver_component && solver_component->type() == "LCPConstraintSolver" && !parts.constraints.empty()) {
      data_.warn(solver_component->where() + ": LCPConstraintSolver solves every row as a contact (three rows each: normal and two "
                 "tangents with mu = " + data_.text(*solver_component, "mu", "0.6") + "; one row each with mu = 0), as SOFA does: "
                 "the Lagrangian constraints here are not held bilaterally (a BlockGaussSeidelConstraintSolver solves them)");
    }
    simulation_.constraints = loop_;
    return parts;
  }

 private:
  StateLocation locate(Component& state, Component& user) {
    const auto found = locate_(state);
    if (!found) {
      throw make_error(state.where(), " is not simulated (no ODE solver integrates it, or it is not a state "
                       "the mechanics follow): ", user.type(), " cannot act on it");
    }
    return *found;
  }

  // `vec1`: the caller is a constraint SOFA defines on Vec1 states (else a Vec1 state is refused).
  ConstraintPoints<double> points_of(Component& state, Component& user, bool vec1 = false) {
    const StateLocation where = locate(state, user);
    ConstraintPoints<double> points;
    points.object = where.object;
    const auto& object = simulation_.objects[where.object];
    if (where.mapped) {
      if (where.mapped->coordinates == 1) {
        if (!vec1) {
          throw make_error(state.where(), " is a Vec1 state: ", user.type(), " acts on Vec3 and Rigid3 states here (on Vec1 states: "
                           "UniformLagrangianConstraint, StopperLagrangianConstraint)");
        }
        return vec1_points(*where.mapped, where.object);
      }
      if (where.mapped->through) {
        throw make_error(state.where(), " is below a SubsetMultiMapping or follows several rigid bodies: "
                         "Lagrangian constraints on it are not supported");
      }
      points.mapping = std::shared_ptr<MechanicalMapping<double>>(mechanical_mapping(where.mapped->map, where.mapped->rigid));
      points.rest_position.resize(points.mapping->size());
      points.mapping->positions(object.system.state.rest_position, points.rest_position);
      return points;
    }
    if (where.rigid) {
      throw make_error(state.where(), " is a Rigid3 state: ", user.type(),
                       " on rigid bodies is not simulated yet (put it on points the rigid carries, under a RigidMapping)");
    }
    for (Index i = 0; i < where.size; ++i) {
      points.blocks.push_back(where.offset + i);
      points.rest_position.push_back(object.system.state.rest_position[static_cast<std::size_t>(where.offset + i)]);
    }
    return points;
  }

  // The points of a Vec1 state (a DistanceMapping's output): the mapping's own copy (it records
  // its directions where the step starts) on the state's points in the object, the state's
  // constraint-force sink for the geometric stiffness, rest values zero (SOFA's mapped state keeps
  // the zeros it was resized with) or, with applyRestPosition, the extensions at rest.
  ConstraintPoints<double> vec1_points(const MappedState& mapped, std::size_t object) {
    const auto distance = std::dynamic_pointer_cast<const DistanceMapping<double>>(mapped.through);
    if (!distance) throw make_error("node ", mapped.node, ": a Vec1 state that is not a DistanceMapping's output");
    ConstraintPoints<double> points;
    points.object = object;
    // The mapping reads its own MechanicalObject's points: where they start in the (merged) object.
    std::vector<Edge> edges = distance->edges();
    for (Edge& e : edges) e = {e[0] + mapped.through_offset, e[1] + mapped.through_offset};
    points.mapping = std::make_shared<DistanceMapping<double>>(std::move(edges), simulation_.objects[object].system.state.position,
                                                               distance->rest_lengths());
    points.constraint_force = mapped.constraint_force;
    points.rest_position.assign(distance->size(), Vec3<double>::Zero());
    if (mapped.apply_rest_position) points.mapping->positions(simulation_.objects[object].system.state.rest_position, points.rest_position);
    return points;
  }

  // A Vec1-only constraint (UniformLagrangianConstraint, StopperLagrangianConstraint) on its
  // node's state: both that state and a written template must be Vec1 (SOFA registers no other).
  ConstraintPoints<double> vec1_state_points(Component& c) {
    Component& state = own_state(c);
    const std::string written = data_.text(c, "template", "Vec1d");
    if (!is_vec1_template(written)) throw make_error("template="", written, "": SOFA defines ", c.type(), " on Vec1 states only");
    if (!is_vec1_template(data_.text(state, "template", "Vec3d"))) {
      throw make_error(state.where(), " is a ", data_.text(state, "template", "Vec3d"), " state: SOFA defines ", c.type(),
                       " on Vec1 states only (here: the output of a DistanceMapping)");
    }
    return points_of(state, c, true);
  }

  // Whether c acts on Rigid3 states: its template when written, else its state's (SOFA's factory
  // takes the linked state's). Only Vec3 and Rigid3 are simulated; the two must agree.
  bool on_rigids(Component& c, Component& state) {
    if (is_vec1_template(data_.text(state, "template", "Vec3d"))) {
      throw make_error(state.where(), " is a Vec1 state: ", c.type(), " acts on Vec3 and Rigid3 states here (on Vec1 states: "
                       "UniformLagrangianConstraint, StopperLagrangianConstraint)");
    }
    const bool rigid_state = is_rigid_template(data_.text(state, "template", "Vec3d"));
    if (!c.has("template")) return rigid_state;
    const std::string written = data_.text(c, "template", "Vec3d");
    const bool rigid = is_rigid_template(written);
    if (!rigid && written != "Vec3d" && written != "Vec3f" && written != "Vec3") {
      throw make_error("template=\"", written, "\": only Vec3 and Rigid3 Lagrangian constraints are simulated");
    }
    if (rigid != rigid_state) {
      throw make_error("template=\"", written, "\" but ", state.where(), " is a ", rigid_state ? "Rigid3" : "Vec3", " state");
    }
    return rigid;
  }

  // The rigids of a simulated Rigid3 MechanicalObject, for the Rigid3 constraints.
  RigidConstraintFrames<double> rigid_frames(Component& state, Component& user) {
    const StateLocation where = locate(state, user);
    const auto& object = simulation_.objects[where.object];
    if (where.mapped || !where.rigid || !object.system.rigids) {
      throw make_error(state.where(), " is not a simulated Rigid3 state: ", user.type(),
                       " on Rigid3 acts on rigid bodies' own MechanicalObject (a mapped Rigid3 state is not supported)");
    }
    const auto& rigids = *object.system.rigids;
    const auto& x = object.system.state;
    RigidConstraintFrames<double> frames;
    frames.rigids = object.system.rigids;
    frames.linear.object = frames.angular.object = where.object;
    for (Index b = where.offset; b < where.offset + where.size; b += 2) {
      const auto found = std::find(rigids.block.begin(), rigids.block.end(), b);
      if (found == rigids.block.end()) throw make_error(state.where(), ": block ", b, " of its object is not a rigid's centre");
      const auto k = static_cast<std::size_t>(found - rigids.block.begin());
      const auto block = static_cast<std::size_t>(b);
      frames.index.push_back(k);
      frames.linear.blocks.push_back(b);
      frames.angular.blocks.push_back(b + 1);
      frames.linear.rest_position.push_back(x.rest_position[block]);
      frames.angular.rest_position.push_back(x.rest_position[block + 1]);
      frames.rest.push_back(rigids.rest_coord(x.rest_position, k));
      frames.initial.push_back(rigids.coord(x.position, k));
    }
    return frames;
  }

  // FixedLagrangianConstraint's and BilateralLagrangianConstraint's indices (fixAll: every one).
  std::vector<Index> fixed_indices(Component& c, std::size_t size) {
    std::vector<Index> indices;
    if (data_.boolean(c, "fixAll", false)) {
      for (std::size_t i = 0; i < size; ++i) indices.push_back(static_cast<Index>(i));
    } else if (c.has("indices")) {
      indices = data_.indices(c, "indices");
    }
    if (indices.empty()) info_.push_back(c.where() + ": no indices: it holds nothing (as in SOFA)");
    return indices;
  }

  // BilateralLagrangianConstraint<Rigid3>: SOFA's Rigid3 specialisation (six numbers per rest vector,
  // keepOrientationDifference; activate and load unused there).
  void add_rigid_bilateral(Component& c, Component& first, Component& second, std::vector<Index> first_points,
                           std::vector<Index> second_points) {
    typename RigidBilateralLagrangianConstraint<double>::Parameters p;
    p.first = std::move(first_points);
    p.second = std::move(second_points);
    p.keep_orientation_difference = data_.boolean(c, "keepOrientationDifference", false);
    const Numbers rest = c.has("rest_vector") ? data_.data(c, "rest_vector") : Numbers{};
    if (rest.size() % 6 != 0) {
      throw make_error("rest_vector has ", rest.size(), " numbers: a Rigid3 pair's is 6 (vx vy vz wx wy wz)");
    }
    for (std::size_t k = 0; k < rest.size(); k += 6) p.rest.push_back({rest[k], rest[k + 1], rest[k + 2], rest[k + 3], rest[k + 4], rest[k + 5]});
    if (p.keep_orientation_difference && !p.rest.empty()) {
      data_.warn(c.where() + ": keepOrientationDifference is set: rest_vector is ignored (as SOFA warns)");
    }
    if (!data_.boolean(c, "activate", true) || data_.real(c, "load", 1.0) != 1.0) {
      data_.warn(c.where() + ": activate and load are not used on Rigid3 states (SOFA's Rigid3 specialisation ignores them): "
                 "the constraint is active with load 1");
    }
    loop_->constraints.push_back(std::make_unique<RigidBilateralLagrangianConstraint<double>>(
        c.where(), rigid_frames(first, c), rigid_frames(second, c), std::move(p)));
  }

  // object1 / object2 of a pair constraint: the linked state, else the node's.
  Component& linked_state(Component& c, const char* name) {
    return c.has(name) ? data_.resolve_state(*c.node, c.object->attributes.at(name), c) : own_state(c);
  }

  // The points of a simulated state, or of one no ODE solver integrates (they stay put).
  ConstraintPoints<double> points_or_unsimulated(Component& state, Component& user) {
    if (!locate_(state)) {
      if (auto still = UnsimulatedPoints(data_, info_, locate_).points(state, user)) return std::move(*still);
    }
    return points_of(state, user);  // throws, saying why, when neither
  }

  // SlidingLagrangianConstraint: object1's sliding_point on the segment axis_1–axis_2 of object2.
  void add_sliding(Component& c) {
    ConstraintPoints<double> sets[2];
    const char* links[2] = {"object1", "object2"};
    for (int k = 0; k < 2; ++k) sets[k] = points_or_unsimulated(linked_state(c, links[k]), c);
    if (sets[0].unsimulated && sets[1].unsimulated) {
      throw make_error("object1 and object2 are both unsimulated: nothing can move to satisfy it");
    }
    typename SlidingLagrangianConstraint<double>::Parameters p;
    p.sliding_point = data_.whole_number(c, "sliding_point", 0);
    p.axis_1 = data_.whole_number(c, "axis_1", 0);
    p.axis_2 = data_.whole_number(c, "axis_2", 0);
    loop_->constraints.push_back(
        std::make_unique<SlidingLagrangianConstraint<double>>(c.where(), std::move(sets[0]), std::move(sets[1]), p));
  }

  void add_constraint(Component& c) {
    if (is_softrobots_constraint(c.type())) {
      Component& state = own_state(c);
      if (on_rigids(c, state)) throw make_error(c.type(), " acts on Vec3 states (a cable's points), not on Rigid3");
      ConstraintPoints<double> points = points_of(state, c);
      const auto& object = simulation_.objects[points.object].system.state;
      std::vector<Vec3<double>> initial;
      if (points.mapping) {
        initial.resize(points.mapping->size());
        points.mapping->positions(object.position, initial);
      } else {
        for (const Index b : points.blocks) initial.push_back(object.position[static_cast<std::size_t>(b)]);
      }
      loop_->constraints.push_back(build_softrobots_constraint(data_, c, std::move(points), initial));
      return;
    }
    if (c.type() == "UniformLagrangianConstraint") {
      typename UniformLagrangianConstraint<double>::Parameters p;
      p.iterative = data_.boolean(c, "iterative", true);
      p.constrain_to_rest = data_.boolean(c, "constrainToRestPos", false);
      loop_->constraints.push_back(std::make_unique<UniformLagrangianConstraint<double>>(c.where(), vec1_state_points(c), p));
      return;
    }
    if (c.type() == "StopperLagrangianConstraint") {
      typename StopperLagrangianConstraint<double>::Parameters p;
      p.index = data_.whole_number(c, "index", 0);
      p.min = data_.real(c, "min", -100.0);
      p.max = data_.real(c, "max", 100.0);
      loop_->constraints.push_back(std::make_unique<StopperLagrangianConstraint<double>>(c.where(), vec1_state_points(c), p));
      return;
    }
    if (c.type() == "SlidingLagrangianConstraint") {
      if (on_rigids(c, linked_state(c, "object1"))) throw make_error("SOFA defines SlidingLagrangianConstraint on Vec3 states only, not on Rigid3");
      add_sliding(c);
      return;
    }
    if (c.type() == "FixedLagrangianConstraint") {
      Component& state = own_state(c);
      if (on_rigids(c, state)) {
        RigidConstraintFrames<double> frames = rigid_frames(state, c);
        std::vector<Index> indices = fixed_indices(c, frames.size());
        loop_->constraints.push_back(std::make_unique<RigidFixedLagrangianConstraint<double>>(c.where(), std::move(frames), std::move(indices)));
        return;
      }
      ConstraintPoints<double> points = points_of(state, c);
      std::vector<Index> indices = fixed_indices(c, points.size());
      loop_->constraints.push_back(std::make_unique<FixedLagrangianConstraint<double>>(c.where(), std::move(points), std::move(indices)));
      return;
    }
    // BilateralLagrangianConstraint: object1 and object2 default to the node's state.
    Component& first = linked_state(c, "object1");
    Component& second = linked_state(c, "object2");
    const bool rigid = on_rigids(c, first);
    if (on_rigids(c, second) != rigid) {
      throw make_error(first.where(), " and ", second.where(), ": one is a Rigid3 state and the other not");
    }
    typename BilateralLagrangianConstraint<double>::Parameters p;
    p.first = c.has("first_point") ? data_.indices(c, "first_point") : std::vector<Index>{};
    p.second = c.has("second_point") ? data_.indices(c, "second_point") : std::vector<Index>{};
    if (p.first.size() != p.second.size()) {
      data_.warn(c.where() + ": first_point has " + std::to_string(p.first.size()) + " indices and second_point " +
                 std::to_string(p.second.size()) + ": only the first " + std::to_string(std::min(p.first.size(), p.second.size())) +
                 " pairs are tied (as in SOFA)");
    }
    if (rigid) {
      add_rigid_bilateral(c, first, second, std::move(p.first), std::move(p.second));
      return;
    }
    p.rest = c.has("rest_vector") ? data_.points(c, "rest_vector") : std::vector<Vec3<double>>{};
    p.active = data_.boolean(c, "activate", true);
    p.load = data_.real(c, "load", 1.0);
    if (p.load < 0 || p.load > 1) {
      data_.warn(c.where() + ": load = " + std::to_string(p.load) + " lies outside [0, 1]: clamped, as SOFA does");
      p.load = std::clamp(p.load, 0.0, 1.0);
    }
    ConstraintPoints<double> first_points = points_or_unsimulated(first, c);
    ConstraintPoints<double> second_points = points_or_unsimulated(second, c);
    if (first_points.unsimulated && second_points.unsimulated) {
      throw make_error("object1 and object2 are both unsimulated: nothing can move to satisfy it");
    }
    loop_->constraints.push_back(std::make_unique<BilateralLagrangianConstraint<double>>(
        c.where(), std::move(first_points), std::move(second_points), std::move(p)));
  }

  // The linear solver component of object o's solver node, if any.
  Component* linear_solver_of(std::size_t o) {
    const auto solvers = solver_nodes_[o]->of_category("linearsolver");
    return solvers.empty() ? nullptr : solvers.front();
  }

  void add_correction(Component& c) {
    const bool through_solver = c.type() == "LinearSolverConstraintCorrection" || c.type() == "GenericConstraintCorrection";
    if (through_solver && c.node->of_category("state").empty()) {
      // Beside the ODE solver, above the objects it integrates (SoftRobots' Trunk): SOFA's
      // correction then serves every state that solver solves.
      bool found = false;
      for (std::size_t o = 0; o < solver_nodes_.size() && o < simulation_.objects.size(); ++o) {
        if (solver_nodes_[o] != c.node) continue;
        add_solver_correction(c, o);
        found = true;
      }
      if (!found) {
        throw make_error(c.where(), ": node ", c.node->path, " has no MechanicalObject and no ODE solver whose objects it could correct");
      }
      return;
    }
    Component& state = own_state(c);
    const StateLocation where = locate(state, c);
    if (where.mapped) {
      throw make_error("its MechanicalObject ", state.where(), " is mapped: a constraint correction belongs with the "
                       "simulated state (the node of the ODE solver's object)");
    }
    const std::size_t o = where.object;
    auto& object = simulation_.objects[o];
    if (c.type() == "PrecomputedConstraintCorrection") {
      add_precomputed(c, where);
      return;
    }
    if (c.type() == "UncoupledConstraintCorrection") {
      if (kind_.count(o) && kind_[o] != "uncoupled") {
        throw make_error(object.path, " already has a ", kind_[o], ": one kind of correction per ODE solver's object");
      }
      kind_[o] = "uncoupled";
      if (data_.boolean(c, "useOdeSolverIntegrationFactors", true) && !object.ode_solver->integration_factors(simulation_.dt)) {
        throw make_error("the ODE solver of ", object.path, " does not give SOFA's integration factors (EulerImplicitSolver "
                         "does): set useOdeSolverIntegrationFactors=\"0\"");
      }
      auto parameters = uncoupled(c, where);
      if (unbuilt_ && parameters.use_ode_factors && !velocity_first_) {
        data_.warn(c.where() + ": under an UnbuiltGaussSeidelConstraintSolver SOFA reads this correction's compliance without the "
                   "ODE factor h (its unbuilt path), so each step closes only about h of a constraint's violation; reproduced as "
                   "SOFA does it (a BlockGaussSeidelConstraintSolver gives the intended compliance)");
      }
      covered_[o].push_back({parameters.offset, parameters.offset + static_cast<Index>(parameters.compliance.size())});
      loop_->corrections.push_back(std::make_unique<UncoupledConstraintCorrection<double>>(c.where(), o, std::move(parameters)));
      return;
    }
    add_solver_correction(c, o);
  }

  // LinearSolverConstraintCorrection and GenericConstraintCorrection of object o: through its solver.
  void add_solver_correction(Component& c, std::size_t o) {
    auto& object = simulation_.objects[o];
    if (kind_.count(o)) {
      if (kind_[o] == "PrecomputedConstraintCorrection") throw make_error(object.path, " already has a PrecomputedConstraintCorrection: one kind of correction per ODE solver's object");
      if (kind_[o] == "uncoupled") throw make_error(object.path, " already has an UncoupledConstraintCorrection: one kind of correction per ODE solver's object");
      // Several objects under one linear solver each with a correction (SOFA issue #5501): one
      // correction of the whole system serves them all.
      info_.push_back(c.where() + ": " + object.path + " is already corrected through its linear solver: this correction is the same one");
      return;
    }
    if (Component* linear = linear_solver_of(o)) {
      const std::string_view type = linear->type();
      const std::string tmpl = data_.text(*linear, "template", "GraphScattered");
      if ((type == "CGLinearSolver" || type == "MinResLinearSolver") && tmpl.find("CompressedRowSparseMatrix") == std::string::npos) {
        throw make_error("the linear solver ", linear->where(), " is matrix-free (SOFA's GraphScattered template), which ",
                         c.type(), " cannot use: use a SparseLDLSolver, a CGLinearSolver with template=\"CompressedRowSparseMatrixMat3x3d\", "
                         "or an UncoupledConstraintCorrection");
      }
    }
    if (!object.ode_solver->integration_factors(simulation_.dt)) {
      throw make_error("the ODE solver of ", object.path, " does not give SOFA's integration factors (EulerImplicitSolver does)");
    }
    kind_[o] = std::string(c.type());
    const double compliance_factor = c.type() == "GenericConstraintCorrection" ? data_.real(c, "complianceFactor", 1.0) : 1.0;
    loop_->corrections.push_back(std::make_unique<LinearSolverConstraintCorrection<double>>(
        c.where(), o, data_.real(c, "regularizationTerm", 0.0), compliance_factor));
  }

  // SOFA's PrecomputedConstraintCorrection (precomputed_correction_builder.cpp).
  void add_precomputed(Component& c, const StateLocation& where) {
    const std::size_t o = where.object;
    if (kind_.count(o)) {
      throw make_error(simulation_.objects[o].path, " already has a ", kind_[o] == "uncoupled" ? "UncoupledConstraintCorrection" : kind_[o],
                       ": one kind of correction per ODE solver's object");
    }
    loop_->corrections.push_back(build_precomputed_correction(data_, info_, c, simulation_, where, lcp_));
    kind_[o] = "PrecomputedConstraintCorrection";
  }

  // SOFA's UncoupledConstraintCorrection::init for points and for rigid bodies.
  typename UncoupledConstraintCorrection<double>::Parameters uncoupled(Component& c, const StateLocation& where) {
    typename UncoupledConstraintCorrection<double>::Parameters p;
    p.offset = where.offset;
    p.use_ode_factors = data_.boolean(c, "useOdeSolverIntegrationFactors", true);
    p.position_factor = data_.real(c, "correctionPositionFactor", 1.0);
    p.velocity_factor = data_.real(c, "correctionVelocityFactor", 1.0);
    const bool default_set = c.has("defaultCompliance");
    const double fallback = data_.real(c, "defaultCompliance", 1e-5);
    const Numbers compliance = c.has("compliance") ? data_.data(c, "compliance") : Numbers{};
    if (!default_set && compliance.empty() && !where.rigid) {
      data_.warn(c.where() + ": neither defaultCompliance nor compliance is set: defaultCompliance 1e-5 is used, as in SOFA "
                 "(set one: the compliance is not derived from the mass for points)");
    }
    if (default_set && fallback == 0) throw make_error("defaultCompliance = 0: the constraint solve would divide by zero");
    for (double value : compliance) {
      if (!std::isfinite(value)) throw make_error("compliance has a value that is not finite");
    }
    if (where.rigid) {
      // 7 numbers: 1/m for the centre, then the rotation's upper triangle.
      const double ode = p.use_ode_factors ? 1.0 : simulation_.dt * simulation_.dt;
      Numbers seven = compliance;
      if (!seven.empty() && seven.size() != 7) {
        data_.warn(c.where() + ": compliance has " + std::to_string(seven.size()) +
                   " values: a rigid body's is 7 (1/m, then the rotation's upper triangle); derived from the mass instead, as SOFA does");
      }
      if (seven.size() != 7) {
        seven.clear();
        const auto& mass = simulation_.objects[where.object].system.mass;
        Mat3<double> inverse_inertia = Mat3<double>::Identity();
        if (default_set) {
          seven.push_back(fallback);
        } else if (mass.is_block_diagonal()) {
          const auto blocks = mass.blocks();
          const double m = blocks[static_cast<std::size_t>(where.offset)](0, 0);
          seven.push_back(ode / m);
          inverse_inertia = blocks[static_cast<std::size_t>(where.offset) + 1].inverse();
        } else {
          throw make_error("no defaultCompliance and no UniformMass on the rigid bodies to derive the compliance from");
        }
        for (auto [r, k] : {std::pair{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}}) seven.push_back(ode * inverse_inertia(r, k));
      }
      if (seven[0] == 0 || seven[1] == 0 || seven[4] == 0 || seven[6] == 0) {
        throw make_error("a zero compliance on a translation or on the rotation's diagonal: the constraint solve would divide by zero");
      }
      Mat3<double> rotation;
      rotation << seven[1], seven[2], seven[3], seven[2], seven[4], seven[5], seven[3], seven[5], seven[6];
      for (Index k = 0; k < where.size / 2; ++k) {
        p.compliance.push_back(seven[0] * Mat3<double>::Identity());
        p.compliance.push_back(rotation);
      }
      return p;
    }
    const auto n = static_cast<std::size_t>(where.size);
    Numbers per_point = compliance;
    double base = fallback;
    if (per_point.size() == 1 && default_set && per_point[0] == fallback) per_point.clear();
    if (!per_point.empty() && per_point.size() != n) {
      if (per_point.size() > 1) {
        data_.warn(c.where() + ": compliance has " + std::to_string(per_point.size()) + " values for " + std::to_string(n) +
                   " points: a default compliance is used, as in SOFA");
      }
      if (!default_set) base = per_point[0];
      per_point.clear();
    }
    for (double value : per_point) {
      if (value == 0) throw make_error("a zero compliance: the constraint solve would divide by zero");
    }
    for (std::size_t i = 0; i < n; ++i) p.compliance.push_back((per_point.empty() ? base : per_point[i]) * Mat3<double>::Identity());
    return p;
  }

  // Every object a constraint acts on has a correction, and under uncoupled corrections every
  // block its points reach is one a correction covers (several MechanicalObjects under one solver
  // each have their own): else W's rows would be empty and the constraint silently ignored.
  void check_corrected() {
    std::vector<std::pair<Index, Mat3<double>>> blocks;
    for (const auto& constraint : loop_->constraints) {
      for (ConstraintPoints<double>* points : constraint->point_sets()) {
        if (points->unsimulated) continue;
        const std::size_t o = points->object;
        const std::string& path = simulation_.objects[o].path;
        if (!kind_.count(o)) {
          throw make_error(constraint->where(), ": it acts on ", path,
                           ", which has no constraint correction (add a LinearSolverConstraintCorrection, "
                           "GenericConstraintCorrection or UncoupledConstraintCorrection in its solver's node)");
        }
        if (kind_[o] != "uncoupled") continue;
        const auto covered = [&](Index block) {
          for (const auto& [first, end] : covered_[o]) {
            if (block >= first && block < end) return true;
          }
          return false;
        };
        if (points->mapping) {
          // J's blocks need the mapping's linearisation (a rigid mapping's rotated points).
          std::vector<Vec3<double>> at(points->size());
          points->mapping->apply(simulation_.objects[o].system.state.position, at);
        }
        for (std::size_t i = 0; i < points->size(); ++i) {
          blocks.clear();
          if (points->mapping) {
            points->mapping->row_blocks(i, blocks);
          } else {
            blocks.push_back({points->blocks[i], Mat3<double>::Identity()});
          }
          for (const auto& [block, weight] : blocks) {
            if (!covered(block)) {
              throw make_error(constraint->where(), ": it acts on a MechanicalObject of ", path,
                               " that has no UncoupledConstraintCorrection (each MechanicalObject under the solver needs its own)");
            }
          }
        }
      }
    }
  }

  SceneData& data_;
  std::vector<std::string>& info_;
  Simulation<double>& simulation_;
  const std::vector<const GraphNode*>& solver_nodes_;
  const LocateState& locate_;
  bool lcp_ = false;  // the loop's solver is an LCPConstraintSolver
  bool unbuilt_ = false;  // ... an unbuilt one (UnbuiltGaussSeidelConstraintSolver)
  bool velocity_first_ = false;  // solveVelocityConstraintFirst
  std::shared_ptr<FreeMotionAnimationLoop<double>> loop_;
  std::map<std::size_t, std::string> kind_;  // the kind of correction of each corrected object
  std::map<std::size_t, std::vector<std::pair<Index, Index>>> covered_;  // blocks [first, end) with an uncoupled correction
};

}  // namespace

bool is_lagrangian_component(std::string_view type) {
  return type == "FreeMotionAnimationLoop" || among(kSolvers, type) || among(kCorrections, type) || among(kConstraints, type) ||
         is_softrobots_constraint(type);
}

LagrangianParts build_free_motion_loop(SceneData& data, std::vector<std::string>& info, Simulation<double>& simulation,
                                       const std::vector<const GraphNode*>& solver_nodes, const LocateState& locate) {
  std::vector<Component*> components;
  collect(data.root(), components);
  Component* loop = nullptr;
  for (Component* c : components) {
    if (c->type() != "FreeMotionAnimationLoop") continue;
    if (c->node != &data.root()) throw make_error(c->where(), ": the animation loop must be in the root node (SOFA uses the root's)");
    loop = c;
  }
  if (!loop) {
    for (Component* c : components) {
      info.push_back(c->where() + ": not used: the scene has no FreeMotionAnimationLoop (SOFA's default loop does not "
                     "solve Lagrangian constraints)");
    }
    return {};
  }
  return LoopBuilder(data, info, simulation, solver_nodes, locate).build(*loop, components);
}

}  // namespace fastcorot::scene_detail
