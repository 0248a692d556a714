// The running simulation behind fastcorot.Simulation: the scene the builder made, and a lock so
// that one step runs at a time whichever Python thread asks. simulation.cpp binds it; matrices.cpp
// and cli.cpp use it.
#pragma once

#include "bindings.h"

#include "fastcorot/scene/scene_builder.h"

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace fastcorot::python {

struct SimulationCore {
  LoadedScene scene;
  std::mutex stepping;  // one step at a time, whichever Python thread asks
  // Scenes replaced by rebuild() (a tree grown while running): kept for the arrays that view them.
  std::vector<std::unique_ptr<LoadedScene>> retired;
  std::size_t rebuilds = 0;  // how many times rebuild() replaced the scene

  explicit SimulationCore(LoadedScene loaded) : scene(std::move(loaded)) {}

  Simulation<double>& simulation() { return scene.simulation; }

  SimulatedObject<double>& object(std::size_t k) {
    if (k >= simulation().objects.size()) {
      throw py::index_error("object " + std::to_string(k) + " out of range (" +
                            std::to_string(simulation().objects.size()) + " objects)");
    }
    return simulation().objects[k];
  }

  MechanicalState<double>& state(std::size_t k) { return object(k).system.state; }
};

// Adds the matrix accessors (matrices.cpp) to the SimulationCore class.
void bind_matrices(py::class_<SimulationCore>& core);
// Adds the constraint stage's accessors (constraints.cpp).
void bind_constraints(py::class_<SimulationCore>& core);
// Adds the collision stage's accessors (contacts.cpp).
void bind_contacts(py::class_<SimulationCore>& core);
// Adds add_python_force_field (python_force_field.cpp).
void bind_python_force_fields(py::class_<SimulationCore>& core);

}  // namespace fastcorot::python
