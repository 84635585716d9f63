#include "spec_support.hpp"

namespace mjarm::python {

SimulationMode simulation_mode_named(std::string_view name) {
  if (name == "kinematic") return SimulationMode::kinematic;
  if (name == "position") return SimulationMode::position;
  if (name == "torque") return SimulationMode::torque;
  throw Error("unknown simulation mode '" + std::string(name) +
              "'; choices: kinematic, position, torque");
}

bool in_python_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace mjarm::python
