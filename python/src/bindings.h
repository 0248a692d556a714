// The pieces of the compiled part of the Python module (`fastcorot._core`), one file per concept:
// errors (how fastcorot::Error becomes a Python exception), arrays (checking numpy inputs), the
// force field on numpy arrays, the scene graph (component table, parsing, building) and the running
// simulation. The pure-Python layer (python/fastcorot/) builds the SofaPython3-like API on top.
#pragma once

#include "fastcorot/scene/scene_graph.h"

#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

namespace fastcorot::python {

namespace py = pybind11;

// A failure while stepping (a diverging state); Python sees fastcorot.SimulationError, a RuntimeError.
class StepFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Raises FileNotFoundError with `message` (pybind11 has no C++ type for it).
[[noreturn]] void throw_file_not_found(const std::string& message);

void bind_errors(py::module_& m);
void bind_force_field(py::module_& m);
void bind_scene(py::module_& m);
void bind_simulation(py::module_& m);
void bind_cli(py::module_& m);

// The scene tree the Python layer hands over: (name, {attribute: text}, [(type, {attribute: text},
// file, line), ...], [child trees], file, line). Throws TypeError when it is not of that shape.
SceneNode scene_node_from_tree(py::handle tree);

}  // namespace fastcorot::python
