#pragma once
/// @file
/// The user's own `mujoco.MjModel` and `mujoco.MjData` in mjarm's calls, without a copy: both
/// modules run on one MuJoCo library (checked at import, `check_shared_mujoco`), so mjarm reads
/// the very structs the user steps and views. Objects are recognized by type — an instance of
/// the imported `mujoco` module's `MjModel` / `MjData` — and only then is their `_address` read;
/// a bare integer or a look-alike is never trusted.
///
/// Where a binding takes a `Robot` it also takes a `mujoco.MjModel`, and where it takes a `Data`
/// a `mujoco.MjData`: the two `type_caster` specializations below convert them per call (their
/// signatures read "Robot | mujoco.MjModel", "Data | mujoco.MjData"). Anything else fails to
/// convert, and pybind11's TypeError names the types the call accepts.
#include <pybind11/pybind11.h>

#include <optional>

#include "data_handle.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::python {

namespace py = pybind11;

/// Imports `mujoco` and refuses (ImportError naming both) a second MuJoCo library in the
/// process: the library mjarm calls must be the one the `mujoco` package's extension calls, and
/// of the version mjarm was compiled with (`check_mujoco_library`). Called once at import.
void check_shared_mujoco();

/// True when @p object is a `mujoco.MjModel` of the imported `mujoco` module.
bool is_mujoco_model(py::handle object);
/// True when @p object is a `mujoco.MjData` of the imported `mujoco` module.
bool is_mujoco_data(py::handle object);

/// A `Robot` sharing the user's `mujoco.MjModel` @p model (shared ownership: the robot and its
/// copies keep the Python object alive, and the last one releases it with the GIL held).
/// @throws py::type_error when @p model is not a `mujoco.MjModel`; Error for a non-finite model.
Robot robot_from_mujoco(py::handle model);

/// A user-kind `DataHandle` borrowing the user's `mujoco.MjData` @p data.
/// @throws py::type_error when @p data is not a `mujoco.MjData`.
DataHandle data_from_mujoco(py::handle data);

inline int any_object(PyObject* /*object*/) { return 1; }

/// The parameter of `Robot(model)`: any object converts to it, so that the constructor's own
/// check names what it got; signatures call it `mujoco.MjModel`.
class ModelArgument : public py::object {
 public:
  PYBIND11_OBJECT_DEFAULT(ModelArgument, py::object, any_object)
};

/// The parameter of `Data(data)`, as `ModelArgument`; signatures call it `mujoco.MjData`.
class DataArgument : public py::object {
 public:
  PYBIND11_OBJECT_DEFAULT(DataArgument, py::object, any_object)
};

}  // namespace mjarm::python

namespace pybind11::detail {

template <>
struct handle_type_name<mjarm::python::ModelArgument> {
  static constexpr auto name = const_name("mujoco.MjModel");
};
template <>
struct handle_type_name<mjarm::python::DataArgument> {
  static constexpr auto name = const_name("mujoco.MjData");
};

/// `Robot` arguments: an `mjarm.Robot`, or a `mujoco.MjModel` shared for the call.
template <>
struct type_caster<mjarm::Robot> : type_caster_base<mjarm::Robot> {
  static constexpr auto name =
      io_name("mjarm._mjarm.Robot | mujoco.MjModel", "mjarm._mjarm.Robot");

  bool load(handle source, bool convert) {
    if (type_caster_base<mjarm::Robot>::load(source, convert)) return true;
    if (!convert || !mjarm::python::is_mujoco_model(source)) return false;
    shared_.emplace(mjarm::python::robot_from_mujoco(source));
    value = &*shared_;
    return true;
  }

 private:
  std::optional<mjarm::Robot> shared_;
};

/// `Data` arguments: an `mjarm.Data`, or a `mujoco.MjData` borrowed for the call.
template <>
struct type_caster<mjarm::python::DataHandle> : type_caster_base<mjarm::python::DataHandle> {
  static constexpr auto name = io_name("mjarm._mjarm.Data | mujoco.MjData", "mjarm._mjarm.Data");

  bool load(handle source, bool convert) {
    if (type_caster_base<mjarm::python::DataHandle>::load(source, convert)) return true;
    if (!convert || !mjarm::python::is_mujoco_data(source)) return false;
    borrowed_.emplace(mjarm::python::data_from_mujoco(source));
    value = &*borrowed_;
    return true;
  }

 private:
  std::optional<mjarm::python::DataHandle> borrowed_;
};

}  // namespace pybind11::detail
