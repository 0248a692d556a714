// The matrices SofaPython3 scripts read from components: a force field's stiffness (SOFA's
// assembleKMatrix: df/dx, with SOFA's sign) and a mass's matrix (assembleMMatrix), each over the
// points of its own MechanicalObject, as scipy.sparse matrices; and a linear system's last solve
// (MatrixLinearSystem's get_system_matrix, get_rhs_vector, get_solution_vector), recorded by
// wrapping each object's linear solver once a script asks for it.
#include "arrays.h"
#include "bindings.h"
#include "simulation_core.h"

#include "fastcorot/fem/matrix_sink.h"
#include "fastcorot/sim/linear_solver.h"
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

// A linear solver that keeps what its last solve was given and gave: the matrix factors, the
// right-hand side and the solution (copies; results are those of the solver it wraps).
class RecordingSolver final : public LinearSolver<double> {
 public:
  explicit RecordingSolver(std::unique_ptr<LinearSolver<double>> inner) : inner_(std::move(inner)) {}

  LinearSolveReport solve(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                          std::span<const Vec3<double>> rhs, std::span<Vec3<double>> x) override {
    const LinearSolveReport report = inner_->solve(system, factors, rhs, x);
    factors_ = factors;
    rhs_.assign(rhs.begin(), rhs.end());
    solution_.assign(x.begin(), x.end());
    solved_ = true;
    return report;
  }
  std::vector<std::int64_t> carried_state() const override { return inner_->carried_state(); }
  void restore_carried_state(const std::vector<std::int64_t>& state) override { inner_->restore_carried_state(state); }
  void check_carried_state(const std::vector<std::int64_t>& state) const override { inner_->check_carried_state(state); }

  bool solved_ = false;
  MatrixFactors<double> factors_;
  std::vector<Vec3<double>> rhs_, solution_;

 private:
  std::unique_ptr<LinearSolver<double>> inner_;
};

py::array_t<double> flat(const std::vector<Vec3<double>>& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(3 * v.size()));
  std::copy_n(v.empty() ? nullptr : v[0].data(), 3 * v.size(), out.mutable_data());
  return out;
}

RecordingSolver* recorder(SimulationCore& c, std::size_t k) {
  auto* solver = dynamic_cast<RecordingSolver*>(c.object(k).linear_solver.get());
  if (!solver) throw py::value_error(c.object(k).path + ": its solves are not recorded (record_solves() first)");
  return solver;
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
          "The mass matrix of object k's points [start, stop) (SOFA's assembleMMatrix).")
      .def(
          "record_solves",
          [](SimulationCore& c) {
            std::lock_guard lock(c.stepping);
            for (auto& object : c.simulation().objects) {
              if (object.linear_solver && !dynamic_cast<RecordingSolver*>(object.linear_solver.get())) {
                object.linear_solver = std::make_unique<RecordingSolver>(std::move(object.linear_solver));
              }
            }
          },
          "From now on, keeps each object's last linear solve (factors, right-hand side, solution).")
      .def(
          "last_solve",
          [](SimulationCore& c, std::size_t k) -> py::object {
            const RecordingSolver* solver = recorder(c, k);
            if (!solver->solved_) return py::none();
            const auto& f = solver->factors_;
            return py::make_tuple(py::make_tuple(f.m, f.b, f.k), flat(solver->rhs_), flat(solver->solution_));
          },
          py::arg("k"), "((m, b, k) factors, rhs, solution) of object k's last solve; None before any.")
      .def(
          "system_matrix",
          [](SimulationCore& c, std::size_t k, double m, double b, double kf) {
            std::lock_guard lock(c.stepping);
            return sparse_matrix(RowMatrix(c.object(k).system.assemble({m, b, kf})));
          },
          py::arg("k"), py::arg("m"), py::arg("b"), py::arg("kf"),
          "m M + b B + k K of object k at its force fields' last linearisation, projected (fixed points' rows "
          "and columns cleared, 1 on their diagonal), as SOFA's MatrixLinearSystem holds it.");
}

}  // namespace fastcorot::python
