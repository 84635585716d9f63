#pragma once
/// @file
/// `DataHandle`, the `mjarm.Data` of Python: an `mjData` lent to Python safely, whoever owns it.
#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::python {

namespace py = pybind11;

/// An `mjData` lent to Python. Four kinds, by who owns the memory:
/// - owned (`Robot.make_data()`): the handle owns it; arrays are writable views into it;
/// - a simulation's (`Simulation.data`): `owner` is the Python `Simulation`, kept alive by the
///   handle; arrays are read-only views (write state through `Simulation.set_state`);
/// - a call's (the `data` a Python controller or reference source receives): valid only during
///   the call (`valid` is cleared after it); arrays are copies, and any use after the call is an
///   `mjarm.Error` instead of a read of freed memory;
/// - the user's (a `mujoco.MjData`, `mujoco_interop.hpp`): borrowed, not copied; `owner` is the
///   `mujoco.MjData` and `model_owner` its `mujoco.MjModel`, both kept alive by the handle;
///   arrays are writable views (the user's own memory). mjarm has no `Robot` for it: the call
///   compares its model with its own robot's (`data_of`).
struct DataHandle {
  enum class Kind { owned, simulation, call, user };

  Kind kind;
  std::optional<Robot> robot;  ///< keeps mjarm's model alive (every kind but the user's)
  const mjModel* model_ptr;    ///< the model the data was made for
  DataPtr owned;               ///< set for an owned handle
  mjData* data = nullptr;
  py::object owner;        ///< the simulation, or the user's mujoco.MjData
  py::object model_owner;  ///< the user's mujoco.MjModel
  bool valid = true;       ///< false once a call's handle has outlived the call

  DataHandle(const Robot& r, DataPtr d)
      : kind(Kind::owned), robot(r), model_ptr(&r.model()), owned(std::move(d)),
        data(owned.get()) {}
  /// A simulation's (@p o is the simulation) or, with @p o None, a call's.
  DataHandle(const Robot& r, mjData* d, py::object o)
      : kind(o.is_none() ? Kind::call : Kind::simulation), robot(r), model_ptr(&r.model()),
        data(d), owner(std::move(o)) {}
  /// The user's @p d of model @p m, kept alive through @p data_object and @p model_object.
  DataHandle(const mjModel* m, mjData* d, py::object data_object, py::object model_object)
      : kind(Kind::user), model_ptr(m), data(d), owner(std::move(data_object)),
        model_owner(std::move(model_object)) {}

  /// The data; throws when a call's handle is used after its call.
  mjData& get() const {
    if (!valid || data == nullptr) {
      throw Error(
          "mjarm.Data: this state was lent for one call (a controller's compute or a reference "
          "source) and that call has ended; copy the arrays you need during the call");
    }
    return *data;
  }
  const mjModel& model() const noexcept { return *model_ptr; }
  /// True for a call's handle: arrays are copies.
  bool borrowed() const noexcept { return kind == Kind::call; }
  /// True where mjarm may write the data when a call documents it (owned and the user's).
  bool writable() const noexcept { return kind == Kind::owned || kind == Kind::user; }
  /// The model as messages name it: "'panda' (/path/panda.xml)".
  std::string model_label() const;
};

/// @p robot's model as messages name it: "'panda' (/path/panda.xml)", or for a user's model
/// "'arm' (mujoco.MjModel at 0x...)".
std::string model_label(const Robot& robot);

/// The data of @p h for a call on @p model (@p label names it: "the chain's model 'panda' (...)").
/// mjarm compares the models themselves, not their names.
/// @throws Error naming @p call and both models when the data was made for another model, and
///         as `DataHandle::get`.
mjData& data_of(const mjModel& model, const std::string& label, const DataHandle& h,
                const char* call);

/// Same, for @p robot's model, @p role naming it ("the chain's model").
mjData& data_of(const Robot& robot, const DataHandle& h, const char* call,
                const char* role = "the robot's model");

}  // namespace mjarm::python
