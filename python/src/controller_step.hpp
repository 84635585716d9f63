#pragma once
/// @file
/// `Controller.compute(data, reference, out=None)`: one control tick from Python, the binding's
/// hot path (docs/python.md, "Overhead of a binding call"). What it avoids per call:
/// - a heap-allocated command: the tick writes into a per-thread command reused across calls
///   (re-entrant: a Python controller calling another controller's compute inside its own
///   finishes with the command before the outer call reads it);
/// - pybind11's Eigen return path (a heap copy of the vector wrapped in a capsule): the result is
///   a NumPy array made directly by NumPy's C API, or written into `out`;
/// - the derived-to-base search of the `self` argument: every C++ controller class binds its
///   own `compute` (`bind_compute<C>`), so `self` matches its type exactly.
/// A C++ controller is never called through the Python trampoline (`PyController`): that is
/// only the class of Python subclasses.
#include <cstring>
#include <string>

#include "bindings.hpp"
#include "mjarm/control/controller.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm::python {

/// The command a tick writes into: this thread's, sized @p n, zeroed.
inline JointCommand& step_command(CommandKind kind, Eigen::Index n) {
  thread_local JointCommand command{CommandKind::torque, Eigen::VectorXd()};
  if (command.value.size() != n) command.value.resize(n);
  command.value.setZero();
  command.kind = kind;
  return command;
}

/// A new float64 array (n,) holding @p values (NumPy's C API, no intermediate containers).
inline py::array_t<double> new_vector(const double* values, Eigen::Index n) {
  auto& api = py::detail::npy_api::get();
  Py_intptr_t dims[1] = {static_cast<Py_intptr_t>(n)};
  PyObject* descr = api.PyArray_DescrFromType_(py::detail::npy_api::NPY_DOUBLE_);
  PyObject* a =
      api.PyArray_NewFromDescr_(api.PyArray_Type_, descr, 1, dims, nullptr, nullptr, 0, nullptr);
  if (a == nullptr) throw py::error_already_set();
  if (n > 0) {
    std::memcpy(py::detail::array_proxy(a)->data, values, sizeof(double) * static_cast<size_t>(n));
  }
  return py::reinterpret_steal<py::array_t<double>>(a);  // no check: it is one
}

/// Writes @p values into @p out, which must be a writable, contiguous float64 array (n,);
/// anything else is a `ValueError` naming `out` (never a silent copy the caller would not see).
inline void write_out(py::handle out, const double* values, Eigen::Index n) {
  auto& api = py::detail::npy_api::get();
  bool ok = api.PyArray_Check_(out.ptr());
  if (ok) {
    const auto* a = py::detail::array_proxy(out.ptr());
    ok = a->nd == 1 && a->dimensions[0] == n && (n == 0 || a->strides[0] == sizeof(double)) &&
         py::detail::array_descriptor_proxy(a->descr)->type_num ==
             py::detail::npy_api::NPY_DOUBLE_ &&
         (a->flags & py::detail::npy_api::NPY_ARRAY_WRITEABLE_) != 0;
  }
  if (!ok) {
    throw py::value_error("out: expected a writable contiguous float64 array of shape (" +
                          std::to_string(n) + ",)");
  }
  if (n > 0) {
    std::memcpy(py::detail::array_proxy(out.ptr())->data, values,
                sizeof(double) * static_cast<size_t>(n));
  }
}

/// One tick of @p c for the state in @p d: a new array (n,), or @p out filled and returned.
template <typename C>
py::array_t<double> controller_step(C& c, const DataHandle& d, const Reference& reference,
                                    py::handle out) {
  const Chain& chain = c.chain();
  const mjData& data = data_of(chain.robot(), d, "compute", "the controller's chain's model");
  JointCommand& command = step_command(c.command_kind(), chain.size());
  c.compute(data, reference, command);
  if (out.is_none()) return new_vector(command.value.data(), command.value.size());
  write_out(out, command.value.data(), command.value.size());
  return py::reinterpret_borrow<py::array_t<double>>(out);  // checked by write_out
}

inline constexpr const char* kComputeDoc =
    "One tick's command (n,) for the state in data (fresh after forward): torques or position "
    "targets in chain order. With out (a writable float64 array (n,)) the command is written "
    "there and out is returned, so a loop allocates nothing.";

/// Binds `compute` on a C++ controller class (self matched exactly, see the file comment).
template <typename C, typename Class>
void bind_compute(Class& cls) {
  cls.def(
      "compute",
      [](C& c, const DataHandle& d, const Reference& reference, py::handle out) {
        return controller_step(c, d, reference, out);
      },
      py::arg("data"), py::arg("reference"), py::arg("out") = py::none(), kComputeDoc);
}

}  // namespace mjarm::python
