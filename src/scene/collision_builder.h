// SOFA's collision components in a scene: the pipeline (CollisionPipeline, or a
// CompositeCollisionPipeline of SubCollisionPipelines), the intersection method, the contact manager
// and its response, the Point, Line, Triangle and Sphere models, built into ContactPipelines on the
// simulated objects (collision/contact_pipeline.h). Internal to src/scene (scene_builder.cpp);
// design in docs/collision.md.
#pragma once

#include "fastcorot/collision/contact_pipeline.h"
#include "fastcorot/sim/simulation.h"
#include "lagrangian_builder.h"
#include "scene_data.h"

#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// One pipeline: the intersection method, contact manager, phases and collision models among
// `components` (models in broad-phase order), a response between two simulated models placed at
// `pipeline_node`, the objects given the force fields or constraints its responses need. Throws
// NotSimulated (collision_model_reader.h) for what is not simulated yet, adding nothing then, and
// fastcorot::Error for bad input.
std::shared_ptr<ContactPipeline<double>> build_contact_pipeline(SceneData& data, Simulation<double>& simulation, const LocateState& locate,
                                                                const std::vector<const GraphNode*>& solver_nodes,
                                                                const GraphNode& pipeline_node, const std::vector<Component*>& components);

// Sets simulation.collisions when the scene's collision components are ones fastcorot simulates
// (a CollisionPipeline with its phases, or a CompositeCollisionPipeline, an intersection method and
// a response docs/collision.md lists; Point, Line, Triangle and Sphere models on simulated objects,
// states mapped from them, or MechanicalObjects nothing moves; each model pair's response placed,
// as SOFA places it, under the ODE solver of the body it acts on, so that it is implicit there),
// adding a penalty force field to each object a contact can reach. Otherwise
// each collision component gets a warning saying why the scene's collisions are not simulated
// (with strict checking, an error). Models without a pipeline: one info line (SOFA makes no
// contact either). Throws fastcorot::Error for bad input in a component it builds (an element
// index outside its state, a negative distance or stiffness).
// `solver_nodes[o]` is the node of object o's ODE solver.
void build_collision_pipeline(SceneData& data, std::vector<std::string>& info, Simulation<double>& simulation,
                              const LocateState& locate, const std::vector<const GraphNode*>& solver_nodes);

}  // namespace fastcorot::scene_detail
