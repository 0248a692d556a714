// The collision stage of a built scene (SOFA's collision pipeline) as Python sees it: the contacts
// the last step's detection kept, as `fastcorot run --dump-state` writes them under "contacts"
// (docs/cli.md), and what the detection did (CollisionReport). SofaPython3 has no such accessor:
// the names are fastcorot's (docs/python.md).
#include "bindings.h"
#include "simulation_core.h"

#include <pybind11/numpy.h>

#include <mutex>

namespace fastcorot::python {

void bind_contacts(py::class_<SimulationCore>& core) {
  core.def(
          "contacts",
          [](SimulationCore& c) {
            std::lock_guard lock(c.stepping);  // not while another thread steps
            const auto* stage = c.simulation().collisions.get();
            const std::span<const DetectedContact<double>> contacts =
                stage ? stage->contacts() : std::span<const DetectedContact<double>>{};
            const auto n = static_cast<py::ssize_t>(contacts.size());
            py::array_t<double> points({n, py::ssize_t{2}, py::ssize_t{3}});
            py::array_t<double> normals({n, py::ssize_t{3}});
            auto p = points.mutable_unchecked<3>();
            auto m = normals.mutable_unchecked<2>();
            for (py::ssize_t k = 0; k < n; ++k) {
              const DetectedContact<double>& contact = contacts[static_cast<std::size_t>(k)];
              for (py::ssize_t a = 0; a < 3; ++a) {
                p(k, 0, a) = contact.point[0][a];
                p(k, 1, a) = contact.point[1][a];
                m(k, a) = contact.normal[a];
              }
            }
            py::dict d;
            d["count"] = contacts.size();
            d["points"] = std::move(points);
            d["normals"] = std::move(normals);
            return d;
          },
          "The contacts the last step's collision detection kept, in solve order: {\"count\": n, \"points\": "
          "(n, 2, 3) (on the first element, on the second), \"normals\": (n, 3) (unit, first to second)}; "
          "count 0 without a collision pipeline or before the first step.")
      .def(
          "collision_report",
          [](SimulationCore& c) {
            std::lock_guard lock(c.stepping);
            const CollisionReport r = c.simulation().collision_report();
            py::dict d;
            d["contacts"] = r.contacts;
            d["model_pairs"] = r.model_pairs;
            d["element_pairs"] = r.element_pairs;
            d["degenerate_elements"] = r.degenerate_elements;
            d["detection_seconds"] = r.detection_seconds;
            d["crossed"] = r.crossed;
            d["deepest_crossing"] = r.deepest_crossing;
            return d;
          },
          "What the last step's collision detection did (all zero without a collision pipeline).");
}

}  // namespace fastcorot::python
