// Turns a parsed SOFA scene into a Simulation: every node that holds an ODE solver becomes one
// simulated object made of the MechanicalObject, force fields, mass, constraints and loads in that
// node and below it (SOFA's solver scope), with SOFA's defaults and implicit links
// (docs/sofa-components.md). Unknown components and attributes, broken links, missing files and
// inconsistent sizes are errors naming the file and line.
#pragma once

#include "fastcorot/scene/scene_graph.h"
#include "fastcorot/sim/simulation.h"

#include <filesystem>
#include <string>
#include <vector>

namespace fastcorot {

struct LoadedScene {
  Simulation<double> simulation;
  std::vector<std::string> info;  // one line per ignored component or node, for the user
};

LoadedScene build_scene(const SceneNode& root);
LoadedScene load_scene_file(const std::filesystem::path& path);

}  // namespace fastcorot
