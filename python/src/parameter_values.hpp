// Parameters between Python and the library's JSON: a scenario's (`mjarm.run_scenario`) and an
// environment task's options (`mjarm.Environment(task, task_options=…)`), checked by the library
// exactly as a command line's or a sweep file's.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bindings.hpp"
#include "mjarm/error.hpp"

namespace mjarm::python {

/// A Python value as JSON: None, bool, int, float, str, or a sequence of them (an array).
inline nlohmann::ordered_json json_of(py::handle value, const std::string& name) {
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<long long>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "tolist") && !py::isinstance<py::str>(value))
    return json_of(value.attr("tolist")(), name);  // NumPy arrays and scalars
  if (py::isinstance<py::sequence>(value)) {
    nlohmann::ordered_json array = nlohmann::ordered_json::array();
    for (py::handle item : value) array.push_back(json_of(item, name));
    return array;
  }
  throw Error("parameter " + name + ": a number, flag, name, sequence of numbers or None, got " +
              std::string(py::str(py::type::of(value).attr("__name__"))));
}

/// A mapping of parameter names to Python values (keywords, a dict) as the JSON object the
/// library reads.
inline nlohmann::ordered_json values_json(const py::dict& values) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [key, value] : values) {
    const std::string name = py::str(key);
    j[name] = json_of(value, name);
  }
  return j;
}

/// JSON as Python values (through the json module: dicts keep their order).
inline py::object python_of(const nlohmann::ordered_json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace mjarm::python
