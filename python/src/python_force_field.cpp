// Force fields written in Python (SofaPython3's Sofa.Core.ForceField subclasses): a ForceField of
// the mechanical system whose every call goes to the Python object, with numpy views of its
// MechanicalObject's range of the state (no copies) and SOFA's mechanical parameters (kFactor,
// bFactor, mFactor). The GIL is taken for each call, so the simulation may step with it released.
// A Python exception becomes a fastcorot::Error naming the force field and the call.
#include "arrays.h"
#include "bindings.h"
#include "simulation_core.h"

#include "fastcorot/core/error.h"
#include "fastcorot/fem/force_field.h"

#include <pybind11/numpy.h>

namespace fastcorot::python {

namespace {

class PythonForceField final : public ForceField<double> {
 public:
  PythonForceField(py::object field, std::string name, Index offset, Index count, Index total)
      : field_(std::move(field)), name_(std::move(name)), offset_(offset), count_(count),
        mesh_(std::make_shared<TetMesh>(total, std::vector<Tetrahedron>{})) {}
  ~PythonForceField() override {
    py::gil_scoped_acquire gil;
    field_ = py::object();
  }

  std::string component() const override { return "Python ForceField '" + name_ + "'"; }
  std::string method_name() const override { return "python"; }
  const TetMesh& mesh() const override { return *mesh_; }

  void set_velocity(std::span<const Vec3<double>> v) override { velocity_ = v; }
  void add_force(std::span<const Vec3<double>> x, std::span<Vec3<double>> f) override { force(x, f); }
  void add_force_only(std::span<const Vec3<double>> x, std::span<Vec3<double>> f) override { force(x, f); }

  void add_dforce(std::span<const Vec3<double>> dx, std::span<Vec3<double>> df, double k_factor,
                  double b_factor) const override {
    py::gil_scoped_acquire gil;
    call("addDForce", [&] {
      field_.attr("_fastcorot_add_dforce")(parameters(k_factor, b_factor), view(range(df), true), view(range(dx), false));
    });
  }

  void add_stiffness(MatrixSink<double>& sink, double k_factor, Index offset, double b_factor) const override {
    const Eigen::MatrixXd k = matrix(k_factor, b_factor);
    for (Index i = 0; i < count_; ++i) {
      for (Index j = 0; j < count_; ++j) {
        const Mat3<double> block = k.block<3, 3>(3 * i, 3 * j);
        if (!block.isZero(0)) sink.add_block(offset + 3 * (offset_ + i), offset + 3 * (offset_ + j), block);
      }
    }
  }
  void add_diagonal_blocks(std::span<Mat3<double>> diagonal, double k_factor, double b_factor) const override {
    const Eigen::MatrixXd k = matrix(k_factor, b_factor);
    for (Index i = 0; i < count_; ++i) diagonal[static_cast<std::size_t>(offset_ + i)] += k.block<3, 3>(3 * i, 3 * i);
  }

  double potential_energy(std::span<const Vec3<double>>) const override { return 0; }
  std::vector<Mat3<double>> rotations() const override { return {}; }
  void check_new_tetrahedra(std::span<const Tetrahedron>) const override {
    throw make_error(component(), ": a Python force field does not follow topological changes");
  }
  void apply(const TopologyChange&) override {
    throw make_error(component(), ": a Python force field does not follow topological changes");
  }
  std::string unsaved_state() const override { return "its Python state"; }
  std::vector<double> model_values() const override { return {}; }
  void set_threads(int) override {}
  int threads() const override { return 1; }
  void set_phase_times(PhaseTimes*) override {}
  std::size_t memory_bytes() const override { return 0; }

 private:
  template <class T>
  std::span<T> range(std::span<T> v) const {
    return v.subspan(static_cast<std::size_t>(offset_), static_cast<std::size_t>(count_));
  }

  // A (count, 3) float64 view of `points` (writable or not); valid for the call only.
  static py::array view(std::span<const Vec3<double>> points, bool writeable) {
    const auto rows = static_cast<py::ssize_t>(points.size());
    auto* data = const_cast<double*>(points.empty() ? nullptr : points[0].data());
    py::array_t<double> array({rows, py::ssize_t(3)}, {py::ssize_t(3 * sizeof(double)), py::ssize_t(sizeof(double))},
                              data, py::capsule(data, [](void*) {}));
    if (!writeable) array.attr("setflags")(py::arg("write") = false);
    return array;
  }

  static py::dict parameters(double k_factor, double b_factor) {
    py::dict mparams;
    mparams["kFactor"] = k_factor;
    mparams["bFactor"] = b_factor;
    mparams["mFactor"] = 0.0;
    mparams["isImplicit"] = true;
    return mparams;
  }

  template <class Call>
  void call(const char* method, const Call& body) const {
    try {
      body();
    } catch (py::error_already_set& error) {
      throw make_error(component(), ": ", method, ": ", py::str(error.value()).cast<std::string>());
    }
  }

  void force(std::span<const Vec3<double>> x, std::span<Vec3<double>> f) {
    py::gil_scoped_acquire gil;
    std::vector<Vec3<double>> zero;
    std::span<const Vec3<double>> v = velocity_;
    if (v.size() != x.size()) {
      zero.assign(x.size(), Vec3<double>::Zero());
      v = zero;
    }
    call("addForce", [&] {
      field_.attr("_fastcorot_add_force")(parameters(0, 0), view(range(f), true), view(range(x), false),
                                          view(range(v), false));
    });
  }

  // addKToMatrix's (3 count) x (3 count) matrix, already scaled by the factors it is given.
  Eigen::MatrixXd matrix(double k_factor, double b_factor) const {
    py::gil_scoped_acquire gil;
    Eigen::MatrixXd k;
    call("addKToMatrix", [&] {
      py::object result = field_.attr("addKToMatrix")(parameters(k_factor, b_factor), count_, 3);
      if (result.is_none()) {
        throw make_error(component(), ": addKToMatrix returned None: an assembling solver needs its (3n, 3n) matrix "
                         "(or use CGLinearSolver, which calls addDForce)");
      }
      const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result);
      if (!array || array.ndim() != 2 || array.shape(0) != 3 * count_ || array.shape(1) != 3 * count_) {
        throw make_error(component(), ": addKToMatrix must return a (", 3 * count_, ", ", 3 * count_, ") array");
      }
      k = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(array.data(),
                                                                                                    3 * count_, 3 * count_);
    });
    return k;
  }

  py::object field_;
  std::string name_;
  Index offset_, count_;
  std::shared_ptr<TetMesh> mesh_;
  std::span<const Vec3<double>> velocity_;
};

}  // namespace

void bind_python_force_fields(py::class_<SimulationCore>& core) {
  core.def(
      "add_python_force_field",
      [](SimulationCore& c, std::size_t k, py::object field, const std::string& name, Index start, Index stop) {
        auto& system = c.object(k).system;
        if (start < 0 || start > stop || stop > system.size()) throw py::index_error("points out of range");
        std::lock_guard lock(c.stepping);
        system.force_fields.push_back(std::make_shared<PythonForceField>(std::move(field), name, start, stop - start,
                                                                          system.size()));
        c.object(k).force_field_drawing.push_back({});
      },
      py::arg("k"), py::arg("field"), py::arg("name"), py::arg("start"), py::arg("stop"),
      "Adds a Python force field (its _fastcorot_add_force, _fastcorot_add_dforce and addKToMatrix) on object k's "
      "points [start, stop).");
}

}  // namespace fastcorot::python
