// Turns a parsed SOFA scene into a Simulation: every node that holds an ODE solver becomes one
// simulated object made of the MechanicalObject, force fields, mass, constraints and loads in that
// node and below it (SOFA's solver scope), with SOFA's defaults and implicit links
// (docs/sofa-components.md). Unknown components, broken links, missing files and inconsistent sizes
// are errors naming the file and line; an unknown attribute of a known component is a warning (as
// SOFA warns), or an error with SceneOptions::strict.
#pragma once

#include "fastcorot/scene/scene_graph.h"
#include "fastcorot/sim/simulation.h"

#include <filesystem>
#include <string>
#include <vector>

namespace fastcorot {

struct SceneOptions {
  bool strict = false;  // warnings (unknown attributes) are errors
  // A scene with nothing to simulate (no solver with a state) is an empty simulation rather than
  // an error: SOFA runs such scenes, and a script's controllers may be all it does.
  bool allow_empty = false;
};

struct LoadedScene {
  Simulation<double> simulation;
  std::vector<std::string> info;      // one line per ignored component or node, for the user
  std::vector<std::string> warnings;  // one line per unknown attribute (ignored), for the user
  // For each simulated object (same order as simulation.objects), the MechanicalObject it was built
  // from, as its rank among all the scene's objects in document order (a node's objects, then its
  // child nodes' depth first). Front ends that keep the scene tree use it to find an object's state.
  std::vector<std::size_t> state_objects;
  // For each simulated object, how many MechanicalObjects it holds: 1, or more where one solver
  // integrates several objects as one system (their states one after the other, in document order).
  std::vector<std::size_t> state_counts;
  // Every simulated MechanicalObject, in the order of simulation.objects and, within a merged
  // object, of its states: its rank (as above), the simulated object that holds it, and its range
  // of points in that object's state.
  struct StatePart {
    std::size_t rank = 0;
    std::size_t object = 0;
    Index offset = 0;
    Index size = 0;
  };
  std::vector<StatePart> state_parts;
  // Under a FreeMotionAnimationLoop: the rank (as above) of each Lagrangian constraint, in the
  // order of the loop's constraints (FreeMotionAnimationLoop::constraints), and of the constraint
  // solver (-1 when SOFA's default one was added).
  std::vector<std::size_t> constraint_objects;
  long constraint_solver_object = -1;
};

LoadedScene build_scene(const SceneNode& root, const SceneOptions& options = {});

// The numbers of data `name` of object `object_index` of the scene (counted in document order: a
// node's objects, then its children's), as the scene builder reads them: links followed, files
// loaded, engines' and loaders' outputs computed. SofaPython3 gives such values as soon as the
// objects are added; this is how fastcorot's Sofa package reads them before init. Throws
// fastcorot::Error naming what fails.
std::vector<double> scene_data_value(const SceneNode& root, std::size_t object_index, const std::string& name);
LoadedScene load_scene_file(const std::filesystem::path& path, const SceneOptions& options = {});

}  // namespace fastcorot
