// The visual models of SOFA scenes on simulated objects: OglModel (and its kin) in a mapped child
// node, its surface (a loader or a file), colour and material, and its mapping onto the object
// (BarycentricMapping, IdentityMapping, SubsetMapping). Internal to src/scene (scene_builder.cpp).
#pragma once

#include "fastcorot/sim/simulation.h"
#include "fastcorot/sim/visual_surface.h"
#include "scene_data.h"

#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// SOFA's RGBAColor syntax: "r g b [a]", "#rgb", "#rgba", "#rrggbb", "#rrggbbaa", or one of the
// names SOFA knows. Throws fastcorot::Error naming `attribute` for what SOFA would refuse, and
// components outside [0, 1].
Rgba parse_color(const std::string& attribute, const std::string& text);

// Adds the visual models of mapped node `node` (a child of the object's nodes) to `object`, each
// with its mapping; models with nothing to draw or no mapping drawn here get an info line. Throws
// fastcorot::Error naming the model for a bad surface, colour or mapping.
void add_visual_surfaces(SceneData& data, std::vector<std::string>& info, GraphNode& node,
                         SimulatedObject<double>& object);

// Adds the MechanicalObjects of mapped node `node` to `object`'s mapped states, each with the mapping
// whose output it is (one that names none outputs to the node's first state); a state without one
// gets an info line. Throws fastcorot::Error naming the state for a bad mapping.
void add_mapped_states(SceneData& data, std::vector<std::string>& info, GraphNode& node,
                       SimulatedObject<double>& object);

}  // namespace fastcorot::scene_detail
