#pragma once
/// @file
/// `PyController`: a `Controller` whose law is written in Python (subclass `mjarm.Controller`
/// and define `compute(self, data, reference) -> ndarray (n,)`), called by `Simulation` like any
/// C++ controller. The prototyping path: each call takes the GIL and copies the state.
///
/// `Controller::compute` is noexcept: an exception raised by the Python method is kept
/// (`keep_callback_error`) and the command is set to NaN, so the simulation stops the run as
/// `bad_command` at that tick with the state of the last good step; the binding of
/// `Simulation.tick`/`run` then raises the Python exception itself.
#include <limits>
#include <string>

#include "bindings.hpp"
#include "mjarm/control/controller.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm::python {

class PyController : public Controller {
 public:
  PyController(const Chain& chain, CommandKind kind, std::string name)
      : chain_(chain), kind_(kind), name_(std::move(name)) {}

  std::string_view name() const noexcept override { return name_; }
  CommandKind command_kind() const noexcept override { return kind_; }
  const Chain& chain() const noexcept override { return chain_; }

  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override {
    py::gil_scoped_acquire gil;
    py::object handle;
    try {
      const py::function f = py::get_override(static_cast<const Controller*>(this), "compute");
      if (!f)
        throw Error("Controller '" + name_ + "': the subclass defines no compute(data, reference)");
      handle = py::cast(DataHandle(chain_.robot(), const_cast<mjData*>(&data), py::none()));
      const py::object out = f(handle, py::cast(reference, py::return_value_policy::copy));
      command.value = to_vector(out, "Controller.compute result", chain_.size());
    } catch (...) {
      keep_callback_error(std::current_exception());
      command.value.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    // the state was lent for this call only
    if (handle) handle.cast<DataHandle&>().valid = false;
  }

  void reset() noexcept override {
    py::gil_scoped_acquire gil;
    try {
      if (const py::function f = py::get_override(static_cast<const Controller*>(this), "reset"))
        f();
    } catch (...) {
      keep_callback_error(std::current_exception());
    }
  }

 private:
  Chain chain_;
  CommandKind kind_;
  std::string name_;
};

}  // namespace mjarm::python
