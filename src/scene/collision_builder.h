// SOFA's collision components in a scene: the pipeline, MinProximityIntersection, the penalty
// response and the Point, Line and Triangle models, built into a ContactPipeline on the simulated
// objects (collision/contact_pipeline.h). Internal to src/scene (scene_builder.cpp); design in
// docs/collision.md.
#pragma once

#include "fastcorot/sim/simulation.h"
#include "lagrangian_builder.h"
#include "scene_data.h"

#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// Sets simulation.collisions when the scene's collision components are ones fastcorot simulates
// (a CollisionPipeline with its phases, MinProximityIntersection and the PenalityContactForceField
// response under the default animation loop; Point, Line and Triangle models on simulated objects,
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
