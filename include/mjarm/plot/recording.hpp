#pragma once
/// @file
/// `Recording`: a directory written by `Recorder` (sim/recorder.hpp), loaded for plotting —
/// state.csv, task.csv, events.csv and summary.json, with errors that name the file and column.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/plot/csv_table.hpp"

namespace mjarm::plot {

/// One row of events.csv.
struct RecordedEvent {
  double t = 0.0;       ///< simulated time [s]
  std::string kind;     ///< "phase", "result", "warning", …
  std::string message;  ///< for a phase: its name
};

/// One actuator as summary.json lists it.
struct RecordedActuator {
  std::string name;   ///< the `force.<name>` column of state.csv
  std::string joint;  ///< joint it drives (empty when not a joint transmission)
  double gear = 1.0;  ///< joint torque = gear · actuator force
  /// Range of the actuator force [N m or N, before the gear]; empty when unbounded or when the
  /// recording predates the field.
  std::optional<std::pair<double, double>> force_range;
};

/// How `Recording::load` reads state.csv and task.csv.
enum class TableRows {
  read,         ///< whole, into `state()` and `task()`
  header_only,  ///< their header rows only (`state()` and `task()` hold no rows): the caller
                ///< streams the rows (`CsvRowReader`), a recording of any length in bounded memory
};

/// A complete recording, read whole (or but for its two long tables: `TableRows::header_only`).
class Recording {
 public:
  /// Loads the recording in @p directory. With `TableRows::header_only` an empty state.csv or
  /// task.csv is not detected here (the caller streaming it sees it), and a summary without
  /// start_time / end_time gives NaN for them.
  /// @throws Error when the directory is missing or not a directory, when one of the four
  ///         files is missing (named, with a hint when a .partial-* folder shows an unfinished
  ///         run), when a file is malformed, or when the recording is empty (no task or state
  ///         rows).
  static Recording load(const std::filesystem::path& directory, TableRows rows = TableRows::read);

  const std::filesystem::path& directory() const noexcept { return directory_; }
  const CsvTable& state() const noexcept { return state_; }  ///< state.csv
  const CsvTable& task() const noexcept { return task_; }    ///< task.csv
  const std::vector<RecordedEvent>& events() const noexcept { return events_; }

  const std::string& model() const noexcept { return model_; }    ///< summary: model
  const std::string& status() const noexcept { return status_; }  ///< summary: status
  const std::string& frame() const noexcept { return frame_; }    ///< summary: end-effector frame
  /// summary: the controllers' names, in the order they ran ("osc", "gripper-pd").
  const std::vector<std::string>& controllers() const noexcept { return controllers_; }
  double start_time() const noexcept { return start_time_; }  ///< [s]
  double end_time() const noexcept { return end_time_; }      ///< [s]
  /// The actuators of summary.json (empty for recordings that predate the field).
  const std::vector<RecordedActuator>& actuators() const noexcept { return actuators_; }

  /// The events of @p kind ("phase"), in time order.
  std::vector<RecordedEvent> events_of(const std::string& kind) const;

 private:
  std::filesystem::path directory_;
  CsvTable state_, task_;
  std::vector<RecordedEvent> events_;
  std::string model_, status_, frame_;
  std::vector<std::string> controllers_;
  double start_time_ = 0.0, end_time_ = 0.0;
  std::vector<RecordedActuator> actuators_;
};

}  // namespace mjarm::plot
