#include "mujoco_interop.hpp"

#include <dlfcn.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "mjarm/model/mujoco_library.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm::python {
namespace {

/// The imported `mujoco` module's MjModel and MjData types, looked up once (never released: the
/// module outlives every call).
struct MujocoTypes {
  py::object model;
  py::object data;
};

const MujocoTypes& mujoco_types() {
  PYBIND11_CONSTINIT static py::gil_safe_call_once_and_store<MujocoTypes> storage;
  return storage
      .call_once_and_store_result([] {
        const py::module_ mujoco = py::module_::import("mujoco");
        return MujocoTypes{mujoco.attr("MjModel"), mujoco.attr("MjData")};
      })
      .get_stored();
}

std::string python_type_name(py::handle object) {
  const py::handle type = py::type::handle_of(object);
  return py::str(type.attr("__module__")).cast<std::string>() + "." +
         py::str(type.attr("__qualname__")).cast<std::string>();
}

std::string address_text(const void* address) {
  char text[32];
  std::snprintf(text, sizeof(text), "%p", address);
  return text;
}

bool is_instance_of(py::handle object, const py::object& type) {
  const int result = PyObject_IsInstance(object.ptr(), type.ptr());
  if (result < 0) throw py::error_already_set();
  return result == 1;
}

/// The struct behind a recognized object (`_address`, an int), refused when null.
void* address_of(py::handle object, const char* what) {
  const py::object address = object.attr("_address");
  void* pointer = PyLong_AsVoidPtr(address.ptr());
  if (pointer == nullptr) {
    if (PyErr_Occurred() != nullptr) throw py::error_already_set();
    throw Error(std::string(what) + " has no struct behind it (its _address is 0)");
  }
  return pointer;
}

/// The library file that holds @p address, resolved (symlinks followed) for comparison.
std::filesystem::path library_holding(const void* address) {
  Dl_info info;
  if (dladdr(address, &info) == 0 || info.dli_fname == nullptr) return {};
  std::error_code ec;
  std::filesystem::path path = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? std::filesystem::path(info.dli_fname) : path;
}

}  // namespace

void check_shared_mujoco() {
  try {
    check_mujoco_library();
  } catch (const Error& e) {
    throw py::import_error(std::string("mjarm: ") + e.what());
  }
  const py::module_ functions = py::module_::import("mujoco._functions");
  const std::string extension = py::str(functions.attr("__file__")).cast<std::string>();
  // the mj_versionString the mujoco package's extension calls: dlsym searches that extension and
  // then its dependencies, as the loader bound them
  void* handle = dlopen(extension.c_str(), RTLD_LAZY | RTLD_NOLOAD);
  void* theirs = handle != nullptr ? dlsym(handle, "mj_versionString") : nullptr;
  if (handle != nullptr) dlclose(handle);
  if (theirs == nullptr) {
    throw py::import_error("mjarm: cannot find which MuJoCo library the mujoco package (" +
                           extension + ") uses");
  }
  using VersionString = const char* (*)();
  const auto version = reinterpret_cast<VersionString>(theirs);
  const std::filesystem::path their_library = library_holding(version());
  const std::filesystem::path our_library = library_holding(mj_versionString());
  if (their_library != our_library) {
    throw py::import_error(
        "mjarm: two MuJoCo libraries are loaded: mjarm uses " + our_library.string() + " (" +
        mj_versionString() + ") but the mujoco package uses " + their_library.string() + " (" +
        version() + "); mujoco.MjModel and mujoco.MjData cannot be shared between them. Build "
        "mjarm against the mujoco package it runs with (configure CMake with "
        "MJARM_PYTHON_EXECUTABLE set to this interpreter, or MUJOCO_ROOT=" +
        their_library.parent_path().string() + ")");
  }
  mujoco_types();
}

bool is_mujoco_model(py::handle object) {
  return is_instance_of(object, mujoco_types().model);
}

bool is_mujoco_data(py::handle object) {
  return is_instance_of(object, mujoco_types().data);
}

Robot robot_from_mujoco(py::handle model) {
  if (!is_mujoco_model(model))
    throw py::type_error("expected a mujoco.MjModel, got " + python_type_name(model));
  const auto* m = static_cast<const mjModel*>(address_of(model, "mujoco.MjModel"));
  // the robot's copies share one reference to the Python object; the last releases it
  PyObject* keep = model.inc_ref().ptr();
  std::shared_ptr<const mjModel> shared(m, [keep](const mjModel*) {
    if (Py_IsInitialized() == 0) return;  // the interpreter is gone, and the object with it
    const py::gil_scoped_acquire gil;
    Py_DECREF(keep);
  });
  return Robot::from_model(std::move(shared), "mujoco.MjModel at " + address_text(m));
}

DataHandle data_from_mujoco(py::handle data) {
  if (!is_mujoco_data(data))
    throw py::type_error("expected a mujoco.MjData, got " + python_type_name(data));
  auto* d = static_cast<mjData*>(address_of(data, "mujoco.MjData"));
  py::object model = data.attr("model");
  if (!is_mujoco_model(model))
    throw py::type_error("mujoco.MjData.model: expected a mujoco.MjModel, got " +
                         python_type_name(model));
  const auto* m = static_cast<const mjModel*>(address_of(model, "mujoco.MjData.model"));
  return DataHandle(m, d, py::reinterpret_borrow<py::object>(data), std::move(model));
}

std::string model_label(const Robot& robot) {
  return "'" + robot.name() + "' (" + robot.source() + ")";
}

std::string DataHandle::model_label() const {
  if (robot) return python::model_label(*robot);
  return "'" + model_name(*model_ptr) + "' (mujoco.MjModel at " + address_text(model_ptr) + ")";
}

mjData& data_of(const mjModel& model, const std::string& label, const DataHandle& h,
                const char* call) {
  if (&h.model() != &model) {
    throw Error(std::string(call) + ": the data belongs to model " + h.model_label() +
                ", not to " + label +
                " (mjarm compares the models themselves, not their names: pass data made for "
                "that model)");
  }
  return h.get();
}

mjData& data_of(const Robot& robot, const DataHandle& h, const char* call, const char* role) {
  return data_of(robot.model(), std::string(role) + " " + model_label(robot), h, call);
}

}  // namespace mjarm::python
