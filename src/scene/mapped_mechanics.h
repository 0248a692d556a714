// Mechanics in mapped nodes (SOFA's mechanical mappings): an object built for the MechanicalObject
// of a mapped child node, folded into the simulated object above it. Internal to src/scene
// (scene_builder.cpp); design in docs/mechanical-graph.md.
#pragma once

#include "fastcorot/mapping/point_mapping.h"
#include "fastcorot/mapping/rigid_points.h"
#include "fastcorot/sim/simulation.h"

#include <string>

namespace fastcorot::scene_detail {

// Makes `child` (built on the mapped state y = J x of `parent`'s points) act on `parent`: its force
// fields through Jᵀ (MappedForceField), its mass as Jᵀ M J (weighing Jᵀ m g), its constant loads as
// Jᵀ f; its visual models and mapped states follow the chain. `where` names the mapped node in
// errors. Throws fastcorot::Error for what a mapped node cannot hold here: projective constraints,
// scripted topological changes.
void fold_mapped_object(SimulatedObject<double>& child, const PointMapping<double>& map, SimulatedObject<double>& parent,
                        const std::string& where);

// The same for a mapped node under a RigidMapping (`points` carried by the parent's rigids): its
// force fields act through the RigidMapping's Jᵀ; visual models and mapped states below it follow
// when each of their points lies on one rigid. Throws fastcorot::Error for a mass or constant
// load on the carried points (not folded yet), projective constraints, scripted changes.
void fold_rigid_mapped_object(SimulatedObject<double>& child, const RigidPoints<double>& points, SimulatedObject<double>& parent,
                              const std::string& where);

}  // namespace fastcorot::scene_detail
