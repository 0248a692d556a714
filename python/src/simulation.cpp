// A running simulation for Python: built by the scene builder from a scene tree (scene.cpp), stepped
// with the GIL released (one step at a time, so that Ctrl-C is seen between steps), and exposing
// each object's positions and velocities as numpy arrays that view the state's own memory. The
// solvers update the state vectors in place and never reallocate them, so a view stays valid for the
// life of the simulation (a test steps and reads through a view taken before).
#include "arrays.h"
#include "bindings.h"
#include "simulation_core.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/machine.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"
#include "fastcorot/io/carried_state.h"
#include "fastcorot/scene/scene_builder.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace fastcorot::python {

namespace {

LoadedScene build_tree(py::handle tree, bool strict, bool allow_empty) {
  SceneOptions options;
  options.strict = strict;
  options.allow_empty = allow_empty;
  return build_scene(scene_node_from_tree(tree), options);
}

std::unique_ptr<SimulationCore> build(py::handle tree, bool strict, bool allow_empty) {
  return std::make_unique<SimulationCore>(build_tree(tree, strict, allow_empty));
}

// The scene built again from its grown (or pruned) tree, with the running state carried over
// (io/carried_state.h); the running scene is kept, retired, so that arrays viewing it stay valid.
py::dict rebuild(SimulationCore& core, py::handle tree, bool strict, bool allow_empty) {
  LoadedScene fresh = build_tree(tree, strict, allow_empty);
  // What the running scene did not say already (a new node's unknown data, a collision component
  // its new models make the pipeline refuse, ...).
  std::vector<std::string> said;
  for (const auto& line : fresh.warnings) {
    if (std::find(core.scene.warnings.begin(), core.scene.warnings.end(), line) == core.scene.warnings.end()) said.push_back(line);
  }
  const auto refuse = [&](const char* what) {
    std::string why;
    for (const auto& line : said) why += "\n  " + line;
    throw py::value_error(std::string("the scene built again with the nodes added or removed while it runs would lose its ") + what +
                          ", so it was left as it was" + why);
  };
  if (core.simulation().collisions && !fresh.simulation.collisions) refuse("collision pipeline");
  if (core.simulation().constraints && !fresh.simulation.constraints) refuse("Lagrangian constraints");
  fresh.simulation.threads = core.simulation().threads;
  fresh.simulation.divergence_factor = core.simulation().divergence_factor;
  std::lock_guard lock(core.stepping);
  const CarriedState carried = carry_state(core.simulation(), fresh.simulation);
  core.retired.push_back(std::make_unique<LoadedScene>(std::move(core.scene)));
  core.scene = std::move(fresh);
  ++core.rebuilds;
  py::dict out;
  out["carried"] = carried.carried;
  out["fresh"] = carried.fresh;
  out["notes"] = carried.notes;
  out["warnings"] = said;
  return out;
}

void step(SimulationCore& core, long count) {
  if (count < 0) throw py::value_error("step: n = " + std::to_string(count) + ": must be >= 0");
  for (long i = 0; i < count; ++i) {
    std::string failure;
    {
      // The GIL is given up before taking the lock: a Python thread that holds the GIL and waits
      // for the lock (a setter) can then never block this step.
      py::gil_scoped_release release;
      std::lock_guard lock(core.stepping);
      try {
        core.simulation().step();
      } catch (const Error& error) {
        failure = error.what();
      }
    }
    if (!failure.empty()) throw StepFailure(failure);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

// An (n, 3) float64 array viewing `points`; `owner` keeps the memory alive.
py::array view(std::vector<Vec3<double>>& points, py::handle owner, bool writeable) {
  py::array_t<double> array({static_cast<py::ssize_t>(points.size()), py::ssize_t(3)},
                            {py::ssize_t(3 * sizeof(double)), py::ssize_t(sizeof(double))},
                            reinterpret_cast<double*>(points.data()), owner);
  if (!writeable) array.attr("setflags")(py::arg("write") = false);
  return array;
}

// Copies an (stop - start, 3) array into points [start, stop) of one of object k's state vectors
// (`what` names it), between steps.
void assign(SimulationCore& core, std::size_t k, std::vector<Vec3<double>> MechanicalState<double>::*vector,
            py::handle value, std::size_t start, std::size_t stop, const std::string& what) {
  auto& points = core.state(k).*vector;
  if (start > stop || stop > points.size()) {
    throw py::index_error(what + ": points [" + std::to_string(start) + ", " + std::to_string(stop) +
                          ") out of range (" + std::to_string(points.size()) + " points)");
  }
  const auto given = point_array<double>(value, what, static_cast<py::ssize_t>(stop - start), "");
  std::lock_guard lock(core.stepping);
  std::copy_n(as_points<double>(given).begin(), stop - start, points.begin() + static_cast<std::ptrdiff_t>(start));
}

// The rigids of object k whose blocks lie in [start, stop) (a Rigid3 MechanicalObject's range).
std::vector<std::size_t> rigids_in(SimulationCore& core, std::size_t k, std::size_t start, std::size_t stop) {
  const auto& rigids = core.simulation().objects[k].system.rigids;
  std::vector<std::size_t> out;
  if (!rigids) return out;
  for (std::size_t r = 0; r < rigids->size(); ++r) {
    const auto b = static_cast<std::size_t>(rigids->block[r]);
    if (b >= start && b < stop) out.push_back(r);
  }
  return out;
}

// The rigid coordinates a script gives for the `picked` rigids (7 numbers each), checked;
// `what` names the data in errors.
std::vector<RigidCoord<double>> rigid_rows_given(const std::vector<std::size_t>& picked, py::handle value, const std::string& what) {
  const auto numbers = number_list(value, what);
  if (numbers.size() != 7 * picked.size()) {
    throw py::value_error(what + ": " + std::to_string(numbers.size()) + " numbers for " + std::to_string(picked.size()) +
                          " rigids (7 each: x y z qx qy qz qw)");
  }
  try {
    return parse_rigid_coords<double>(numbers, what);
  } catch (const Error& error) {
    throw py::value_error(error.what());
  }
}

// (n, 7) rows x y z qx qy qz qw of those rigids, at the positions or the rest positions.
py::array_t<double> rigid_rows(SimulationCore& core, std::size_t k, std::size_t start, std::size_t stop, bool rest) {
  core.state(k);  // checks k
  std::lock_guard lock(core.stepping);
  const auto& system = core.simulation().objects[k].system;
  const auto picked = rigids_in(core, k, start, stop);
  py::array_t<double> out({static_cast<py::ssize_t>(picked.size()), py::ssize_t(7)});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < picked.size(); ++i) {
    const RigidCoord<double> c = rest ? system.rigids->rest_coord(system.state.rest_position, picked[i])
                                      : system.rigids->coord(system.state.position, picked[i]);
    const std::vector<double> values = to_values<double>(std::span<const RigidCoord<double>>(&c, 1));
    for (py::ssize_t j = 0; j < 7; ++j) o(static_cast<py::ssize_t>(i), j) = values[static_cast<std::size_t>(j)];
  }
  return out;
}

Vec3<double> vec3_of(py::handle value, const std::string& what) {
  const auto numbers = number_list(value, what);
  if (numbers.size() != 3) throw py::value_error(what + ": expected 3 numbers, got " + std::to_string(numbers.size()));
  const Vec3<double> v(numbers[0], numbers[1], numbers[2]);
  if (!v.allFinite()) throw py::value_error(what + ": expected 3 finite numbers");
  return v;
}

}  // namespace

void bind_simulation(py::module_& m) {
  m.def("default_thread_count", &default_thread_count, py::arg("points"),
        "The threads fastcorot chooses for a simulation of this many points (core/machine.h).");
  py::class_<SimulationCore> core(m, "SimulationCore",
                                  "The compiled simulation behind fastcorot.Simulation (built from a scene tree).");
  bind_matrices(core);
  bind_constraints(core);
  bind_contacts(core);
  bind_python_force_fields(core);
  core.def(py::init(&build), py::arg("tree"), py::arg("strict") = true, py::arg("allow_empty") = false)
      .def("rebuild", &rebuild, py::arg("tree"), py::arg("strict") = true, py::arg("allow_empty") = false,
           "The scene built again from `tree` (grown or pruned while running), the running state carried over: "
           "a dict of the objects carried, those new, and notes on what starts afresh.")
      .def_property_readonly("warnings", [](SimulationCore& c) { return c.scene.warnings; })
      .def("step", &step, py::arg("n") = 1, "Advances n time steps (the GIL is released while stepping).")
      .def_property(
          "dt", [](SimulationCore& c) { return c.simulation().dt; },
          [](SimulationCore& c, double dt) {
            if (!(dt > 0) || !std::isfinite(dt)) throw py::value_error("dt = " + std::to_string(dt) + ": must be a finite number > 0");
            std::lock_guard lock(c.stepping);
            c.simulation().dt = dt;
          })
      .def_property(
          "gravity",
          [](SimulationCore& c) {
            const auto& g = c.simulation().gravity;
            return py::make_tuple(g.x(), g.y(), g.z());
          },
          [](SimulationCore& c, py::handle value) {
            const Vec3<double> g = vec3_of(value, "gravity");
            std::lock_guard lock(c.stepping);
            c.simulation().gravity = g;
            for (auto& object : c.simulation().objects) object.system.gravity = g;
          })
      .def_property(
          "threads", [](SimulationCore& c) { return c.simulation().threads; },
          [](SimulationCore& c, int threads) {
            if (threads < 1) throw py::value_error("threads = " + std::to_string(threads) + ": must be at least 1");
            std::lock_guard lock(c.stepping);
            c.simulation().threads = threads;
          })
      .def_property_readonly("time", [](SimulationCore& c) { return c.simulation().time(); })
      .def_property_readonly("steps_done", [](SimulationCore& c) { return c.simulation().steps_done(); })
      .def_property_readonly("info", [](SimulationCore& c) { return c.scene.info; })
      .def_property_readonly("state_objects", [](SimulationCore& c) { return c.scene.state_objects; })
      .def_property_readonly("state_counts", [](SimulationCore& c) { return c.scene.state_counts; })
      .def_property_readonly("state_parts",
                             [](SimulationCore& c) {
                               py::list parts;
                               for (const auto& p : c.scene.state_parts) parts.append(py::make_tuple(p.rank, p.object, p.offset, p.size));
                               return parts;
                             },
                             "(rank, object, offset, size) of every simulated MechanicalObject")
      .def_property_readonly("paths",
                             [](SimulationCore& c) {
                               std::vector<std::string> paths;
                               for (const auto& object : c.simulation().objects) paths.push_back(object.path);
                               return paths;
                             })
      .def(
          "states",
          [](SimulationCore& c) {
            py::dict out;
            // (n, 3) arrays, or (n, 1) for a Vec1 state (SofaPython3's shapes).
            const auto copy = [](const std::vector<Vec3<double>>& points, int coordinates) {
              PointArray<double> array(std::vector<py::ssize_t>{static_cast<py::ssize_t>(points.size()), coordinates});
              for (std::size_t i = 0; i < points.size(); ++i) {
                std::copy_n(points[i].data(), coordinates, array.mutable_data() + coordinates * static_cast<std::ptrdiff_t>(i));
              }
              return array;
            };
            for (const auto& object : c.simulation().objects) {
              for (const StateSnapshot& state : state_snapshots(object)) {
                py::dict entry;
                entry["node"] = state.node;
                entry["object"] = state.name;
                entry["mapped"] = state.mapped;
                if (state.rigid) {
                  // SofaPython3's Rigid3d arrays: (n, 7) positions, (n, 6) velocities.
                  const auto rows = [](const std::vector<double>& values, py::ssize_t width) {
                    PointArray<double> array(std::vector<py::ssize_t>{static_cast<py::ssize_t>(values.size()) / width, width});
                    std::copy(values.begin(), values.end(), array.mutable_data());
                    return array;
                  };
                  entry["position"] = rows(state.rigid_position, 7);
                  entry["velocity"] = rows(state.rigid_velocity, 6);
                } else {
                  entry["position"] = copy(state.position, state.coordinates);
                  entry["velocity"] = copy(state.velocity, state.coordinates);
                }
                out[py::str(state.key())] = entry;
              }
            }
            return out;
          },
          "Every MechanicalObject, mapped ones included, as `fastcorot run --dump-state` dumps a step: "
          "{'node path/object': {'node', 'object', 'mapped', 'position', 'velocity'}} (copies).")
      .def(
          "position", [](py::object self, std::size_t k) { return view(self.cast<SimulationCore&>().state(k).position, self, true); },
          py::arg("k"))
      .def(
          "velocity", [](py::object self, std::size_t k) { return view(self.cast<SimulationCore&>().state(k).velocity, self, true); },
          py::arg("k"))
      .def(
          "rest_position",
          [](py::object self, std::size_t k) { return view(self.cast<SimulationCore&>().state(k).rest_position, self, false); },
          py::arg("k"))
      .def(
          "tetrahedra",
          [](SimulationCore& c, std::size_t k) {
            c.state(k);  // checks k
            const auto& mesh = c.simulation().objects[k].mesh;
            const auto count = mesh ? static_cast<py::ssize_t>(mesh->num_tetrahedra()) : 0;
            py::array_t<Index> out({count, py::ssize_t(4)});
            auto o = out.mutable_unchecked<2>();
            for (py::ssize_t t = 0; t < count; ++t) {
              for (py::ssize_t j = 0; j < 4; ++j) o(t, j) = mesh->tetrahedron(static_cast<Index>(t))[static_cast<std::size_t>(j)];
            }
            return out;
          },
          py::arg("k"), "(m, 4) tetrahedra of object k's force field (empty without one).")
      .def(
          "von_mises_stress",
          [](SimulationCore& c, std::size_t k, bool per_node) -> py::object {
            c.state(k);  // checks k
            std::lock_guard lock(c.stepping);
            for (const auto& field : c.simulation().objects[k].system.force_fields) {
              const auto* fem = dynamic_cast<const TetrahedronFEMForceField<double>*>(field.get());
              if (!fem || !fem->computes_von_mises_stress()) continue;
              const auto values = per_node ? fem->von_mises_per_node() : fem->von_mises_per_element();
              py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
              std::copy(values.begin(), values.end(), out.mutable_data());
              return std::move(out);
            }
            return py::none();
          },
          py::arg("k"), py::arg("per_node"),
          "Object k's von Mises stress (TetrahedronFEMForceField with computeVonMisesStress 1 or 2), per point "
          "or per tetrahedron, after the last step (a copy); None when none is computed.")
      .def(
          "remove_tetrahedra",
          [](SimulationCore& c, std::size_t k, py::handle indices) {
            c.state(k);  // checks k
            const std::vector<Index> list = index_list(indices, "indices");
            auto& object = c.simulation().objects[k];
            if (!object.mesh) throw py::value_error(object.path + " has no tetrahedral topology to cut");
            std::lock_guard lock(c.stepping);
            const Index before = object.mesh->num_tetrahedra();
            const TopologyChange change = object.system.remove_tetrahedra(*object.mesh, list);
            return index_array(old_to_new(before, change.tetrahedron_moves));
          },
          py::arg("k"), py::arg("indices"),
          "Removes tetrahedra from object k's mesh (its force fields and mass follow); returns old -> new indices.")
      .def(
          "add_tetrahedra",
          [](SimulationCore& c, std::size_t k, py::handle tetrahedra) {
            c.state(k);
            const auto tets = index_tuples<4>(tetrahedra, "tetrahedra");
            auto& object = c.simulation().objects[k];
            if (!object.mesh) throw py::value_error(object.path + " has no tetrahedral topology");
            std::lock_guard lock(c.stepping);
            object.system.add_tetrahedra(*object.mesh, tets);
          },
          py::arg("k"), py::arg("tetrahedra"), "Appends tetrahedra to object k's mesh (its force fields and mass follow).")
      .def(
          "set_position",
          [](SimulationCore& c, std::size_t k, py::handle value, std::size_t start, std::size_t stop) {
            assign(c, k, &MechanicalState<double>::position, value, start, stop, "position");
          },
          py::arg("k"), py::arg("value"), py::arg("start"), py::arg("stop"))
      .def(
          "rigid_position",
          [](SimulationCore& c, std::size_t k, std::size_t start, std::size_t stop) { return rigid_rows(c, k, start, stop, false); },
          py::arg("k"), py::arg("start"), py::arg("stop"),
          "(n, 7) positions x y z qx qy qz qw of object k's rigids with blocks in [start, stop) (a copy).")
      .def(
          "rigid_rest_position",
          [](SimulationCore& c, std::size_t k, std::size_t start, std::size_t stop) { return rigid_rows(c, k, start, stop, true); },
          py::arg("k"), py::arg("start"), py::arg("stop"), "(n, 7) rest positions of those rigids (a copy).")
      .def(
          "set_rigid_position",
          [](SimulationCore& c, std::size_t k, py::handle value, std::size_t start, std::size_t stop) {
            c.state(k);  // checks k
            const auto picked = rigids_in(c, k, start, stop);
            const auto coords = rigid_rows_given(picked, value, "position");
            std::lock_guard lock(c.stepping);
            auto& system = c.simulation().objects[k].system;
            for (std::size_t i = 0; i < picked.size(); ++i) {
              const auto b = static_cast<std::size_t>(system.rigids->block[picked[i]]);
              system.state.position[b] = coords[i].center;
              system.state.position[b + 1].setZero();
              system.rigids->orientation[picked[i]] = coords[i].orientation;
            }
            system.rigids->rebase(system.state.position);  // passes the orientations on to the followers
          },
          py::arg("k"), py::arg("value"), py::arg("start"), py::arg("stop"))
      .def(
          "set_rest_position",
          [](SimulationCore& c, std::size_t k, py::handle value, std::size_t start, std::size_t stop) {
            assign(c, k, &MechanicalState<double>::rest_position, value, start, stop, "rest_position");
            std::lock_guard lock(c.stepping);
            return c.simulation().objects[k].system.follow_rest_positions();
          },
          py::arg("k"), py::arg("value"), py::arg("start"), py::arg("stop"),
          "Writes rest positions; the fields that read them each step in SOFA (RestShapeSpringsForceField) follow. "
          "Returns how many did.")
      .def(
          "set_rigid_rest_position",
          [](SimulationCore& c, std::size_t k, py::handle value, std::size_t start, std::size_t stop) {
            c.state(k);  // checks k
            const auto picked = rigids_in(c, k, start, stop);
            const auto coords = rigid_rows_given(picked, value, "rest_position");
            std::lock_guard lock(c.stepping);
            auto& system = c.simulation().objects[k].system;
            auto& rigids = *system.rigids;
            for (std::size_t i = 0; i < picked.size(); ++i) {
              const auto b = static_cast<std::size_t>(rigids.block[picked[i]]);
              system.state.rest_position[b] = coords[i].center;
              rigids.rest_orientation[picked[i]] = coords[i].orientation;
            }
            for (auto& [follower, first] : rigids.followers) {  // merged objects' own blocks
              std::copy_n(rigids.rest_orientation.begin() + static_cast<std::ptrdiff_t>(first), follower->size(),
                          follower->rest_orientation.begin());
            }
            return system.follow_rest_positions();
          },
          py::arg("k"), py::arg("value"), py::arg("start"), py::arg("stop"))
      .def(
          "set_velocity",
          [](SimulationCore& c, std::size_t k, py::handle value, std::size_t start, std::size_t stop) {
            assign(c, k, &MechanicalState<double>::velocity, value, start, stop, "velocity");
          },
          py::arg("k"), py::arg("value"), py::arg("start"), py::arg("stop"));
}

}  // namespace fastcorot::python
