// The scenario registry (mjarm/scenarios/): `mjarm.scenarios()`, `mjarm.find_scenario(name)`,
// `mjarm.run_scenario(name, **parameters)` returning a `TrialOutcome`. Parameters go in as
// Python values (keywords with underscores, as the command line's names with dashes) and are
// checked by the library exactly as a command line's or a sweep file's.
#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "parameter_values.hpp"

namespace mjarm::python {

using Json = nlohmann::ordered_json;

void bind_scenarios(py::module_& m) {
  py::class_<ScenarioOutputs>(m, "ScenarioOutputs",
                              "What a trial writes besides its figures (none by default).")
      .def(py::init<>())
      .def_readwrite("record", &ScenarioOutputs::record, "recording folder; '' = none")
      .def_readwrite("video", &ScenarioOutputs::video, "MP4 path; '' = none")
      .def_readwrite("cameras", &ScenarioOutputs::cameras,
                     "camera names; empty = the scenario's default")
      .def_readwrite("width", &ScenarioOutputs::width, "[pixels], even")
      .def_readwrite("height", &ScenarioOutputs::height, "[pixels], even")
      .def_readwrite("fps", &ScenarioOutputs::fps, "frames per simulated second");

  py::class_<TrialOutcome>(m, "TrialOutcome",
                           "How one trial ended: the run's status, the scenario's verdict and its "
                           "typed metrics (the same shape for every scenario).")
      .def_readonly("scenario", &TrialOutcome::scenario, "the scenario's name")
      .def_property_readonly(
          "metrics",
          [](const TrialOutcome& o) {
            return py::dict(python_of(outcome_json(find_scenario(o.scenario), o)["metrics"]));
          },
          "the scenario's metrics by name (None: did not happen); units: Scenario.metrics")
      .def_property_readonly(
          "status", [](const TrialOutcome& o) { return std::string(to_string(o.status)); },
          "the simulation's account")
      .def_readonly("verdict", &TrialOutcome::verdict,
                    "one of the scenario's verdicts (\"held\", \"misplaced\", \"seated\")")
      .def_readonly("success", &TrialOutcome::success, "the verdict is the scenario's success")
      .def_readonly("message", &TrialOutcome::message, "one line: what happened (why it failed)")
      .def_readonly("end_time", &TrialOutcome::end_time, "simulated time at the end [s]")
      .def_readonly("recording", &TrialOutcome::recording,
                    "the recording folder (empty when not recorded)")
      .def_readonly("recording_error", &TrialOutcome::recording_error,
                    "why the recording is incomplete (empty when fine)")
      .def_readonly("videos", &TrialOutcome::videos, "the MP4s written complete")
      .def_readonly("video_error", &TrialOutcome::video_error,
                    "why a video was not written (empty when fine)")
      .def_property_readonly(
          "parameters", [](const TrialOutcome& o) { return py::dict(python_of(o.parameters)); },
          "every parameter's value the trial ran with, by name")
      .def("__bool__", [](const TrialOutcome& o) { return o.success; });

  py::class_<Scenario, std::unique_ptr<Scenario, py::nodelete>>(
      m, "Scenario", "A scenario of the registry: its parameters, metrics and verdicts.")
      .def_property_readonly(
          "name", [](const Scenario& s) { return std::string(s.name()); },
          "the scenario's name (as `mjarm run` takes it)")
      .def_property_readonly(
          "doc", [](const Scenario& s) { return std::string(s.doc()); },
          "one line on what the scenario does")
      .def_property_readonly(
          "camera", [](const Scenario& s) { return std::string(s.camera()); },
          "the scenario's default camera")
      .def_property_readonly("verdicts", &Scenario::verdicts, "the success first")
      .def_property_readonly(
          "metrics",
          [](const Scenario& s) { return py::list(python_of(scenario_json(s)["metrics"])); },
          "list of {name, unit, better, doc}")
      .def_property_readonly(
          "parameters",
          [](const Scenario& s) { return py::list(python_of(scenario_json(s)["parameters"])); },
          "list of {name, kind, unit, range, names, length, optional, default, doc}")
      .def(
          "resolve",
          [](const Scenario& s, const py::kwargs& values) {
            return py::dict(python_of(s.resolve(values_json(values))));
          },
          "Every parameter's value after the keywords are set on the defaults (checked).")
      .def("__repr__",
           [](const Scenario& s) { return "<mjarm.Scenario '" + std::string(s.name()) + "'>"; });

  m.def(
      "scenarios",
      [] {
        py::list list;
        for (const Scenario* s : scenarios())
          list.append(py::cast(s, py::return_value_policy::reference));
        return list;
      },
      "Every scenario of the registry, in the order `mjarm run --list` shows them.");
  m.def("find_scenario", &find_scenario, py::arg("name"), py::return_value_policy::reference,
        "The scenario called name (an unknown name raises with the closest).");
  m.def(
      "run_scenario",
      [](const std::string& name, const ScenarioOutputs* outputs, const py::kwargs& values) {
        const Scenario& scenario = find_scenario(name);
        const Json j = values_json(values);
        const ScenarioOutputs given = outputs != nullptr ? *outputs : ScenarioOutputs{};
        py::gil_scoped_release release;
        return scenario.run(j, given);
      },
      py::arg("name"), py::kw_only(), py::arg("outputs") = py::none(),
      "Runs one trial of the scenario called name with the keyword parameters (names with "
      "underscores; nested ones as 'motion.approach_height' through **{...}); returns its "
      "TrialOutcome. The GIL is released while it runs.");
}

}  // namespace mjarm::python
