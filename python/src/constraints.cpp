// The constraint stage of a built scene (FreeMotionAnimationLoop) as Python sees it: the last
// step's impulses and figures (the constraint solver's constraintForces, currentIterations,
// currentError, currentNumConstraints) and the data scripts change between steps
// (BilateralLagrangianConstraint's rest_vector, activate, load).
#include "arrays.h"
#include "bindings.h"
#include "simulation_core.h"

#include "fastcorot/constraint/free_motion_animation_loop.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace fastcorot::python {

namespace {

FreeMotionAnimationLoop<double>& loop_of(SimulationCore& c) {
  auto* loop = dynamic_cast<FreeMotionAnimationLoop<double>*>(c.simulation().constraints.get());
  if (!loop) throw py::value_error("the scene has no FreeMotionAnimationLoop");
  return *loop;
}

BilateralLagrangianConstraint<double>& bilateral(SimulationCore& c, std::size_t index) {
  auto& constraints = loop_of(c).constraints;
  if (index >= constraints.size()) throw py::index_error("constraint " + std::to_string(index) + " out of range");
  auto* constraint = dynamic_cast<BilateralLagrangianConstraint<double>*>(constraints[index].get());
  if (!constraint) throw py::value_error(constraints[index]->where() + " is not a BilateralLagrangianConstraint");
  return *constraint;
}

}  // namespace

void bind_constraints(py::class_<SimulationCore>& core) {
  core.def_property_readonly("constraint_objects", [](SimulationCore& c) { return c.scene.constraint_objects; })
      .def_property_readonly("constraint_solver_object", [](SimulationCore& c) { return c.scene.constraint_solver_object; })
      .def(
          "constraint_forces",
          [](SimulationCore& c) {
            std::lock_guard lock(c.stepping);  // not while another thread steps
            std::vector<double> values;
            if (c.simulation().constraints) {
              const auto forces = c.simulation().constraints->constraint_forces();
              values.assign(forces.begin(), forces.end());
            }
            py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
            std::copy(values.begin(), values.end(), array.mutable_data());
            return array;
          },
          "The last step's constraint impulses λ, one per row (force × dt, SOFA's constraintForces); empty "
          "without a FreeMotionAnimationLoop.")
      .def(
          "constraint_report",
          [](SimulationCore& c) {
            std::lock_guard lock(c.stepping);
            const ConstraintReport r = c.simulation().constraint_report();
            py::dict d;
            d["rows"] = r.rows;
            d["iterations"] = r.iterations;
            d["error"] = r.error;
            d["tolerance"] = r.tolerance;
            d["converged"] = r.converged;
            d["compliance_seconds"] = r.compliance_seconds;
            d["solve_seconds"] = r.solve_seconds;
            return d;
          },
          "What the last step's constraint solve did.")
      .def(
          "bilateral",
          [](SimulationCore& c, std::size_t index) {
            std::lock_guard lock(c.stepping);
            auto& p = bilateral(c, index).parameters();
            py::array_t<double> rest({static_cast<py::ssize_t>(p.rest.size()), py::ssize_t{3}});
            for (std::size_t k = 0; k < p.rest.size(); ++k) {
              for (int a = 0; a < 3; ++a) rest.mutable_at(static_cast<py::ssize_t>(k), a) = p.rest[k][a];
            }
            py::dict d;
            d["rest_vector"] = rest;
            d["activate"] = p.active;
            d["load"] = p.load;
            return d;
          },
          py::arg("index"))
      .def(
          "set_bilateral",
          [](SimulationCore& c, std::size_t index, py::object rest, py::object activate, py::object load) {
            std::lock_guard lock(c.stepping);
            auto& constraint = bilateral(c, index);
            auto& p = constraint.parameters();
            if (!rest.is_none()) {
              const auto array = point_array<double>(rest, constraint.where() + ": rest_vector", -1, "");
              const auto points = as_points(array);
              for (std::size_t k = 0; k < points.size(); ++k) {
                if (!points[k].allFinite()) throw py::value_error(constraint.where() + ": rest_vector[" + std::to_string(k) + "] is not finite");
              }
              p.rest.assign(points.begin(), points.end());
            }
            if (!activate.is_none()) p.active = activate.cast<bool>();
            if (!load.is_none()) {
              if (!py::isinstance<py::float_>(load) && !py::isinstance<py::int_>(load)) {
                throw py::type_error(constraint.where() + ": load: expected a number");
              }
              double value = load.cast<double>();
              if (!std::isfinite(value)) throw py::value_error(constraint.where() + ": load is not finite");
              if (value < 0 || value > 1) {
                // SOFA clamps it, with a warning.
                const std::string message = constraint.where() + ": load = " + std::to_string(value) + " lies outside [0, 1]: clamped, as SOFA does";
                if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) < 0) throw py::error_already_set();
                value = std::clamp(value, 0.0, 1.0);
              }
              p.load = value;
            }
          },
          py::arg("index"), py::arg("rest_vector") = py::none(), py::arg("activate") = py::none(), py::arg("load") = py::none());
}

}  // namespace fastcorot::python
