#pragma once
/// @file
/// What the binding files share: the module's pieces (one `bind_<room>` per room of the
/// library), the `Data` handle that lends an `mjData` to Python safely (data_handle.hpp), the
/// user's mujoco objects (mujoco_interop.hpp), and the conversions.
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
#include "mujoco_interop.hpp"

namespace mjarm::python {

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
void bind_state(py::module_& m);
void bind_trajectory(py::module_& m);
void bind_planning(py::module_& m);
void bind_scene(py::module_& m);
void bind_tasks(py::module_& m);
void bind_render(py::module_& m);
void bind_teleop(py::module_& m);
void bind_env(py::module_& m);
void bind_scenarios(py::module_& m);
void bind_web(py::module_& m);

}  // namespace mjarm::python
