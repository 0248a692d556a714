// The constraint stage of a built scene (FreeMotionAnimationLoop) as Python sees it: the last
// step's impulses and figures (the constraint solver's constraintForces, currentIterations,
// currentError, currentNumConstraints) and the data scripts change between steps
// (BilateralLagrangianConstraint's rest_vector, activate, load; StopperLagrangianConstraint's min
// and max).
#include "arrays.h"
#include "bindings.h"
#include "simulation_core.h"

#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/constraint/rigid_lagrangian_constraints.h"
#include "fastcorot/constraint/vec1_lagrangian_constraints.h"

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

LagrangianConstraint<double>& constraint_at(SimulationCore& c, std::size_t index) {
  auto& constraints = loop_of(c).constraints;
  if (index >= constraints.size()) throw py::index_error("constraint " + std::to_string(index) + " out of range");
  return *constraints[index];
}

BilateralLagrangianConstraint<double>& bilateral(SimulationCore& c, std::size_t index) {
  auto& constraint = constraint_at(c, index);
  auto* bilateral = dynamic_cast<BilateralLagrangianConstraint<double>*>(&constraint);
  if (!bilateral) throw py::value_error(constraint.where() + " is not a BilateralLagrangianConstraint");
  return *bilateral;
}

// A Rigid3 BilateralLagrangianConstraint (null for any other constraint).
RigidBilateralLagrangianConstraint<double>* rigid_bilateral(SimulationCore& c, std::size_t index) {
  return dynamic_cast<RigidBilateralLagrangianConstraint<double>*>(&constraint_at(c, index));
}

// A (pairs × 6) array of a Rigid3 pair's rest values (v then ω).
py::array_t<double> rigid_rest(const std::vector<std::array<double, 6>>& rest) {
  py::array_t<double> array({static_cast<py::ssize_t>(rest.size()), py::ssize_t{6}});
  for (std::size_t k = 0; k < rest.size(); ++k) {
    for (int a = 0; a < 6; ++a) array.mutable_at(static_cast<py::ssize_t>(k), a) = rest[k][static_cast<std::size_t>(a)];
  }
  return array;
}

// A script's rest_vector for a Rigid3 pair constraint: (pairs × 6) finite numbers; activate and
// load are accepted and, as in SOFA's Rigid3 variant, have no effect (warned).
void set_rigid_rest(RigidBilateralLagrangianConstraint<double>& constraint, py::object rest, py::object activate, py::object load) {
  if (!activate.is_none() || !load.is_none()) {
    const std::string message = constraint.where() + ": activate and load have no effect on a Rigid3 BilateralLagrangianConstraint (as in SOFA)";
    if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) < 0) throw py::error_already_set();
  }
  if (rest.is_none()) return;
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(rest);
  if (!array || array.size() % 6 != 0) {
    throw py::value_error(constraint.where() + ": rest_vector: 6 numbers per Rigid3 pair (vx vy vz wx wy wz) are needed");
  }
  std::vector<std::array<double, 6>> values(static_cast<std::size_t>(array.size() / 6));
  for (py::ssize_t i = 0; i < array.size(); ++i) {
    const double v = array.data()[i];
    if (!std::isfinite(v)) throw py::value_error(constraint.where() + ": rest_vector[" + std::to_string(i / 6) + "] is not finite");
    values[static_cast<std::size_t>(i / 6)][static_cast<std::size_t>(i % 6)] = v;
  }
  constraint.set_rest(std::move(values));
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
            if (auto* rigid = rigid_bilateral(c, index)) {
              // SOFA's Rigid3 variant reads rest_vector (6 numbers per pair), not activate or load.
              py::dict d;
              d["rest_vector"] = rigid_rest(rigid->parameters().rest);
              d["activate"] = true;
              d["load"] = 1.0;
              return d;
            }
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
            if (auto* rigid = rigid_bilateral(c, index)) {
              set_rigid_rest(*rigid, rest, activate, load);
              return;
            }
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
          py::arg("index"), py::arg("rest_vector") = py::none(), py::arg("activate") = py::none(), py::arg("load") = py::none())
      .def(
          "constraint_live",
          [](SimulationCore& c, std::size_t index) { return constraint_at(c, index).live_data(); },
          "The data of constraint `index` that scripts read or write between steps (SOFA's names).", py::arg("index"))
      .def(
          "read_constraint",
          [](SimulationCore& c, std::size_t index, const std::string& name) {
            std::vector<double> values;
            {
              std::lock_guard lock(c.stepping);  // not while another thread steps
              values = constraint_at(c, index).read_live(name);
            }
            return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
          },
          "Datum `name` of constraint `index` as the running simulation holds it (numbers, a copy).", py::arg("index"),
          py::arg("name"))
      .def(
          "write_constraint",
          [](SimulationCore& c, std::size_t index, const std::string& name, const std::vector<double>& values) {
            std::lock_guard lock(c.stepping);  // not while another thread steps
            constraint_at(c, index).write_live(name, values);
          },
          "Changes datum `name` of constraint `index` for the next steps (ValueError naming it when refused).", py::arg("index"),
          py::arg("name"), py::arg("values"))
      .def(
          "set_stopper",
          [](SimulationCore& c, std::size_t index, py::object min, py::object max) {
            std::lock_guard lock(c.stepping);
            auto& constraint = constraint_at(c, index);
            auto* stopper = dynamic_cast<StopperLagrangianConstraint<double>*>(&constraint);
            if (!stopper) throw py::value_error(constraint.where() + " is not a StopperLagrangianConstraint");
            auto p = stopper->parameters();
            const auto number = [&](py::object value, const char* name) {
              if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value)) {
                throw py::type_error(constraint.where() + ": " + name + ": expected a number");
              }
              const double v = value.cast<double>();
              if (!std::isfinite(v)) throw py::value_error(constraint.where() + ": " + name + " is not finite");
              return v;
            };
            if (!min.is_none()) p.min = number(min, "min");
            if (!max.is_none()) p.max = number(max, "max");
            if (p.min > p.max) {
              throw py::value_error(constraint.where() + ": min = " + std::to_string(p.min) + " is above max = " + std::to_string(p.max));
            }
            stopper->parameters() = p;
          },
          py::arg("index"), py::arg("min") = py::none(), py::arg("max") = py::none());
}

}  // namespace fastcorot::python
