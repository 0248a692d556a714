// The matrices SofaPython3 scripts read from components: a force field's stiffness (SOFA's
// assembleKMatrix: df/dx, with SOFA's sign) and a mass's matrix (assembleMMatrix), each over the
// points of its own MechanicalObject, as scipy.sparse matrices.
#include "arrays.h"
#include "bindings.h"
#include "simulation_core.h"

#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/sim/merged_objects.h"

#include <pybind11/stl.h>

namespace fastcorot::python {

namespace {

using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Rows and columns [3 start, 3 stop) of `matrix`: one MechanicalObject's part of a merged object.
RowMatrix part(const RowMatrix& matrix, Index start, Index stop) {
  if (start == 0 && 3 * stop == matrix.rows()) return matrix;
  return matrix.block(3 * start, 3 * start, 3 * (stop - start), 3 * (stop - start));
}

}  // namespace

void bind_matrices(py::class_<SimulationCore>& core) {
  core.def(
          "force_field_types",
          [](SimulationCore& c, std::size_t k) {
            std::vector<std::string> types;
            for (const auto& field : c.object(k).system.force_fields) types.push_back(field->component());
            return types;
          },
          py::arg("k"), "The component type of each of object k's force fields, in scene order.")
      .def(
          "stiffness_matrix",
          [](SimulationCore& c, std::size_t k, std::size_t i) {
            auto& fields = c.object(k).system.force_fields;
            if (i >= fields.size()) throw py::index_error("force field " + std::to_string(i) + " out of range");
            std::lock_guard lock(c.stepping);
            const ForceField<double>* field = fields[i].get();
            if (const auto* shifted = dynamic_cast<const OffsetForceField<double>*>(field)) field = &shifted->inner();
            return sparse_matrix(RowMatrix(field->stiffness_matrix(1.0)));
          },
          py::arg("k"), py::arg("i"),
          "df/dx of object k's force field i at its last linearisation, over its own points (SOFA's "
          "assembleKMatrix).")
      .def(
          "mass_matrix",
          [](SimulationCore& c, std::size_t k, Index start, Index stop) {
            auto& system = c.object(k).system;
            if (system.mass.size() == 0) throw py::value_error(c.object(k).path + " has no mass");
            std::lock_guard lock(c.stepping);
            TripletSink<double> sink;
            system.mass.add_to_matrix(sink, 1.0);
            RowMatrix matrix(3 * system.size(), 3 * system.size());
            matrix.setFromTriplets(sink.triplets.begin(), sink.triplets.end());
            return sparse_matrix(part(matrix, start, stop));
          },
          py::arg("k"), py::arg("start"), py::arg("stop"),
          "The mass matrix of object k's points [start, stop) (SOFA's assembleMMatrix).");
}

}  // namespace fastcorot::python
