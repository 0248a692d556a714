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
// (a CollisionPipeline with MinProximityIntersection and the PenalityContactForceField response
// under the default animation loop; Point, Line and Triangle models on simulated objects, states
// mapped from them, or MechanicalObjects no solver moves; contacts between a body and an obstacle
// or within one body), adding a penalty force field to each object a contact can reach. Otherwise
// each collision component gets a warning saying why the scene's collisions are not simulated
// (with strict checking, an error). Models without a pipeline: one info line (SOFA makes no
// contact either). Throws fastcorot::Error for bad input in a component it builds (an element
// index outside its state, a negative distance or stiffness).
void build_collision_pipeline(SceneData& data, std::vector<std::string>& info, Simulation<double>& simulation,
                              const LocateState& locate);

}  // namespace fastcorot::scene_detail
