// `python3 -m fastcorot ...`: the fastcorot command line run from the Python module, so that a
// Python scene script (SofaPython3's createScene(root)) is a scene like a .scn file. The loader
// given by python/fastcorot/__main__.py builds the script's scene into a SimulationCore and calls
// its controllers around each step; the command line runs with the GIL released and takes it back
// for each call into Python.
#include "bindings.h"
#include "simulation_core.h"

#include "cli_main.h"
#include "scene_source.h"

#include "fastcorot/core/error.h"

#include <pybind11/stl.h>

namespace fastcorot::python {

namespace {

// The text of the Python exception being handled (the loader raises one-line messages).
std::string message_of(py::error_already_set& error) { return py::str(error.value()).cast<std::string>(); }

// A script's scene, as the Python ScriptRun object (Sofa/_script.py) holds it.
class PythonScript final : public cli::SceneSource {
 public:
  explicit PythonScript(py::object run) : run_(std::move(run)) { fetch_core(); }
  ~PythonScript() override {
    py::gil_scoped_acquire gil;
    run_ = py::object();
  }

  LoadedScene& scene() override { return core_->scene; }
  LoadedScene& reload() override {
    call("reload");
    py::gil_scoped_acquire gil;
    fetch_core();
    return core_->scene;
  }
  void begin_step() override { call("begin_step"); }
  void end_step() override { call("end_step"); }
  void key_pressed(char key) override { call("key_pressed", std::string(1, key)); }
  bool take_rebuilt() override {
    py::gil_scoped_acquire gil;
    fetch_core();
    const bool rebuilt = core_->rebuilds != seen_rebuilds_;
    seen_rebuilds_ = core_->rebuilds;
    return rebuilt;
  }
  bool has_controllers() const override {
    py::gil_scoped_acquire gil;
    return run_.attr("has_controllers").cast<bool>();
  }

 private:
  void fetch_core() {
    SimulationCore* core = run_.attr("core").cast<SimulationCore*>();
    if (core != core_) seen_rebuilds_ = core->rebuilds;  // a reload: a new scene, not one rebuilt
    core_ = core;
  }

  template <class... Arguments>
  void call(const char* method, const Arguments&... arguments) {
    py::gil_scoped_acquire gil;
    try {
      run_.attr(method)(arguments...);
    } catch (py::error_already_set& error) {
      throw Error(message_of(error));
    }
  }

  py::object run_;
  SimulationCore* core_ = nullptr;
  std::size_t seen_rebuilds_ = 0;
};

int cli_main(const std::vector<std::string>& arguments, py::object loader) {
  cli::set_script_loader([loader](const std::string& script, bool strict) -> std::unique_ptr<cli::SceneSource> {
    py::gil_scoped_acquire gil;
    try {
      return std::make_unique<PythonScript>(loader(script, strict));
    } catch (py::error_already_set& error) {
      throw Error(message_of(error));
    }
  });
  std::vector<std::string> copies = arguments;
  std::vector<char*> argv;
  for (auto& argument : copies) argv.push_back(argument.data());
  argv.push_back(nullptr);
  int status = 0;
  {
    py::gil_scoped_release release;
    status = cli::run_cli(static_cast<int>(copies.size()), argv.data());
  }
  cli::set_script_loader(nullptr);
  return status;
}

}  // namespace

void bind_cli(py::module_& m) {
  m.def("cli_main", &cli_main, py::arg("arguments"), py::arg("loader"),
        "Runs the fastcorot command line (arguments[0]: the program's name) with `loader(script, strict)` "
        "building .py scenes; returns the exit status.");
}

}  // namespace fastcorot::python
