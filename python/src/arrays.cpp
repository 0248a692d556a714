#include "arrays.h"

#include <cmath>
#include <limits>

namespace fastcorot::python {

namespace {

py::object numpy() { return py::module_::import("numpy"); }

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

std::string dtype_name(const py::array& array) { return py::str(array.dtype()); }

// A sequence converted by numpy; what numpy cannot convert is a TypeError naming the argument.
py::array converted(py::handle value, const std::string& what, const std::string& expected,
                    py::object dtype) {
  try {
    return numpy().attr("asarray")(value, py::arg("dtype") = dtype);
  } catch (py::error_already_set& error) {
    throw py::type_error(what + ": expected " + expected + ", got a " + type_name(value) +
                         " that numpy cannot convert (" + std::string(py::str(error.value())) + ")");
  }
}

}  // namespace

std::string shape_text(const py::array& array) { return py::str(py::tuple(array.attr("shape"))); }

int float_itemsize(py::handle value) {
  if (!py::isinstance<py::array>(value)) return 0;
  const py::dtype dtype = py::reinterpret_borrow<py::array>(value).dtype();
  if (dtype.kind() != 'f' || (dtype.itemsize() != 4 && dtype.itemsize() != 8)) return 0;
  return static_cast<int>(dtype.itemsize());
}

bool integer_array(py::handle value) {
  if (!py::isinstance<py::array>(value)) return false;
  const char kind = py::reinterpret_borrow<py::array>(value).dtype().kind();
  return kind == 'i' || kind == 'u';
}

template <class Real>
PointArray<Real> point_array(py::handle value, const std::string& what, py::ssize_t rows,
                             const std::string& dtype_note) {
  const std::string expected = "an (n, 3) array of numbers";
  py::array array;
  if (py::isinstance<py::array>(value)) {
    array = py::reinterpret_borrow<py::array>(value);
    // Integers become floating point as numpy's own functions convert them; another float type
    // is refused, since converting it would hide a precision the caller did not ask for.
    if (integer_array(array)) array = converted(value, what, expected, py::dtype::of<Real>());
    if (float_itemsize(array) != static_cast<int>(sizeof(Real))) {
      throw py::type_error(what + ": dtype " + dtype_name(array) + "; expected " +
                           (sizeof(Real) == 4 ? "float32" : "float64") + dtype_note);
    }
  } else {
    array = converted(value, what, expected, py::dtype::of<Real>());
  }
  if (array.ndim() != 2 || array.shape(1) != 3 || (rows >= 0 && array.shape(0) != rows)) {
    const std::string wanted = rows >= 0 ? "(" + std::to_string(rows) + ", 3)" : "(n, 3)";
    throw py::value_error(what + ": expected shape " + wanted + ", got " + shape_text(array));
  }
  auto points = PointArray<Real>::ensure(array);  // native byte order, C order
  if (!points) throw py::error_already_set();
  const Real* data = points.data();
  for (py::ssize_t i = 0; i < 3 * points.shape(0); ++i) {
    if (!std::isfinite(data[i])) {
      throw py::value_error(what + "[" + std::to_string(i / 3) + "] has a coordinate that is not finite (" +
                            std::string(py::str(py::float_(data[i]))) + ")");
    }
  }
  return points;
}

template <std::size_t N>
std::vector<std::array<Index, N>> index_tuples(py::handle value, const std::string& what) {
  const std::string expected = "an (m, " + std::to_string(N) + ") array of integer indices";
  py::array array = py::isinstance<py::array>(value) ? py::reinterpret_borrow<py::array>(value)
                                                     : converted(value, what, expected, py::none());
  if (array.size() == 0 && array.ndim() == 1) array = array.attr("reshape")(0, N).attr("astype")("int64");
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u') {
    throw py::type_error(what + ": dtype " + dtype_name(array) + "; expected " + expected);
  }
  if (array.ndim() != 2 || array.shape(1) != static_cast<py::ssize_t>(N)) {
    throw py::value_error(what + ": expected shape (m, " + std::to_string(N) + "), got " + shape_text(array));
  }
  const auto wide = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!wide) throw py::error_already_set();
  std::vector<std::array<Index, N>> tuples(static_cast<std::size_t>(wide.shape(0)));
  const long long* data = wide.data();
  for (std::size_t t = 0; t < tuples.size(); ++t) {
    for (std::size_t k = 0; k < N; ++k) {
      const long long index = data[N * t + k];
      if (index < 0 || index > std::numeric_limits<Index>::max()) {
        throw py::value_error(what + "[" + std::to_string(t) + "] has index " + std::to_string(index) +
                              ", outside [0, " + std::to_string(std::numeric_limits<Index>::max()) + "]");
      }
      tuples[t][k] = static_cast<Index>(index);
    }
  }
  return tuples;
}

std::vector<double> number_list(py::handle value, const std::string& what) {
  const std::string expected = "a number or a list of numbers";
  if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value)) {
    throw py::type_error(what + ": expected " + expected + ", got a " + type_name(value));
  }
  py::array array = converted(value, what, expected, py::dtype::of<double>());
  if (array.ndim() > 1) throw py::value_error(what + ": expected " + expected + ", got shape " + shape_text(array));
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  return {values.data(), values.data() + values.size()};
}

template PointArray<float> point_array<float>(py::handle, const std::string&, py::ssize_t, const std::string&);
template PointArray<double> point_array<double>(py::handle, const std::string&, py::ssize_t, const std::string&);
std::vector<Index> index_list(py::handle value, const std::string& what) {
  py::array array = py::module_::import("numpy").attr("asarray")(value);
  if (array.ndim() != 1) throw py::value_error(what + ": expected a list of indices, got shape " + shape_text(array));
  if (array.size() == 0) return {};
  std::vector<Index> indices;
  for (const auto& one : index_tuples<1>(array.attr("reshape")(-1, 1), what)) indices.push_back(one[0]);
  return indices;
}

py::array index_array(const std::vector<Index>& values) {
  py::array_t<Index> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

template std::vector<std::array<Index, 1>> index_tuples<1>(py::handle, const std::string&);
template std::vector<std::array<Index, 2>> index_tuples<2>(py::handle, const std::string&);
template std::vector<std::array<Index, 4>> index_tuples<4>(py::handle, const std::string&);

template <class Real>
py::object sparse_matrix(Eigen::SparseMatrix<Real, Eigen::RowMajor> input) {
  // The matrix moves to the heap and numpy views its arrays, which scipy takes as they are: no copy.
  using Matrix = Eigen::SparseMatrix<Real, Eigen::RowMajor>;
  auto* matrix = new Matrix(std::move(input));
  matrix->makeCompressed();
  const py::capsule owner(matrix, [](void* p) { delete static_cast<Matrix*>(p); });
  const auto nonzeros = static_cast<py::ssize_t>(matrix->nonZeros());
  py::array_t<Real> values(nonzeros, matrix->valuePtr(), owner);
  py::array_t<Index> columns(nonzeros, matrix->innerIndexPtr(), owner);
  py::array_t<Index> starts(matrix->rows() + 1, matrix->outerIndexPtr(), owner);
  py::object sparse;
  try {
    sparse = py::module_::import("scipy.sparse");
  } catch (py::error_already_set& error) {
    if (!error.matches(PyExc_ImportError)) throw;
    py::array_t<Index> rows(nonzeros);
    auto r = rows.mutable_unchecked<1>();
    for (Eigen::Index row = 0; row < matrix->rows(); ++row) {
      for (Index k = matrix->outerIndexPtr()[row]; k < matrix->outerIndexPtr()[row + 1]; ++k) r(k) = static_cast<Index>(row);
    }
    return py::make_tuple(rows, columns, values);
  }
  return sparse.attr("csr_matrix")(py::make_tuple(values, columns, starts),
                                   py::arg("shape") = py::make_tuple(matrix->rows(), matrix->cols()));
}

template py::object sparse_matrix(Eigen::SparseMatrix<float, Eigen::RowMajor>);
template py::object sparse_matrix(Eigen::SparseMatrix<double, Eigen::RowMajor>);

}  // namespace fastcorot::python
