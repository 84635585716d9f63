#include "convert.hpp"

#include <cstring>

namespace mjarm::python {
namespace {

std::string shape_text(Eigen::Index rows, Eigen::Index cols, bool matrix) {
  const auto dim = [](Eigen::Index n) { return n < 0 ? std::string("n") : std::to_string(n); };
  if (!matrix) return "(" + dim(rows) + ",)";
  return "(" + dim(rows) + ", " + dim(cols) + ")";
}

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    if (i > 0) s += ", ";
    s += std::to_string(a.shape(i));
  }
  if (a.ndim() == 1) s += ",";
  return s + ")";
}

/// A C-contiguous float64 array of the expected shape, or a Python exception naming @p name.
py::array_t<double, py::array::c_style> checked(py::handle object, const char* name,
                                                Eigen::Index rows, Eigen::Index cols, bool matrix) {
  const std::string expected = shape_text(rows, cols, matrix);
  if (object.is_none()) {
    throw py::type_error(std::string(name) + ": expected a float64 array of shape " + expected +
                         ", got None");
  }
  // fast path: already a contiguous float64 array
  if (py::isinstance<py::array_t<double, py::array::c_style>>(object)) {
    auto a = py::reinterpret_borrow<py::array_t<double, py::array::c_style>>(object);
    if ((a.flags() & py::array::c_style) != 0) {
      const bool shape_ok = matrix ? (a.ndim() == 2 && (rows < 0 || a.shape(0) == rows) &&
                                      (cols < 0 || a.shape(1) == cols))
                                   : (a.ndim() == 1 && (rows < 0 || a.shape(0) == rows));
      if (shape_ok) return a;
    }
  }
  py::array a;
  if (py::isinstance<py::array>(object)) {
    a = py::reinterpret_borrow<py::array>(object);
  } else {
    // lists, tuples, scalars: NumPy decides what they are
    try {
      a = py::module_::import("numpy").attr("asarray")(object);
    } catch (py::error_already_set&) {
      throw py::value_error(std::string(name) + ": expected a float64 array of shape " + expected +
                            ", got an object NumPy cannot read as numbers");
    }
  }
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::value_error(std::string(name) + ": expected a float64 array of shape " + expected +
                          ", got dtype " + py::str(a.dtype()).cast<std::string>());
  }
  const bool shape_ok = matrix ? (a.ndim() == 2 && (rows < 0 || a.shape(0) == rows) &&
                                  (cols < 0 || a.shape(1) == cols))
                               : (a.ndim() == 1 && (rows < 0 || a.shape(0) == rows));
  if (!shape_ok) {
    throw py::value_error(std::string(name) + ": expected shape " + expected + ", got " +
                          shape_of(a));
  }
  // converts the dtype and copies a non-contiguous array (never reads it with wrong strides)
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

}  // namespace

Eigen::VectorXd to_vector(py::handle object, const char* name, Eigen::Index size) {
  const auto a = checked(object, name, size, 0, false);
  Eigen::VectorXd v(a.shape(0));
  if (v.size() > 0) std::memcpy(v.data(), a.data(), sizeof(double) * static_cast<size_t>(v.size()));
  return v;
}

Eigen::MatrixXd to_matrix(py::handle object, const char* name, Eigen::Index rows,
                          Eigen::Index cols) {
  const auto a = checked(object, name, rows, cols, true);
  Eigen::MatrixXd M(a.shape(0), a.shape(1));
  // NumPy is row major, Eigen's default column major
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = 0; j < M.cols(); ++j) M(i, j) = a.at(i, j);
  return M;
}

py::array_t<double> to_array(const double* values, Eigen::Index size) {
  py::array_t<double> a(size);
  if (size > 0) std::memcpy(a.mutable_data(), values, sizeof(double) * static_cast<size_t>(size));
  return a;
}

py::array_t<double> readonly_view(const double* data, Eigen::Index size, py::handle owner) {
  py::array_t<double> a({size}, {static_cast<py::ssize_t>(sizeof(double))}, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array_t<double> writable_view(double* data, Eigen::Index size, py::handle owner) {
  return py::array_t<double>({size}, {static_cast<py::ssize_t>(sizeof(double))}, data, owner);
}

namespace {
thread_local std::exception_ptr callback_error;
}

void keep_callback_error(std::exception_ptr error) noexcept {
  if (!callback_error) callback_error = std::move(error);  // the first one is the cause
}

void raise_callback_error() {
  if (callback_error) {
    std::exception_ptr e = std::move(callback_error);
    callback_error = nullptr;
    std::rethrow_exception(e);
  }
}

void clear_callback_error() noexcept { callback_error = nullptr; }

}  // namespace mjarm::python
