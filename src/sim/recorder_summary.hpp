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
  /// Who wrote the recording: the program's command line (/proc/self/cmdline), where and when,
  /// the run's seed, and the versions of mjarm and MuJoCo.
  struct Invocation {
    std::vector<std::string> command_line;
    std::string working_directory;
    long pid = 0;
    std::string started;  // UTC, ISO 8601
    bool has_seed = false;
    std::uint64_t seed = 0;
    std::string mjarm_version, mujoco_version;
  };
  Invocation invocation;
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

/// This process's invocation (command line, working directory, PID, the time now, the library
/// versions); @p seed when the run has one.
SummaryInfo::Invocation current_invocation(const std::uint64_t* seed);

/// Writes summary_json(info) to @p path and syncs it (every write checked).
/// @throws Error "cannot write '<path>': <reason>" when it cannot be created or written.
void write_summary(const std::filesystem::path& path, const SummaryInfo& info);

}  // namespace mjarm::sim_detail
