#pragma once
/// @file
/// What the scene and task bindings share: plain option structs built from keyword arguments
/// (`mjarm.ObjectSpec(name="cube", size=[...])`), `std::array` fields as NumPy arrays with the
/// shape checked like any argument, enum fields that also take their names ("box", "weld"), and
/// long library calls run with the GIL released and Ctrl-C turned into `KeyboardInterrupt`.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/sim/simulation_options.hpp"

namespace mjarm::python {

/// A `T` whose fields are set from @p fields by name, through the bound properties (so every
/// value is converted and checked as when it is assigned); an unknown name is a `TypeError`
/// naming it and @p type.
template <typename T>
T from_fields(const py::kwargs& fields, const char* type, T start = T{}) {
  py::object o = py::cast(std::move(start));
  for (const auto& [key, value] : fields) {
    const std::string name = py::str(key);
    if (name.starts_with("_") || !py::hasattr(o, key)) {
      throw py::type_error(std::string(type) + ": no field '" + name + "'");
    }
    py::setattr(o, key, value);
  }
  return o.cast<T>();
}

/// Binds `T(**fields)`: the default value with the named fields set.
template <typename T, typename Class>
void fields_init(Class& cls, const char* type) {
  cls.def(py::init([type](const py::kwargs& fields) { return from_fields<T>(fields, type); }),
          "Default values, with any field set by keyword.");
}

/// The spec an `add_*`-style call takes: @p spec itself, or the fields as keywords (applied to a
/// copy of @p spec when both are given). `None` without keywords is a `TypeError`.
template <typename T>
T spec_of(const py::object& spec, const py::kwargs& fields, const char* call, const char* type) {
  if (spec.is_none()) {
    if (fields.empty()) {
      throw py::type_error(std::string(call) + ": expected " + type +
                           " or its fields as keywords, got None");
    }
    return from_fields<T>(fields, type);
  }
  if (!py::isinstance<T>(spec)) {
    throw py::type_error(std::string(call) + ": expected " + type + ", got " +
                         py::str(py::type::of(spec).attr("__name__")).cast<std::string>());
  }
  return fields.empty() ? spec.cast<T>() : from_fields<T>(fields, type, spec.cast<T>());
}

/// A `std::array<double, N>` field as a float64 array (N,), set from any array-like of N numbers.
template <typename T, std::size_t N, typename Class>
void array_property(Class& cls, const char* name, std::array<double, N> T::*member,
                    const char* doc) {
  cls.def_property(
      name, [member](const T& o) { return to_array((o.*member).data(), N); },
      [member, name](T& o, py::handle v) {
        const Eigen::VectorXd x = to_vector(v, name, static_cast<Eigen::Index>(N));
        for (std::size_t i = 0; i < N; ++i) (o.*member)[i] = x[static_cast<Eigen::Index>(i)];
      },
      doc);
}

/// A `std::vector<double>` field as a float64 array (n,), set from any array-like of numbers.
template <typename T, typename Class>
void list_property(Class& cls, const char* name, std::vector<double> T::*member, const char* doc) {
  cls.def_property(
      name,
      [member](const T& o) {
        return to_array((o.*member).data(), static_cast<Eigen::Index>((o.*member).size()));
      },
      [member, name](T& o, py::handle v) {
        const Eigen::VectorXd x = to_vector(v, name);
        o.*member = std::vector<double>(x.data(), x.data() + x.size());
      },
      doc);
}

/// An enum field that also takes its name: `parse` maps a string (and throws `mjarm.Error`
/// naming the choices for an unknown one).
template <typename T, typename E, typename Class, typename Parse>
void enum_property(Class& cls, const char* name, E T::*member, Parse parse, const char* doc) {
  cls.def_property(
      name, [member](const T& o) { return o.*member; },
      [member, name, parse](T& o, py::handle v) {
        if (py::isinstance<py::str>(v)) {
          o.*member = parse(v.cast<std::string>());
        } else if (py::isinstance<E>(v)) {
          o.*member = v.cast<E>();
        } else {
          throw py::type_error(
              std::string(name) + ": expected a name or an enum value, got " +
              (v.is_none() ? std::string("None")
                           : py::str(py::type::of(v).attr("__name__")).cast<std::string>()));
        }
      },
      doc);
}

/// `SimulationMode` by name ("kinematic", "position", "torque").
SimulationMode simulation_mode_named(std::string_view name);

/// True in Python's main thread (where a Ctrl-C handler may be installed).
bool in_python_main_thread();

/// Runs @p f with the GIL released. In the main thread a Ctrl-C (or SIGTERM) meanwhile stops the
/// library's run at its next tick (an `InterruptGuard`), and is raised as `KeyboardInterrupt`
/// once it returned.
template <typename F>
auto call_released(F&& f) {
  std::optional<InterruptGuard> guard;
  if (in_python_main_thread()) guard.emplace();
  auto result = [&] {
    py::gil_scoped_release release;
    return f();
  }();
  if (guard && interrupt_requested()) {
    guard.reset();
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  return result;
}

void bind_pick_place(py::module_& m);
void bind_docking(py::module_& m);

}  // namespace mjarm::python
