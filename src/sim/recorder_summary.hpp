#pragma once
// The JSON summary of a recording (summary.json), written by hand: a handful of fields.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace mjarm::sim_detail {

struct SummaryInfo {
  struct ControllerInfo {
    std::string name;
    std::string command;  // "torque" or "position"
    std::vector<std::string> joints;
  };
  struct Saturation {
    std::string actuator;
    std::int64_t ticks = 0;
  };
  /// One actuator and the range of its scalar force (the state.csv `force.<actuator>` column).
  struct Actuator {
    std::string name, kind, joint;  // joint empty when the transmission is not a joint
    double gear = 1.0;
    bool force_limited = false;  // false: no finite range is known
    double force_lower = 0.0, force_upper = 0.0;
  };
  struct File {
    std::string layer;
    std::string name;
    int columns = 0;
  };
  std::string model, source, mode, integrator, frame;
  double timestep = 0.0, control_period = 0.0;
  int steps_per_tick = 1, state_decimation = 1;
  double start_time = 0.0, end_time = 0.0;
  std::int64_t state_rows = 0, task_rows = 0, event_rows = 0;
  std::string status, message, write_error;
  std::vector<ControllerInfo> controllers;
  std::vector<Saturation> saturation;
  std::vector<Actuator> actuators;
  std::vector<File> files;
};

/// The summary as a JSON document.
std::string summary_json(const SummaryInfo& info);

/// Writes summary_json(info) to @p path and syncs it (every write checked).
/// @throws Error "cannot write '<path>': <reason>" when it cannot be created or written.
void write_summary(const std::filesystem::path& path, const SummaryInfo& info);

}  // namespace mjarm::sim_detail
