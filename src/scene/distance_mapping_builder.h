// SOFA's DistanceMapping<Vec3, Vec1> in a scene: the Vec1 MechanicalObject of a mapped node made
// the extensions of a topology's edges, and the mapping's geometric stiffness added to the parent
// object. Internal to src/scene (visual_surface_builder.cpp's mapped states); design in
// docs/mechanical-graph.md ("Vec1 states").
#pragma once

#include "fastcorot/sim/simulation.h"
#include "scene_data.h"

namespace fastcorot::scene_detail {

// Whether a MechanicalObject's template names a one-coordinate state (Vec1d, Vec1f, Vec1).
inline bool is_vec1_template(std::string_view name) { return name == "Vec1d" || name == "Vec1f" || name == "Vec1"; }

// `state` (of mapped node `node`) as DistanceMapping `mapping` defines it from `object`'s points:
// fills `mapped` (a Vec1 state: coordinates 1, `through` the mapping, its constraint-force sink)
// and adds the geometric stiffness to the object's force fields (unless geometricStiffness is
// None). Throws fastcorot::Error for a state that is not Vec1, a Rigid3 parent, no topology or no
// edges, an edge outside the object, rest lengths not one per edge, an unknown geometricStiffness.
void build_distance_mapped_state(SceneData& data, GraphNode& node, Component& state, Component& mapping,
                                 SimulatedObject<double>& object, MappedState& mapped);

}  // namespace fastcorot::scene_detail
