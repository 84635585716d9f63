#pragma once
/// @file
/// One interface for every scenario mjarm runs (shelf pick, pick and place, docking, …): its name,
/// its typed parameters (declared fields as data, field_table.hpp), its verdicts and typed
/// metrics, and one run from parameter values to one `TrialOutcome`. The CLI, Python and sweeps
/// are built from it (registry.hpp); docs/scenarios.md.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/field_table.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/sim/run_result.hpp"

namespace mjarm {

/// Which way a metric is better.
enum class Better { lower, higher };

constexpr auto declared_names(const Better*) {
  return std::array{EnumName{Better::lower, "lower"}, EnumName{Better::higher, "higher"}};
}

/// One typed figure a trial reports.
struct MetricInfo {
  std::string name;  ///< "placement_error"
  std::string unit;  ///< "m"; empty when none
  Better better = Better::lower;
  std::string doc;  ///< one line
};

/// What a trial writes besides its figures (none by default).
struct ScenarioOutputs {
  std::filesystem::path record;  ///< recording folder; empty: none
  std::filesystem::path video;   ///< MP4; empty: none
  /// Cameras by name (the scenario's own names, "follow" for one following the tool); empty:
  /// the scenario's default camera. A scenario that films one camera takes at most one.
  std::vector<std::string> cameras;
  int width = 640;    ///< [pixels], even
  int height = 480;   ///< [pixels], even
  double fps = 30.0;  ///< frames per simulated second
};

/// How one trial ended: the run's status, the scenario's verdict and its typed metrics.
struct TrialOutcome {
  std::string scenario;                            ///< the scenario's name
  RunStatus status = RunStatus::duration_reached;  ///< the simulation's account
  std::string verdict;          ///< one of the scenario's verdicts ("held", "misplaced", "seated")
  bool success = false;         ///< the verdict is the scenario's success
  std::string message;          ///< one line: what happened (why it failed)
  double end_time = 0.0;        ///< simulated time at the end [s]
  std::vector<double> metrics;  ///< one per `Scenario::metrics()`, NaN when it did not happen
  nlohmann::ordered_json parameters;          ///< every parameter's value the trial ran with
  std::filesystem::path recording;            ///< the recording folder (empty when not recorded)
  std::string recording_error;                ///< why the recording is incomplete (empty when fine)
  std::vector<std::filesystem::path> videos;  ///< the MP4s written complete
  std::string video_error;                    ///< why a video was not written (empty when fine)
};

/// A scenario: described once, run from parameter values.
class Scenario {
 public:
  virtual ~Scenario() = default;

  virtual std::string_view name() const = 0;  ///< "pick-place"
  virtual std::string_view doc() const = 0;   ///< one line
  /// Every parameter, with its default value, under its name as a command line writes it
  /// ("object-size", "motion.approach-height").
  virtual std::vector<FieldInfo> parameters() const = 0;
  virtual const std::vector<MetricInfo>& metrics() const = 0;
  /// Every verdict a trial can end with, the success first.
  virtual const std::vector<std::string>& verdicts() const = 0;
  /// The default camera of its video, described.
  virtual std::string_view camera() const = 0;

  /// Every parameter's value after @p values (an object of parameter names, dashes or
  /// underscores, to JSON values) are set on the defaults: what a trial with them runs with.
  /// @throws Error naming the scenario and the parameter for an unknown name (with the closest),
  ///         a value of the wrong kind or out of range
  virtual nlohmann::ordered_json resolve(const nlohmann::ordered_json& values) const = 0;

  /// Runs one trial with @p values (see `resolve`). A trial that fails, diverges or is
  /// interrupted is an outcome, not an exception.
  /// @throws Error for bad values, a folder or video that cannot be written, or input the
  ///         scenario refuses before its first step (an unreachable target)
  virtual TrialOutcome run(const nlohmann::ordered_json& values,
                           const ScenarioOutputs& outputs = {}) const = 0;
};

/// The parameter name @p path is written as: underscores as dashes ("object-size").
std::string parameter_name(std::string_view path);

/// One trial's outcome as JSON, the same shape for every scenario: scenario, parameters, status,
/// verdict, success, message, end_time, metrics (by name; null when not happened) and outputs.
nlohmann::ordered_json outcome_json(const Scenario& scenario, const TrialOutcome& outcome);

/// One parameter as JSON: name, kind, unit, range (numbers), names (enums), length, optional,
/// default, doc.
nlohmann::ordered_json parameter_json(const FieldInfo& parameter);

/// The scenario's description as JSON: name, doc, camera, verdicts, metrics and parameters (name,
/// kind, unit, range, names, length, optional, default, doc).
nlohmann::ordered_json scenario_json(const Scenario& scenario);

}  // namespace mjarm
