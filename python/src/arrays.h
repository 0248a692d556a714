// Checking what Python hands to the module: numpy arrays of points, index tuples and parameter
// lists. Every check names the argument and says what was expected and what came: a wrong dtype or
// something that is not numbers is a TypeError, a wrong shape or a non-finite value a ValueError.
// Arrays of points come back as C-contiguous (n, 3) arrays, so that they can be seen as spans of
// Vec3 without copying.
#pragma once

#include "fastcorot/core/types.h"

#include <Eigen/SparseCore>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <span>
#include <string>
#include <vector>

namespace fastcorot::python {

namespace py = pybind11;

template <class Real>
using PointArray = py::array_t<Real, py::array::c_style>;

// True when `value` is a numpy array whose dtype is float32 (returns 4) or float64 (8); 0 otherwise.
int float_itemsize(py::handle value);

// True when `value` is a numpy array of an integer dtype (signed or unsigned, any size).
bool integer_array(py::handle value);

// An (rows, 3) array of Real. A floating-point numpy array must have exactly that dtype
// (`dtype_note` explains the requirement in the TypeError); integer arrays and nested sequences
// are converted to Real. rows < 0 accepts any count.
template <class Real>
PointArray<Real> point_array(py::handle value, const std::string& what, py::ssize_t rows,
                             const std::string& dtype_note);

template <class Real>
std::span<const Vec3<Real>> as_points(const PointArray<Real>& array) {
  return {reinterpret_cast<const Vec3<Real>*>(array.data()), static_cast<std::size_t>(array.shape(0))};
}

// (rows, N) non-negative integer indices (any integer dtype, or nested sequences of integers).
template <std::size_t N>
std::vector<std::array<Index, N>> index_tuples(py::handle value, const std::string& what);

// A number, or a one-dimensional sequence of numbers.
std::vector<double> number_list(py::handle value, const std::string& what);

// A 1-D list or array of non-negative integer indices (TypeError / ValueError naming `what`).
std::vector<Index> index_list(py::handle value, const std::string& what);
// A numpy int array holding `values`.
py::array index_array(const std::vector<Index>& values);

// A scipy.sparse.csr_matrix of `matrix`, whose arrays are the matrix's own (it is kept alive by
// them: no copy), or (rows, cols, values) arrays when scipy is not installed.
template <class Real>
py::object sparse_matrix(Eigen::SparseMatrix<Real, Eigen::RowMajor> matrix);

// Python's repr of the shape of an array ("(4, 2)").
std::string shape_text(const py::array& array);

}  // namespace fastcorot::python
