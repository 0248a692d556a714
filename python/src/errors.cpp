// How fastcorot's errors reach Python. The library throws one type, fastcorot::Error, whose message
// names the file, line, object, attribute or element (the message the command line prints after
// "fastcorot: error: "). Python receives the same message as a ValueError, except where the message
// reports a file that does not exist (a FileNotFoundError), and a failure while stepping (a
// diverging state) is fastcorot.SimulationError, a RuntimeError.
#include "bindings.h"

#include "fastcorot/core/error.h"

namespace fastcorot::python {

void throw_file_not_found(const std::string& message) {
  PyErr_SetString(PyExc_FileNotFoundError, message.c_str());
  throw py::error_already_set();
}

void bind_errors(py::module_& m) {
  py::register_exception<StepFailure>(m, "SimulationError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr failure) {
    try {
      if (failure) std::rethrow_exception(failure);
    } catch (const Error& error) {
      const std::string message = error.what();
      // The mesh readers' words for an absent file (src/io/mesh_readers.cpp).
      const bool absent = message.find(": no such file") != std::string::npos;
      PyErr_SetString(absent ? PyExc_FileNotFoundError : PyExc_ValueError, message.c_str());
    }
  });
}

}  // namespace fastcorot::python
