// One collision pipeline built from its components: the intersection method's settings, the contact
// manager's response for the model pairs, the models, and the response's force fields or constraints
// on the objects (collision_builder.h).
#include "collision_builder.h"
#include "collision_model_reader.h"
#include "contact_manager_rules.h"

#include "fastcorot/collision/contact_pipeline.h"
#include "fastcorot/collision/explicit_contact_forces.h"
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/core/error.h"

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <set>

namespace fastcorot::scene_detail {

namespace {

class CollisionBuilder {
 public:
  CollisionBuilder(SceneData& data, Simulation<double>& simulation, const LocateState& locate,
                   const std::vector<const GraphNode*>& solver_nodes, const GraphNode& pipeline_node)
      : data_(data), simulation_(simulation), locate_(locate), solver_nodes_(solver_nodes), pipeline_node_(pipeline_node) {
    loop_ = dynamic_cast<FreeMotionAnimationLoop<double>*>(simulation.constraints.get());
  }

  std::shared_ptr<ContactPipeline<double>> build(const std::vector<Component*>& components) {
    Component* intersection = nullptr;
    Component* response = nullptr;
    for (Component* c : components) {
      const std::string_view type = c->type();
      if (type == "MinProximityIntersection" || type == "NewProximityIntersection" || type == "LocalMinDistance" ||
          type == "DiscreteIntersection") {
        intersection = intersection ? intersection : c;
      }
      if (type == "CollisionResponse" || type == "RuleBasedContactManager") response = response ? response : c;
      if ((type == "CollisionPipeline" || type == "DefaultPipeline") && c->has("depth") && data_.real(*c, "depth", 6.0) != 6.0) {
        data_.warn(c->where() + ": depth " + data_.text(*c, "depth", "6") + " is not followed: fastcorot's trees have SOFA's default "
                   "depth 6, which decides only the order of contacts that tie exactly (the first of equal ones is kept)");
      }
      if (type == "BruteForceBroadPhase" && c->has("box")) throw NotSimulated{c->where() + ": its box (a region of interest) is not simulated yet"};
    }
    if (!intersection) throw NotSimulated{"the scene has no intersection method (MinProximityIntersection, NewProximityIntersection, LocalMinDistance or DiscreteIntersection)"};
    const typename ContactPipeline<double>::Parameters p = intersection_settings(*intersection);
    method_ = p.method;
    const ContactManagerRules manager(data_, *response);
    reader_.emplace(data_, simulation_, locate_, method_);
    std::vector<CollisionModel<double>> models;
    std::vector<ContactModelIdentity> identities;
    std::vector<const GraphNode*> nodes;
    for (Component* c : components) {
      const std::string_view type = c->type();
      if (type != "TriangleCollisionModel" && type != "LineCollisionModel" && type != "PointCollisionModel" && type != "SphereCollisionModel") {
        continue;
      }
      if (!data_.boolean(*c, "active", true)) continue;
      models.push_back(reader_->model(*c));
      identities.push_back({c->sofa_name(), models.back().groups, data_.text(*c, "contactResponse", "")});
      nodes.push_back(c->node);
      // SOFA's mpoints / m_pointModels: the node's first PointCollisionModel.
      auto& added = models.back();
      added.node_point_model = added.kind == CollisionElements::points &&
                               std::none_of(models.begin(), models.end() - 1, [&](const CollisionModel<double>& other) {
                                 return other.node == added.node && other.kind == CollisionElements::points;
                               });
      if (models.back().kind != CollisionElements::points && models.back().size() == 0) {
        data_.warn(c->where() + ": its topology gives it no elements: it takes part in no contact");
      }
    }
    for (const auto& model : models) {
      if (!model.points->is_still() && !simulation_.objects[model.points->object()].topology_scripts.empty()) {
        throw NotSimulated{model.where + " is on " + simulation_.objects[model.points->object()].path +
                           ", whose topology a TopologicalChangeProcessor changes: contacts on a changing topology are not simulated yet"};
      }
    }
    const auto pairs = ContactPipeline<double>::rule_pairs(models, p);
    Responses responses;
    responses.kind.assign(pairs.size(), Response::none);
    responses.explicit_pairs.assign(pairs.size(), 0);
    responses.penalties.resize(simulation_.objects.size());
    responses.sticks.resize(simulation_.objects.size());
    responses.explicit_forces.resize(simulation_.objects.size());
    responses.constraints.resize(pairs.size());
    responses.stick_constraints.resize(pairs.size());
    // Each pair's response as SOFA's contact factory reads it (the name before '?', its parameters
    // after); with no pair, the manager's is still checked.
    std::vector<std::string> chosen;
    for (const auto& pair : pairs) chosen.push_back(manager.response(identities[pair.first], identities[pair.second]));
    if (pairs.empty()) response_kind(*response, manager.default_response());
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      responses.kind[k] = response_kind(*response, chosen[k]);
      const bool sticking = responses.kind[k] == Response::stick_springs || responses.kind[k] == Response::stick_constraint;
      for (const std::size_t m : {pairs[k].first, pairs[k].second}) {
        if (sticking && models[m].kind == CollisionElements::spheres && models[m].points->is_rigid()) {
          throw NotSimulated{models[m].where + ": SOFA has no " + name_of(chosen[k]) + " response for rigid spheres"};
        }
      }
    }
    const auto empty_mesh = [&](std::size_t o) {
      return std::make_shared<const TetMesh>(simulation_.objects[o].system.size(), std::vector<Tetrahedron>{});
    };
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const Response kind = responses.kind[k];
      if (kind != Response::penalty && kind != Response::stick_springs) continue;
      responses.explicit_pairs[k] = explicit_placement(models, nodes, pairs[k]);
      for (const std::size_t m : {pairs[k].first, pairs[k].second}) {
        if (models[m].points->is_still()) continue;
        const std::size_t o = models[m].points->object();
        if (responses.explicit_pairs[k]) {
          if (!responses.explicit_forces[o]) responses.explicit_forces[o] = std::make_shared<ExplicitContactForces<double>>(empty_mesh(o));
        } else if (kind == Response::stick_springs) {
          if (!responses.sticks[o]) responses.sticks[o] = std::make_shared<StickContactForceField<double>>(empty_mesh(o));
        } else if (!responses.penalties[o]) {
          responses.penalties[o] = std::make_shared<PenaltyContactForceField<double>>(empty_mesh(o));
        }
      }
    }
    const auto placed = lagrangian_constraints(*response, models, nodes, pairs, chosen, responses);
    std::shared_ptr<ContactPipeline<double>> pipeline;
    try {
      pipeline = std::make_shared<ContactPipeline<double>>(p, std::move(models), responses);
    } catch (const Error& error) {
      throw NotSimulated{error.what()};
    }
    for (std::size_t o = 0; o < simulation_.objects.size(); ++o) {
      for (const std::shared_ptr<ForceField<double>>& field : {std::shared_ptr<ForceField<double>>(responses.penalties[o]),
                                                               std::shared_ptr<ForceField<double>>(responses.sticks[o]),
                                                               std::shared_ptr<ForceField<double>>(responses.explicit_forces[o])}) {
        if (!field) continue;
        simulation_.objects[o].system.force_fields.push_back(field);
        simulation_.objects[o].force_field_drawing.push_back({});
      }
    }
    for (const std::size_t k : placed) {
      if (responses.constraints[k]) loop_->constraints.push_back(responses.constraints[k]);
      if (responses.stick_constraints[k]) loop_->constraints.push_back(responses.stick_constraints[k]);
    }
    return pipeline;
  }

 private:
  using Response = typename ContactPipeline<double>::Response;
  using Responses = typename ContactPipeline<double>::Responses;

  static std::string name_of(const std::string& response) { return response.substr(0, response.find('?')); }

  // What a response (SOFA's "Name?parameters") is here; throws NotSimulated for a response
  // fastcorot does not have or one the animation loop cannot solve. Its parameters are read where
  // they are used (Lagrangian responses), else warned unused (once per response).
  Response response_kind(Component& manager, const std::string& response) {
    const std::string name = name_of(response);
    const bool lagrangian = name == "FrictionContactConstraint" || name == "AugmentedLagrangianResponseConstraint" ||
                            name == "StickContactConstraint";
    if (!lagrangian && name != "StickContactForceField" && name != "PenalityContactForceField") {
      throw NotSimulated{"the response " + (name.empty() ? std::string("'' (none)") : name) +
                         " is not simulated yet (PenalityContactForceField, StickContactForceField, FrictionContactConstraint, "
                         "AugmentedLagrangianResponseConstraint and StickContactConstraint are)"};
    }
    if (lagrangian && !loop_) {
      throw NotSimulated{manager.where() + ": " + name + " makes Lagrangian constraints, which only a "
                         "FreeMotionAnimationLoop solves (SOFA's default loop leaves them unsolved)"};
    }
    if (!lagrangian && loop_) {
      throw NotSimulated{name + " contacts under FreeMotionAnimationLoop are not simulated (SOFA applies them a step late)"};
    }
    if ((!lagrangian || name == "StickContactConstraint") && response.find('?') != std::string::npos && warned_.insert(response).second) {
      data_.warn(manager.where() + ": parameters '" + response.substr(response.find('?') + 1) + "' are not read by " + name + ": ignored");
    }
    return name == "PenalityContactForceField"    ? Response::penalty
           : name == "StickContactForceField"    ? Response::stick_springs
           : name == "StickContactConstraint"    ? Response::stick_constraint
                                                 : Response::friction;
  }

  // The intersection method's settings, SOFA's defaults.
  typename ContactPipeline<double>::Parameters intersection_settings(Component& c) {
    typename ContactPipeline<double>::Parameters p;
    const std::string_view type = c.type();
    p.method = type == "NewProximityIntersection" ? IntersectionMethod::new_proximity
               : type == "LocalMinDistance"       ? IntersectionMethod::local_min_distance
               : type == "DiscreteIntersection"   ? IntersectionMethod::discrete
                                                  : IntersectionMethod::min_proximity;
    if (p.method == IntersectionMethod::discrete) return p;
    p.alarm_distance = data_.real(c, "alarmDistance", 1.0);
    p.contact_distance = data_.real(c, "contactDistance", 0.5);
    if (!(p.alarm_distance >= 0) || !(p.contact_distance >= 0)) {
      throw error_at(c.where(), make_error("alarmDistance and contactDistance must be ≥ 0"));
    }
    if (p.alarm_distance < p.contact_distance) {
      data_.warn(c.where() + ": alarmDistance " + std::to_string(p.alarm_distance) + " is below contactDistance " +
                 std::to_string(p.contact_distance) + ": contacts are found only once the bodies are already closer than the distance kept");
    }
    p.use_line_line = data_.boolean(c, "useLineLine", p.method != IntersectionMethod::new_proximity);
    if (p.method == IntersectionMethod::new_proximity) return p;
    p.use_point_point = data_.boolean(c, "usePointPoint", true);
    p.use_line_point = data_.boolean(c, "useLinePoint", true);
    p.use_sphere_triangle = data_.boolean(c, "useSphereTriangle", true);
    if (p.method == IntersectionMethod::min_proximity) {
      p.use_surface_normals = data_.boolean(c, "useSurfaceNormals", false);
      return p;
    }
    auto& f = p.local_min_distance;
    f.filter_intersection = data_.boolean(c, "filterIntersection", true);
    f.angle_cone = data_.real(c, "angleCone", 0.0);
    f.cone_factor = data_.real(c, "coneFactor", 0.5);
    f.use_lmd_filters = data_.boolean(c, "useLMDFilters", false);
    return p;
  }

  // SOFA's Lagrangian contact responses: one constraint per model pair (FrictionContactConstraint's
  // or AugmentedLagrangianResponseConstraint's UnilateralLagrangianConstraint, or
  // StickContactConstraint's bilateral one) into `responses`. Returns the pairs in the order their
  // rows go after the scene's own Lagrangian constraints: as SOFA's graph places the responses (the
  // simulated model's node against a still one, else the pipeline's node: nodes in depth-first
  // order, pairs in broad-phase order within a node).
  std::vector<std::size_t> lagrangian_constraints(Component& manager, const std::vector<CollisionModel<double>>& models,
                                                  const std::vector<const GraphNode*>& nodes,
                                                  const std::vector<typename ContactPipeline<double>::ModelPair>& pairs,
                                                  const std::vector<std::string>& chosen, Responses& responses) {
    if (!loop_) return {};
    std::set<std::size_t> corrected;
    for (const auto& correction : loop_->corrections) corrected.insert(correction->object());
    std::map<const GraphNode*, int> depth_first;
    number_nodes(data_.root(), depth_first);
    std::map<std::string, typename UnilateralLagrangianConstraint<double>::Parameters> parameters;  // by response
    std::vector<std::pair<int, std::size_t>> placed;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const Response kind = responses.kind[k];
      if (kind != Response::friction && kind != Response::stick_constraint) continue;
      const auto& a = models[pairs[k].first];
      const auto& b = models[pairs[k].second];
      const std::string name = name_of(chosen[k]);
      if (kind == Response::friction && (a.contact_stiffness == 0 || b.contact_stiffness == 0)) {
        data_.warn(manager.where() + ": " + a.where + " and " + b.where + ": a contactStiffness of 0 disables their " + name +
                   " response, as in SOFA (no contacts between them)");
        responses.kind[k] = Response::none;
        continue;
      }
      const auto uncorrected = [&](const CollisionModel<double>& side) {
        return side.points->is_still() || !corrected.count(side.points->object());
      };
      if (uncorrected(a) && uncorrected(b)) {
        // Neither side's compliance reaches W, and no correction moves either: SOFA builds the rows
        // and nothing comes of them (STLIB's RigidObject has no correction).
        data_.warn(manager.where() + ": " + a.where + " and " + b.where + ": no constraint correction on either side, so their " +
                   name + " contacts move neither, as in SOFA (add an UncoupledConstraintCorrection to a moving body)");
        responses.kind[k] = Response::none;
        continue;
      }
      for (const auto* side : {&a, &b}) {
        if (side->points->is_still() || corrected.count(side->points->object())) continue;
        // Only the other side's compliance reaches W and only it is corrected: the uncorrected body
        // moves on as if nothing touched it, as in SOFA.
        loop_->uncorrected.push_back(side->points->object());
        data_.warn(side->where + ": its object " + simulation_.objects[side->points->object()].path +
                   " has no constraint correction: its " + name + " contacts push the other side only, as in SOFA (add a "
                   "LinearSolverConstraintCorrection or an UncoupledConstraintCorrection for both to respond)");
      }
      const std::string where = manager.where() + ": contacts of " + a.where + " and " + b.where;
      if (kind == Response::stick_constraint) {
        responses.stick_constraints[k] = std::make_shared<StickContactConstraint<double>>(where);
      } else {
        auto found = parameters.find(chosen[k]);
        if (found == parameters.end()) found = parameters.emplace(chosen[k], response_parameters(manager, chosen[k])).first;
        responses.constraints[k] = std::make_shared<UnilateralLagrangianConstraint<double>>(where, found->second);
      }
      const GraphNode* node = !a.simulated ? nodes[pairs[k].second] : !b.simulated ? nodes[pairs[k].first] : &pipeline_node_;
      placed.emplace_back(depth_first.at(node), k);
    }
    std::stable_sort(placed.begin(), placed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<std::size_t> order;
    for (const auto& [depth, k] : placed) order.push_back(k);
    return order;
  }

  // A Lagrangian response's parameters (what follows '?': the manager's responseParams, or a
  // model's or a rule's own): "name=value" pairs joined by '&' or '?' (mu, tol; epsilon for
  // AugmentedLagrangianResponseConstraint, whose mu is 0 by default); other names warned.
  typename UnilateralLagrangianConstraint<double>::Parameters response_parameters(Component& manager, const std::string& response) {
    typename UnilateralLagrangianConstraint<double>::Parameters parameters;
    const std::string name = name_of(response);
    if (name == "AugmentedLagrangianResponseConstraint") {
      parameters.augmented = true;
      parameters.mu = 0;  // its own default, where FrictionContactConstraint's is 0.8
    }
    const std::string text = response.find('?') == std::string::npos ? "" : response.substr(response.find('?') + 1);
    std::size_t start = 0;
    while (start < text.size()) {
      const std::size_t end = std::min(text.find_first_of("&?", start), text.size());
      const std::string item = text.substr(start, end - start);
      start = end + 1;
      if (item.empty()) continue;
      const std::size_t equal = item.find('=');
      const std::string key = item.substr(0, equal);
      double value = 0;
      try {
        std::size_t used = 0;
        if (equal == std::string::npos) throw std::invalid_argument("no value");
        value = std::stod(item.substr(equal + 1), &used);
        if (used != item.size() - equal - 1) throw std::invalid_argument("trailing text");
      } catch (const std::exception&) {
        throw error_at(manager.where(), make_error("responseParams: '", item, "' is not name=number"));
      }
      if (key == "mu") {
        parameters.mu = value;
      } else if (key == "tol") {
        parameters.tolerance = value;
      } else if (key == "epsilon" && parameters.augmented) {
        parameters.epsilon = value;
      } else {
        data_.warn(manager.where() + ": responseParams: '" + key + "' is not a parameter of " + name + " (mu, tol" +
                   (parameters.augmented ? ", epsilon" : "") + "): ignored");
      }
    }
    if (!(parameters.mu >= 0) || !(parameters.tolerance >= 0) || !(parameters.epsilon >= 0)) {
      throw error_at(manager.where(), make_error("responseParams: mu, tol and epsilon must be ≥ 0"));
    }
    return parameters;
  }

  static void number_nodes(const GraphNode& node, std::map<const GraphNode*, int>& order) {
    order.emplace(&node, static_cast<int>(order.size()));
    for (const auto& child : node.children) number_nodes(*child, order);
  }

  // SOFA's placement of a model pair's response (SubCollisionPipeline::computeCollisionResponse): in
  // the node of the simulated model when the other is not simulated, else in the pipeline's node.
  // Its penalty is implicit in the body's step when that node is at or below the body's ODE solver
  // (true returned: false); when it is below none of the sides' solvers SOFA evaluates it once per
  // step, explicitly (true). Below one side's solver only: not simulated.
  bool explicit_placement(const std::vector<CollisionModel<double>>& models, const std::vector<const GraphNode*>& nodes,
                          const typename ContactPipeline<double>::ModelPair& pair) const {
    const auto& a = models[pair.first];
    const auto& b = models[pair.second];
    const GraphNode* node = !a.simulated ? nodes[pair.second] : !b.simulated ? nodes[pair.first] : &pipeline_node_;
    int below_count = 0, sides = 0;
    for (const auto* side : {&a, &b}) {
      if (side->points->is_still()) continue;
      ++sides;
      const std::size_t o = side->points->object();
      const GraphNode* solver = o < solver_nodes_.size() ? solver_nodes_[o] : nullptr;
      bool below = false;
      for (const GraphNode* n = node; n && !below; n = n->parent) below = n == solver;
      below_count += below;
      if (solver) {
        for (const auto& c : solver->components) {
          if (c->type() == "PETScLinearSolver") throw NotSimulated{simulation_.objects[o].path + " is solved by PETScLinearSolver, whose matrix pattern does not follow contacts yet"};
        }
      }
    }
    if (below_count == sides) {
      const bool two_objects = !a.points->is_still() && !b.points->is_still() && a.points->object() != b.points->object();
      if (!two_objects) return false;
    }
    if (below_count != 0 && below_count != sides) {
      throw NotSimulated{a.where + " and " + b.where + ": SOFA places their penalty response in node " + node->path +
                         ", under the ODE solver of one of their bodies only: not simulated"};
    }
    return true;
  }

  SceneData& data_;
  Simulation<double>& simulation_;
  const LocateState& locate_;
  const std::vector<const GraphNode*>& solver_nodes_;
  const GraphNode& pipeline_node_;
  FreeMotionAnimationLoop<double>* loop_ = nullptr;
  IntersectionMethod method_ = IntersectionMethod::min_proximity;
  std::set<std::string> warned_;  // responses whose unread parameters were warned
  std::optional<CollisionModelReader> reader_;
};

}  // namespace

std::shared_ptr<ContactPipeline<double>> build_contact_pipeline(SceneData& data, Simulation<double>& simulation, const LocateState& locate,
                                                                const std::vector<const GraphNode*>& solver_nodes,
                                                                const GraphNode& pipeline_node, const std::vector<Component*>& components) {
  return CollisionBuilder(data, simulation, locate, solver_nodes, pipeline_node).build(components);
}

}  // namespace fastcorot::scene_detail
