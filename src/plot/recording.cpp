#include "mjarm/plot/recording.hpp"

#include <algorithm>
#include <cerrno>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "json_document.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

bool has_partial_folder(const fs::path& directory) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory, ec))
    if (entry.path().filename().string().rfind(".partial-", 0) == 0) return true;
  return false;
}

// The keys the recorder writes (sim/recorder_summary.cpp); the plot tests read real recordings,
// so a key the recorder gains and this list lacks fails them.
// clang-format off
const std::vector<std::string> kSummaryKeys = {
    "invocation", "model", "source", "mode", "integrator", "timestep", "control_period",
    "steps_per_tick", "state_decimation", "frame", "status", "message", "write_error",
    "start_time", "end_time", "duration", "counts", "controllers", "saturated_ticks",
    "actuators", "files"};
// clang-format on
const std::vector<std::string> kControllerKeys = {"name", "command", "joints"};
const std::vector<std::string> kActuatorKeys = {"name", "kind", "joint", "gear", "force_range"};

// Strict JSON, no key twice, and no key the recorder does not write: a misspelt key of a summary
// edited by hand ("gera") would leave its value unused without a word.
nlohmann::json read_summary(const fs::path& path) {
  const JsonDocument json(read_user_file(path, "recording summary"), quoted(path));
  const nlohmann::json& root = json.root();
  if (!root.is_object()) throw Error(quoted(path) + " is not a JSON object");
  json.check_keys("", kSummaryKeys, "the summary");
  for (const auto& [list, keys] :
       {std::pair{"controllers", &kControllerKeys}, std::pair{"actuators", &kActuatorKeys}}) {
    const auto it = root.find(list);
    if (it == root.end() || !it->is_array()) continue;
    for (std::size_t k = 0; k < it->size(); ++k)
      if ((*it)[k].is_object())
        json.check_keys(std::string("/") + list + "/" + std::to_string(k), *keys,
                        std::string(list) + " entry " + std::to_string(k));
  }
  return root;
}

// a value as JSON text for a message, cut after 60 characters
std::string shown(const nlohmann::json& value) {
  const std::string text = value.dump();
  return text.size() <= 60 ? text : text.substr(0, 60) + "…";
}

/// The value of @p key, @p fallback when it is absent or null.
/// @throws Error naming @p summary and the key when it holds a value of another type (a gear
///         of "2" would otherwise scale the torques by 1 without a word).
template <typename T>
T field_or(const nlohmann::json& j, const char* key, T fallback, const fs::path& summary) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return fallback;
  try {
    return it->get<T>();
  } catch (const nlohmann::json::exception&) {
    throw Error(quoted(summary) + ": key '" + key + "' holds " + it->type_name() + " " +
                shown(*it) + ", expected " +
                (std::is_same_v<T, std::string> ? "a string" : "a number"));
  }
}

}  // namespace

Recording Recording::load(const fs::path& directory, TableRows rows) {
  std::error_code ec;
  const fs::file_status status = fs::status(directory, ec);
  if (ec.value() == ELOOP)
    throw Error("recording " + quoted(directory) +
                " is a symbolic link loop (ELOOP: too many levels of symbolic links)");
  if (!fs::exists(status))
    throw Error("recording " + quoted(directory) +
                " does not exist (make one with `mjarm run … --record DIR`)");
  if (!fs::is_directory(directory, ec))
    throw Error("recording " + quoted(directory) +
                " is not a directory (expected the folder written by --record)");
  for (const char* name : {"summary.json", "state.csv", "task.csv", "events.csv"}) {
    if (fs::exists(directory / name, ec)) continue;
    std::string hint;
    if (has_partial_folder(directory))
      hint = "; a .partial-* folder holds the rows of a run that did not finish";
    throw Error("recording " + quoted(directory) + " has no " + name +
                " (not a complete recording" + hint + ")");
  }

  Recording r;
  r.directory_ = directory;
  const bool whole = rows == TableRows::read;
  r.state_ = whole ? CsvTable::read(directory / "state.csv")
                   : CsvTable::read_header(directory / "state.csv");
  r.task_ = whole ? CsvTable::read(directory / "task.csv")
                  : CsvTable::read_header(directory / "task.csv");
  const CsvTable events = CsvTable::read(directory / "events.csv");
  if (whole && (r.task_.rows() == 0 || r.state_.rows() == 0)) {
    throw Error("recording " + quoted(directory) +
                " is empty: " + (r.task_.rows() == 0 ? "task.csv" : "state.csv") +
                " has no rows (the run never ticked)");
  }
  const std::vector<double> t = events.numbers("t");
  const std::vector<std::string> kinds = events.text("kind");
  const std::vector<std::string> messages = events.text("message");
  for (std::size_t i = 0; i < t.size(); ++i) r.events_.push_back({t[i], kinds[i], messages[i]});
  std::stable_sort(r.events_.begin(), r.events_.end(),
                   [](const RecordedEvent& a, const RecordedEvent& b) { return a.t < b.t; });

  const fs::path summary_path = directory / "summary.json";
  const nlohmann::json summary = read_summary(summary_path);
  r.model_ = field_or<std::string>(summary, "model", "", summary_path);
  r.status_ = field_or<std::string>(summary, "status", "", summary_path);
  r.frame_ = field_or<std::string>(summary, "frame", "", summary_path);
  const std::vector<double> task_t = whole ? r.task_.numbers("t") : std::vector<double>{};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.start_time_ =
      field_or<double>(summary, "start_time", whole ? task_t.front() : nan, summary_path);
  r.end_time_ = field_or<double>(summary, "end_time", whole ? task_t.back() : nan, summary_path);
  const auto controllers = summary.find("controllers");
  if (controllers != summary.end() && controllers->is_array())
    for (const nlohmann::json& c : *controllers)
      r.controllers_.push_back(field_or<std::string>(c, "name", "?", summary_path));
  const auto actuators = summary.find("actuators");
  if (actuators != summary.end() && actuators->is_array()) {
    for (const nlohmann::json& a : *actuators) {
      RecordedActuator actuator;
      actuator.name = field_or<std::string>(a, "name", "", summary_path);
      actuator.joint = field_or<std::string>(a, "joint", "", summary_path);
      actuator.gear = field_or<double>(a, "gear", 1.0, summary_path);
      const auto range = a.find("force_range");
      if (range != a.end() && !range->is_null()) {
        if (!range->is_array() || range->size() != 2 || !(*range)[0].is_number() ||
            !(*range)[1].is_number())
          throw Error(quoted(summary_path) + ": key 'force_range' holds " + shown(*range) +
                      ", expected [lower, upper] in N or N·m");
        actuator.force_range = std::make_pair((*range)[0].get<double>(), (*range)[1].get<double>());
      }
      r.actuators_.push_back(std::move(actuator));
    }
  }
  return r;
}

std::vector<RecordedEvent> Recording::events_of(const std::string& kind) const {
  std::vector<RecordedEvent> out;
  for (const RecordedEvent& e : events_)
    if (e.kind == kind) out.push_back(e);
  return out;
}

}  // namespace mjarm::plot
