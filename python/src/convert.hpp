#pragma once
/// @file
/// NumPy ↔ Eigen conversion rules of the bindings, in one place:
/// - every vector and matrix is float64; integer and float32 input is converted, anything else
///   (complex, strings, objects) is refused with a `ValueError` naming the argument;
/// - shapes are checked and a wrong one is a `ValueError` naming the argument and the expected
///   shape ("q: expected shape (7,), got (3,)");
/// - non-contiguous arrays (slices, transposes) are copied, never misread;
/// - `None` where a value is required is a `TypeError` naming the argument.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <string>

namespace mjarm::python {

namespace py = pybind11;

/// A float64 vector of @p size entries (any size when @p size < 0) from @p object.
Eigen::VectorXd to_vector(py::handle object, const char* name, Eigen::Index size = -1);

/// A float64 matrix of @p rows × @p cols (any count where negative) from @p object.
Eigen::MatrixXd to_matrix(py::handle object, const char* name, Eigen::Index rows,
                          Eigen::Index cols);

/// Fixed-size vector (3, 4, 6) from @p object.
template <int N>
Eigen::Matrix<double, N, 1> to_fixed(py::handle object, const char* name) {
  return to_vector(object, name, N);
}

/// Fixed-size matrix from @p object.
template <int R, int C>
Eigen::Matrix<double, R, C> to_fixed_matrix(py::handle object, const char* name) {
  return to_matrix(object, name, R, C);
}

/// A NumPy copy of @p values (1-D float64).
py::array_t<double> to_array(const double* values, Eigen::Index size);

/// A read-only NumPy view of @p size doubles at @p data that keeps @p owner alive: the view can
/// never outlive what it looks into.
py::array_t<double> readonly_view(const double* data, Eigen::Index size, py::handle owner);

/// A writable NumPy view of @p size doubles at @p data that keeps @p owner alive.
py::array_t<double> writable_view(double* data, Eigen::Index size, py::handle owner);

}  // namespace mjarm::python
