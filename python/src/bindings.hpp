#pragma once
/// @file
/// What the binding files share: the module's pieces (one `bind_<room>` per room of the
/// library), the `Data` handle that lends an `mjData` to Python safely, and the conversions.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <exception>
#include <string>

#include "convert.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::python {

/// An `mjData` lent to Python. Three kinds, by who owns the memory:
/// - owned (`Robot.make_data()`): the handle owns it; arrays are writable views into it;
/// - a simulation's (`Simulation.data`): `owner` is the Python `Simulation`, kept alive by the
///   handle; arrays are read-only views (write state through `Simulation.set_state`);
/// - a call's (the `data` a Python controller or reference source receives): valid only during
///   the call (`valid` is cleared after it); arrays are copies, and any use after the call is an
///   `mjarm.Error` instead of a read of freed memory.
struct DataHandle {
  Robot robot;    ///< keeps the model alive
  DataPtr owned;  ///< set for an owned handle
  mjData* data = nullptr;
  py::object owner;   ///< the simulation, for a simulation's handle
  bool valid = true;  ///< false once a call's handle has outlived the call

  DataHandle(const Robot& r, DataPtr d) : robot(r), owned(std::move(d)), data(owned.get()) {}
  DataHandle(const Robot& r, mjData* d, py::object o) : robot(r), data(d), owner(std::move(o)) {}

  /// The data; throws when a call's handle is used after its call.
  mjData& get() const {
    if (!valid || data == nullptr) {
      throw Error(
          "mjarm.Data: this state was lent for one call (a controller's compute or a reference "
          "source) and that call has ended; copy the arrays you need during the call");
    }
    return *data;
  }
  const mjModel& model() const noexcept { return robot.model(); }
  /// True for a call's handle: arrays are copies.
  bool borrowed() const noexcept { return !owned && owner.is_none(); }
};

/// Python exceptions raised inside a callback the library calls from a noexcept loop (an IK
/// iteration observer, a Python controller, a reference source) are kept here, per thread, and
/// raised again by the binding once the library call returned.
void keep_callback_error(std::exception_ptr error) noexcept;
/// Raises the kept error, if any (call with the GIL held).
void raise_callback_error();
/// Forgets a kept error (before a call).
void clear_callback_error() noexcept;

/// A property of a float64 vector member, converted and checked like any argument (any size;
/// the library checks sizes where it knows them).
template <typename T, typename Class>
void vector_property(Class& cls, const char* name, Eigen::VectorXd T::*member, const char* doc) {
  cls.def_property(
      name, [member](const T& o) { return Eigen::VectorXd(o.*member); },
      [member, name](T& o, py::handle v) { o.*member = to_vector(v, name); }, doc);
}

/// A property of a fixed-size Eigen member (Vector3d, Vector6d, Matrix6d, ...).
template <typename T, typename Class, typename M>
void fixed_property(Class& cls, const char* name, M T::*member, const char* doc) {
  cls.def_property(
      name, [member](const T& o) { return M(o.*member); },
      [member, name](T& o, py::handle v) {
        if constexpr (M::ColsAtCompileTime == 1) {
          o.*member = to_vector(v, name, M::RowsAtCompileTime);
        } else {
          o.*member = to_matrix(v, name, M::RowsAtCompileTime, M::ColsAtCompileTime);
        }
      },
      doc);
}

/// Pose from a `Pose` or a 4×4 homogeneous matrix; `None` and other shapes are refused.
Pose to_pose(py::handle object, const char* name);

void bind_model(py::module_& m);
void bind_lie(py::module_& m);
void bind_kinematics(py::module_& m);
void bind_ik(py::module_& m);
void bind_dynamics(py::module_& m);
void bind_control(py::module_& m);
void bind_sim(py::module_& m);
void bind_trajectory(py::module_& m);
void bind_planning(py::module_& m);
void bind_scene(py::module_& m);
void bind_tasks(py::module_& m);
void bind_render(py::module_& m);
void bind_env(py::module_& m);

}  // namespace mjarm::python
