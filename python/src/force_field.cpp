// fastcorot.ForceField: CorotationalForceField on numpy arrays, in the precision of its points
// (float32 or float64). Arrays given to it must have its dtype; forces, products, rotations and the
// stiffness come back in that dtype. The computations release the GIL.
#include "arrays.h"
#include "bindings.h"

#include "fastcorot/fem/corotational_force_field.h"

#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <variant>

namespace fastcorot::python {

namespace {

const char* kForceFieldDoc = R"(SOFA's FastTetrahedralCorotationalForceField over a tetrahedral mesh, on numpy arrays.

ForceField(points, tetrahedra, young_modulus=5000, poisson_ratio=0.45, method="qr", edges=None,
           rayleigh_stiffness=0)

points: (n, 3) rest positions, float32 or float64 (the field computes in that dtype; a list gives
float64). tetrahedra: (m, 4) integer indices into points. young_modulus, poisson_ratio: one number,
or one per tetrahedron. method: "qr" ("large"), "polar", "polar2" or "none" ("linear", "small").
edges: an optional (k, 2) edge list (any order and orientation); derived as SOFA derives it otherwise.
Bad parameters and degenerate tetrahedra raise ValueError with the messages of `fastcorot probe`.)";

template <class Real>
using Field = CorotationalForceField<Real>;

template <class F>
struct RealOf;
template <class Real>
struct RealOf<Field<Real>> {
  using type = Real;
};

class ForceField {
 private:
  template <class F>
  using real_of = typename RealOf<std::remove_cvref_t<F>>::type;

  template <class Real>
  static std::unique_ptr<Field<Real>> make(py::handle points, const std::vector<Tetrahedron>& tets,
                                           const std::vector<double>& young, const std::vector<double>& poisson,
                                           const std::string& method, bool derive_edges, std::vector<Edge> edges,
                                           double rayleigh_stiffness) {
    const auto rest = point_array<Real>(points, "points", -1, "");
    typename Field<Real>::Parameters parameters;
    parameters.young_modulus.assign(young.begin(), young.end());
    parameters.poisson_ratio.assign(poisson.begin(), poisson.end());
    parameters.method = parse_rotation_method(method);
    parameters.rayleigh_stiffness = static_cast<Real>(rayleigh_stiffness);
    const auto n = static_cast<Index>(rest.shape(0));
    auto mesh = derive_edges ? std::make_shared<TetMesh>(n, tets) : std::make_shared<TetMesh>(n, tets, std::move(edges));
    return std::make_unique<Field<Real>>(mesh, as_points<Real>(rest), parameters);
  }

  bool single() const { return std::holds_alternative<std::unique_ptr<Field<float>>>(field_); }

  template <class Visitor>
  decltype(auto) visit(Visitor&& visitor) const {
    return std::visit([&](const auto& field) -> decltype(auto) { return visitor(*field); }, field_);
  }
  template <class Visitor>
  decltype(auto) visit(Visitor&& visitor) {
    return std::visit([&](auto& field) -> decltype(auto) { return visitor(*field); }, field_);
  }

  template <class Real>
  PointArray<Real> points(py::handle value, const std::string& what) const {
    return point_array<Real>(value, what, num_points(),
                             std::string(" (this ForceField computes in ") + (single() ? "float32" : "float64") +
                                 ", the dtype of its points; convert with .astype)");
  }

  template <class Real>
  PointArray<Real> zeros() const {
    PointArray<Real> out({static_cast<py::ssize_t>(num_points()), py::ssize_t(3)});
    std::fill(out.mutable_data(), out.mutable_data() + out.size(), Real(0));
    return out;
  }

  template <class Real>
  static std::span<Vec3<Real>> mutable_points(PointArray<Real>& array) {
    return {reinterpret_cast<Vec3<Real>*>(array.mutable_data()), static_cast<std::size_t>(array.shape(0))};
  }


 public:
  ForceField(py::handle points, py::handle tetrahedra, py::handle young_modulus, py::handle poisson_ratio,
             py::handle method, py::handle edges, double rayleigh_stiffness) {
    const int itemsize = float_itemsize(points);
    if (py::isinstance<py::array>(points) && itemsize == 0 && !integer_array(points)) {
      throw py::type_error("points: dtype " + std::string(py::str(points.attr("dtype"))) +
                           "; expected float32 or float64 (the ForceField computes in the dtype of its points;"
                           " integer arrays are converted to float64)");
    }
    if (!py::isinstance<py::str>(method)) {
      throw py::type_error("method: expected a string (qr, large, polar, polar2, none, linear or small)");
    }
    const auto tets = index_tuples<4>(tetrahedra, "tetrahedra");
    const auto young = number_list(young_modulus, "young_modulus");
    const auto poisson = number_list(poisson_ratio, "poisson_ratio");
    const auto edge_list = edges.is_none() ? std::vector<Edge>{} : index_tuples<2>(edges, "edges");
    if (itemsize == 4) {
      field_ = make<float>(points, tets, young, poisson, method.cast<std::string>(), edges.is_none(), edge_list,
                           rayleigh_stiffness);
    } else {
      field_ = make<double>(points, tets, young, poisson, method.cast<std::string>(), edges.is_none(), edge_list,
                            rayleigh_stiffness);
    }
  }

  py::dtype dtype() const { return single() ? py::dtype::of<float>() : py::dtype::of<double>(); }
  Index num_points() const { return visit([](const auto& f) { return f.mesh().num_points(); }); }
  Index num_tetrahedra() const { return visit([](const auto& f) { return f.mesh().num_tetrahedra(); }); }
  std::string method() const { return visit([](const auto& f) { return to_string(f.method()); }); }

  py::array add_force(py::handle x) {
    return visit([&](auto& f) -> py::array {
      using Real = real_of<decltype(f)>;
      const auto positions = points<Real>(x, "x");
      PointArray<Real> force = zeros<Real>();
      {
        py::gil_scoped_release release;
        const std::lock_guard lock(*busy_);
        f.add_force(as_points<Real>(positions), mutable_points(force));
      }
      return force;
    });
  }

  py::array add_dforce(py::handle dx, double k_factor) {
    return visit([&](auto& f) -> py::array {
      using Real = real_of<decltype(f)>;
      const auto displacement = points<Real>(dx, "dx");
      PointArray<Real> dforce = zeros<Real>();
      {
        py::gil_scoped_release release;
        const std::lock_guard lock(*busy_);
        f.add_dforce(as_points<Real>(displacement), mutable_points(dforce), static_cast<Real>(k_factor));
      }
      return dforce;
    });
  }

  double potential_energy(py::handle x) {
    return visit([&](auto& f) -> double {
      using Real = real_of<decltype(f)>;
      const auto positions = points<Real>(x, "x");
      py::gil_scoped_release release;
      const std::lock_guard lock(*busy_);
      return static_cast<double>(f.potential_energy(as_points<Real>(positions)));
    });
  }

  // K at x (after add_force(x)), or at the last add_force when x is None.
  py::object stiffness(py::handle x, double k_factor) {
    if (!x.is_none()) add_force(x);
    return visit([&](auto& f) -> py::object {
      using Real = real_of<decltype(f)>;
      Eigen::SparseMatrix<Real, Eigen::RowMajor> matrix;
      {
        py::gil_scoped_release release;
        const std::lock_guard lock(*busy_);
        matrix = f.stiffness_matrix(static_cast<Real>(k_factor));
        matrix.makeCompressed();
      }
      return sparse_matrix(std::move(matrix));
    });
  }

  // Cutting: the field's own mesh changes and the field follows (docs/cutting.md).
  py::array remove_tetrahedra(py::handle indices) {
    const std::vector<Index> list = index_list(indices, "indices");
    return visit([&](auto& f) -> py::array {
      const std::lock_guard lock(*busy_);
      const Index before = f.mesh().num_tetrahedra();
      const TopologyChange change = f.remove_tetrahedra(list);
      return index_array(old_to_new(before, change.tetrahedron_moves));
    });
  }

  void add_tetrahedra(py::handle tetrahedra) {
    const auto tets = index_tuples<4>(tetrahedra, "tetrahedra");
    visit([&](auto& f) {
      const std::lock_guard lock(*busy_);
      f.add_tetrahedra(tets);
    });
  }

  py::array tetrahedra() const {
    return visit([&](const auto& f) -> py::array {
      const auto tets = f.mesh().tetrahedra();
      py::array_t<Index> out({static_cast<py::ssize_t>(tets.size()), py::ssize_t(4)});
      Index* o = out.mutable_data();
      for (const Tetrahedron& t : tets) o = std::copy(t.begin(), t.end(), o);
      return out;
    });
  }

  py::array rotations() const {
    return visit([&](const auto& f) -> py::array {
      using Real = real_of<decltype(f)>;
      const auto all = [&] {
        const std::lock_guard lock(*busy_);
        return f.rotations();
      }();
      py::array_t<Real> out({static_cast<py::ssize_t>(all.size()), py::ssize_t(3), py::ssize_t(3)});
      auto o = out.template mutable_unchecked<3>();
      for (std::size_t t = 0; t < all.size(); ++t) {
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) o(static_cast<py::ssize_t>(t), i, j) = all[t](i, j);
        }
      }
      return out;
    });
  }

  py::array rest_volumes() const {
    return visit([](const auto& f) -> py::array { return py::array(py::cast(f.rest_volumes())); });
  }

  py::array edges() const {
    return visit([](const auto& f) -> py::array {
      const auto edges = f.mesh().edges();
      py::array_t<Index> out({static_cast<py::ssize_t>(edges.size()), py::ssize_t(2)});
      auto o = out.mutable_unchecked<2>();
      for (std::size_t e = 0; e < edges.size(); ++e) {
        o(static_cast<py::ssize_t>(e), 0) = edges[e][0];
        o(static_cast<py::ssize_t>(e), 1) = edges[e][1];
      }
      return out;
    });
  }

  int threads() const { return visit([](const auto& f) { return f.threads(); }); }
  void set_threads(int threads) {
    if (threads < 1) throw py::value_error("threads = " + std::to_string(threads) + ": must be at least 1");
    visit([&](auto& f) { f.set_threads(threads); });
  }

  std::string repr() const {
    return "<fastcorot.ForceField " + std::to_string(num_points()) + " points, " + std::to_string(num_tetrahedra()) +
           " tetrahedra, method " + method() + ", " + std::string(py::str(dtype())) + ">";
  }

 private:
  std::variant<std::unique_ptr<Field<double>>, std::unique_ptr<Field<float>>> field_;
  // One call into the field at a time: the methods above give up the GIL while they compute, and a
  // field keeps scratch and linearisation state, so two Python threads on one field take turns.
  // Nothing waits for the GIL while holding this lock (so no deadlock with a thread that holds the
  // GIL and waits for it).
  std::unique_ptr<std::mutex> busy_ = std::make_unique<std::mutex>();
};

}  // namespace

void bind_force_field(py::module_& m) {
  py::class_<ForceField>(m, "ForceField", kForceFieldDoc)
      .def(py::init<py::handle, py::handle, py::handle, py::handle, py::handle, py::handle, double>(), py::arg("points"),
           py::arg("tetrahedra"), py::arg("young_modulus") = 5000.0, py::arg("poisson_ratio") = 0.45,
           py::arg("method") = "qr", py::arg("edges") = py::none(), py::arg("rayleigh_stiffness") = 0.0)
      .def("add_force", &ForceField::add_force, py::arg("x"),
           "Forces at positions x ((n, 3)), from zero; x becomes the linearisation point of add_dforce and "
           "stiffness.")
      .def("add_dforce", &ForceField::add_dforce, py::arg("dx"), py::arg("k_factor") = 1.0,
           "k_factor * K dx ((n, 3)), K = df/dx as SOFA assembles it at the last add_force (rest state before).")
      .def("stiffness", &ForceField::stiffness, py::arg("x") = py::none(), py::arg("k_factor") = 1.0,
           "k_factor * df/dx, 3n x 3n (row = 3 * point + axis), at x (which add_force records) or, when x is "
           "None, at the last add_force: a scipy.sparse.csr_matrix, or (rows, cols, values) arrays without scipy.")
      .def("potential_energy", &ForceField::potential_energy, py::arg("x"),
           "Elastic energy at x: sum over tetrahedra of -1/2 sum_j u_j . g_j in the rest frame (SOFA returns 0).")
      .def_property_readonly("rotations", &ForceField::rotations,
                             "(m, 3, 3) rotation of each tetrahedron (rest frame to world) at the last add_force.")
      .def_property_readonly("rest_volumes", &ForceField::rest_volumes,
                             "(m,) signed rest volume of each tetrahedron (SOFA's sign convention).")
      .def_property_readonly("edges", &ForceField::edges, "(k, 2) the mesh edges, in the order the stiffness uses.")
      .def_property_readonly("dtype", &ForceField::dtype, "float32 or float64: the dtype of the points given.")
      .def_property_readonly("num_points", &ForceField::num_points)
      .def_property_readonly("num_tetrahedra", &ForceField::num_tetrahedra)
      .def_property_readonly("method", &ForceField::method, "The rotation method's canonical name.")
      .def_property_readonly("tetrahedra", &ForceField::tetrahedra, "(m, 4) the current tetrahedra.")
      .def("remove_tetrahedra", &ForceField::remove_tetrahedra, py::arg("indices"),
           "Removes tetrahedra (cutting) as SOFA does: in decreasing index order, each replaced by the last one.\n"
           "Returns the new index of every old tetrahedron (-1 for removed ones). Edges no tetrahedron uses any\n"
           "more go; points stay. Raises ValueError for an index out of range or listed twice (nothing changes).")
      .def("add_tetrahedra", &ForceField::add_tetrahedra, py::arg("tetrahedra"),
           "Appends (m, 4) tetrahedra over existing points (rest data from the rest positions; E and nu of\n"
           "per-tetrahedron lists from entry 0). Raises ValueError for a bad index or a degenerate tetrahedron.")
      .def_property("threads", &ForceField::threads, &ForceField::set_threads,
                    "Threads for the computations; results do not depend on it.")
      .def("__repr__", &ForceField::repr);
}

}  // namespace fastcorot::python
