// fastcorot._core: the compiled part of the Python module; `import fastcorot` re-exports it with
// the scene and simulation classes of python/fastcorot/.
#include "bindings.h"

PYBIND11_MODULE(_core, m) {
  m.doc() = "fastcorot's compiled core: the force field on numpy arrays, the scene table and the simulation.";
  fastcorot::python::bind_errors(m);
  fastcorot::python::bind_force_field(m);
  fastcorot::python::bind_scene(m);
  fastcorot::python::bind_simulation(m);
  fastcorot::python::bind_cli(m);
}
