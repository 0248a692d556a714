// Which collision pipeline a scene has: SOFA's CollisionPipeline over every collision model, or a
// CompositeCollisionPipeline of SubCollisionPipelines, each over the models it links (each built by
// collision_builder.cpp); what is not simulated warned per component. Design: docs/collision.md.
#include "collision_builder.h"
#include "collision_model_reader.h"

#include "fastcorot/collision/composite_collision_pipeline.h"
#include "fastcorot/collision/contact_pipeline.h"
#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/core/error.h"

#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

namespace {

void collect(GraphNode& node, std::vector<Component*>& spec, std::vector<Component*>& other, bool& free_motion) {
  for (const auto& c : node.components) {
    if (c->type() == "FreeMotionAnimationLoop") free_motion = true;
    if (c->spec && c->spec->category == "collision") {
      spec.push_back(c.get());
    } else if (!c->spec && is_collision_component(c->type())) {
      other.push_back(c.get());
    }
  }
  for (const auto& child : node.children) collect(*child, spec, other, free_motion);
}

// The words of a link list ("@a @b/c", across lines).
std::vector<std::string> link_words(const std::string& text) {
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

// What a simulation's force fields and Lagrangian constraints held before a builder ran, to undo
// what it added when a later part of the scene's collisions is not simulated.
struct CollisionUndo {
  std::vector<std::size_t> fields;
  std::size_t constraints = 0;

  explicit CollisionUndo(const Simulation<double>& simulation) {
    for (const auto& object : simulation.objects) fields.push_back(object.system.force_fields.size());
    if (const auto* loop = dynamic_cast<const FreeMotionAnimationLoop<double>*>(simulation.constraints.get())) {
      constraints = loop->constraints.size();
    }
  }
  void undo(Simulation<double>& simulation) const {
    for (std::size_t o = 0; o < fields.size(); ++o) {
      simulation.objects[o].system.force_fields.resize(fields[o]);
      simulation.objects[o].force_field_drawing.resize(fields[o]);
    }
    if (auto* loop = dynamic_cast<FreeMotionAnimationLoop<double>*>(simulation.constraints.get())) loop->constraints.resize(constraints);
  }
};

// SOFA's CompositeCollisionPipeline: each SubCollisionPipeline it links (in order) with its own
// linked models, intersection method, phases and contact manager, built as a pipeline of its own
// placed at the sub-pipeline's node. A sub-pipeline missing a link does nothing (warned, as SOFA);
// models no sub-pipeline lists take part in nothing (warned, as SOFA).
std::shared_ptr<CollisionStage<double>> composite_pipeline(SceneData& data, Simulation<double>& simulation, const LocateState& locate,
                                                           const std::vector<const GraphNode*>& solver_nodes, Component& composite,
                                                           const std::vector<Component*>& components) {
  const auto links = link_words(data.text(composite, "subCollisionPipelines", ""));
  if (links.empty()) {
    data.warn(composite.where() + ": no SubCollisionPipeline in subCollisionPipelines: nothing is done, as in SOFA");
    return nullptr;
  }
  std::set<const Component*> listed;
  std::vector<std::pair<Component*, std::vector<Component*>>> subs;
  for (const std::string& link : links) {
    Component& sub = data.resolve_object(*composite.node, link, composite);
    if (sub.type() != "SubCollisionPipeline") {
      throw error_at(composite.where(), make_error("subCollisionPipelines: ", link, " is a ", sub.type(), ", not a SubCollisionPipeline"));
    }
    std::vector<Component*> parts;
    std::string missing;
    for (const char* role : {"broadPhaseDetection", "narrowPhaseDetection", "intersectionMethod", "contactManager"}) {
      const std::string text = data.text(sub, role, "");
      if (text.empty()) {
        missing += (missing.empty() ? "" : ", ") + std::string(role);
        continue;
      }
      parts.push_back(&data.resolve_object(*sub.node, text, sub));
    }
    const auto models = link_words(data.text(sub, "collisionModels", ""));
    if (models.empty()) missing += (missing.empty() ? "" : ", ") + std::string("collisionModels");
    for (const std::string& model : models) {
      Component& m = data.resolve_object(*sub.node, model, sub);
      listed.insert(&m);
      parts.push_back(&m);
    }
    if (!missing.empty()) {
      data.warn(sub.where() + ": no " + missing + ": this sub-pipeline does nothing, as in SOFA");
      continue;
    }
    if (sub.has("depth") && data.real(sub, "depth", 6.0) != 6.0) {
      data.warn(sub.where() + ": depth " + data.text(sub, "depth", "6") + " is not followed: fastcorot's trees have SOFA's default "
                "depth 6, which decides only the order of contacts that tie exactly (the first of equal ones is kept)");
    }
    subs.emplace_back(&sub, std::move(parts));
  }
  for (const Component* c : components) {
    const std::string_view type = c->type();
    const bool model = type == "TriangleCollisionModel" || type == "LineCollisionModel" || type == "PointCollisionModel" ||
                       type == "SphereCollisionModel";
    if (model && !listed.count(c)) data.warn(c->where() + " is in no SubCollisionPipeline of " + composite.where() + ": it collides with nothing, as in SOFA");
  }
  std::vector<std::shared_ptr<CollisionStage<double>>> stages;
  for (auto& [sub, parts] : subs) {
    stages.push_back(build_contact_pipeline(data, simulation, locate, solver_nodes, *sub->node, parts));
  }
  if (stages.empty()) return nullptr;
  return std::make_shared<CompositeCollisionPipeline<double>>(std::move(stages));
}

}  // namespace

void build_collision_pipeline(SceneData& data, std::vector<std::string>& info, Simulation<double>& simulation,
                              const LocateState& locate, const std::vector<const GraphNode*>& solver_nodes) {
  std::vector<Component*> components, others;
  bool free_motion = false;
  collect(data.root(), components, others, free_motion);
  if (components.empty() && others.empty()) return;
  Component* pipeline_component = nullptr;
  Component* composite = nullptr;
  for (Component* c : components) {
    if ((c->type() == "CollisionPipeline") && !pipeline_component) pipeline_component = c;
    if (c->type() == "CompositeCollisionPipeline" && !composite) composite = c;
  }
  std::string reason;
  if (!others.empty()) {
    reason = std::string(others.front()->type()) + " is not simulated yet";
  } else if (composite && pipeline_component) {
    reason = "the scene has both " + pipeline_component->where() + " and " + composite->where() + ": one pipeline, please";
  } else if (!pipeline_component && !composite) {
    info.push_back(components.front()->where() + ": collision models without a CollisionPipeline: no contacts, as in SOFA");
    return;
  }
  if (reason.empty() && composite) {
    const CollisionUndo before(simulation);
    try {
      simulation.collisions = composite_pipeline(data, simulation, locate, solver_nodes, *composite, components);
      return;
    } catch (const NotSimulated& why) {
      before.undo(simulation);
      reason = why.reason;
    }
  }
  if (reason.empty() && pipeline_component) {
    // SOFA's pipeline does nothing without its phases and a contact manager with a response.
    bool broad = false, narrow = false, manager = false;
    for (Component* c : components) {
      const std::string_view type = c->type();
      broad = broad || type == "BruteForceBroadPhase" || (type == "BVHNarrowPhase" && c->object->type == "BruteForceDetection");
      narrow = narrow || type == "BVHNarrowPhase";
      manager = manager || ((type == "CollisionResponse" || type == "RuleBasedContactManager") && c->has("response"));
    }
    if (!broad || !narrow || !manager) {
      data.warn(pipeline_component->where() + ": no " + std::string(!broad ? "broad phase" : !narrow ? "narrow phase" : "CollisionResponse with a response") +
                ": SOFA's pipeline makes no contact without it, nor does fastcorot's");
      return;
    }
  }
  if (reason.empty()) {
    try {
      simulation.collisions = build_contact_pipeline(data, simulation, locate, solver_nodes, *pipeline_component->node, components);
      return;
    } catch (const NotSimulated& why) {
      reason = why.reason;
    }
  }
  for (Component* c : components) {
    data.warn(c->where() + " ignored: collisions and contacts are not simulated by fastcorot here: " + reason);
  }
}

}  // namespace fastcorot::scene_detail
