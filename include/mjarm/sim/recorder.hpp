#pragma once
/// @file
/// `Recorder`: streams a run to CSV files plus a JSON summary, and never leaves a recording lost
/// or half-written.
///
/// Layers (one CSV file each, header row of named columns):
/// - state.csv: every physics step, or every N-th (`state_decimation`): `t`, `q.<joint>`,
///   `v.<joint>` (`.k` suffix for each coordinate of free/ball joints), `ctrl.<actuator>`,
///   `force.<actuator>` (MuJoCo's actuator_force: the scalar actuator force, before the gear),
///   `contact.count` (active contacts of the whole model) and `contact.normal_force` (the sum of
///   their normal forces [N]; NaN in kinematic mode, where no constraint forces are computed).
///   Row at time t: qpos/qvel at t, with the ctrl applied and the actuator force produced during
///   the step from t to t + h.
/// - task.csv: every control tick: `t`; the end-effector frame E (`ee.x ee.y ee.z ee.qw ee.qx
///   ee.qy ee.qz`), the reference pose (`ref.*`), the error `err.vx … err.wz` (task_error: world
///   axes, linear first, m and rad); `gripper_ref`; `qref.<joint>` of the first controller's chain
///   (NaN when reference.joint.q does not have that size); per controller `cmd.<ctrl>.<joint>`
///   and `<ctrl>.<internal>`; `sat.<actuator>` (1 when clipped this tick); then the
///   `RecorderOptions::channels` (a task's own figures: grasp force, slip).
/// - events.csv: `t,kind,message` for phase changes, grasps, warnings, divergence, interrupts.
/// - summary.json also lists the actuators: name, kind, joint, gear and `force_range`, the range
///   of the `force.<actuator>` column (forcerange, and gain·ctrlrange for motors; null when
///   unbounded); and first, `invocation`: whose recording it is — the program's command line
///   (its arguments as given, /proc/self/cmdline), working directory, PID, the UTC time the
///   recorder started, the run's seed (`RecorderOptions::seed`, null when none), and the
///   versions of mjarm and MuJoCo.
///
/// One writer per directory: the directory is locked from construction until `finalize` (a
/// hidden `.mjarm-lock` file, flock); a second recorder of it, in this process or another, is
/// refused at construction with an error naming the directory and the first one's PID. The
/// kernel drops the lock of a process that dies, so a killed run never blocks the next.
///
/// Atomicity: every file is written into DIR/.partial-XXXXXX and moved into DIR by `finalize`,
/// summary.json last: a DIR with summary.json holds a complete recording. Every write, flush,
/// sync and close is checked; when one failed (a full disk), `finalize` moves nothing: the rows
/// written so far stay in the .partial folder with a summary.json whose `write_error` names the
/// failure (when the summary itself can still be written), and the error names both. The destructor
/// finalizes a recording that was not finalized, with status "error" when an exception is
/// unwinding, the status of the last `Simulation::run` when there was one, "aborted" otherwise. If
/// the process is killed outright, the rows flushed so far stay in the .partial folder.
///
/// Rows are formatted into preallocated buffers (shortest round-trip decimal) and written through
/// stdio buffers owned by the recorder: recording a row allocates nothing.

#include <cstdint>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/reference.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/sim/run_result.hpp"

namespace mjarm {

class Simulation;

/// An extra task.csv column: a value something else keeps up to date (a grasp monitor's force),
/// read at every control tick after the controllers ran.
struct RecorderChannel {
  std::string name;               ///< column name, e.g. "grasp.force"
  const double* value = nullptr;  ///< read each tick; must outlive the recorder's last row
};

/// Options of a `Recorder`.
struct RecorderOptions {
  int state_decimation = 1;  ///< one state row every N physics steps (≥ 1)
  int flush_rows = 256;      ///< flush each CSV file every N rows (≥ 1); events flush at once
  /// Frame (site or body name) logged as the end effector in task.csv; empty: the frame of the
  /// first controller's chain; no pose columns when there is neither.
  std::string frame;
  /// Extra task.csv columns, after the `sat.*` columns, in this order.
  std::vector<RecorderChannel> channels;
  /// The seed the run was drawn from, for summary.json's `invocation` (none: null).
  std::optional<std::uint64_t> seed;
};

constexpr auto declared_fields(const RecorderOptions*) {
  using S = RecorderOptions;
  return declare<S>(
      "recorder",
      field("state_decimation", &S::state_decimation, "", Range::at_least(1),
            "one state row every N physics steps"),
      field("flush_rows", &S::flush_rows, "", Range::at_least(1), "flush each CSV file every N rows"),
      field("frame", &S::frame, "frame logged as the end effector; empty: the first controller's"));
}

/// Records the run of one `Simulation` into a directory. Build it after the controllers were
/// added to the simulation (their commands and internals are columns), pass it to
/// `Simulation::tick`/`run`, then call `finalize`.
class Recorder {
 public:
  /// Creates @p directory if needed, locks it and makes a staging folder inside it, opens the
  /// CSV files and writes their headers.
  /// @throws Error when the directory cannot be created or written (before anything runs), when
  ///         another recorder is writing it (naming its PID), when the options are out of range
  ///         or the frame is unknown.
  Recorder(const Simulation& simulation, const std::filesystem::path& directory,
           const RecorderOptions& options = {});
  /// Finalizes when not finalized yet: "error" when an exception is unwinding, else the last
  /// run's status (see `on_run_end`), else "aborted". Never throws (problems go to stderr).
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Adds an event row and flushes it. `kind` is a short word ("phase", "grasp", "warning",
  /// "divergence"); commas, quotes and newlines in `message` are quoted. Messages longer than
  /// 1000 bytes are cut.
  void event(double time, std::string_view kind, std::string_view message) noexcept;

  /// Flushes every file now.
  void flush() noexcept;

  /// Closes the files, writes summary.json and moves everything into the directory.
  /// Idempotent: a second call does nothing.
  /// @param status "duration_reached", "finished", "diverged", "interrupted", ... or any word
  /// @param message one line for people (may be empty)
  /// @throws Error when a file could not be written or moved: the message names the file, the
  ///         system's reason and the staging folder, which is kept with the rows written so far
  ///         (nothing is moved into the directory).
  void finalize(std::string_view status, std::string_view message = {});
  /// `finalize(to_string(result.status), result.message)`.
  void finalize(const RunResult& result);

  bool finalized() const noexcept { return finalized_; }
  /// The recording directory (where the files end up).
  const std::filesystem::path& directory() const noexcept;
  /// Final paths of the files: state.csv, task.csv, events.csv, summary.json.
  std::filesystem::path state_path() const;
  std::filesystem::path task_path() const;
  std::filesystem::path events_path() const;
  std::filesystem::path summary_path() const;

  std::int64_t state_rows() const noexcept;
  std::int64_t task_rows() const noexcept;
  std::int64_t event_rows() const noexcept;

  // ---- called by Simulation (the run loop) ----

  /// Counts one physics step and writes a state row every `state_decimation` steps.
  /// @param time, qpos, qvel the state at the start of the step; ctrl/actuator_force are read
  ///        from the simulation's data (this step's values).
  void on_physics_step(const Simulation& simulation, double time, const double* qpos,
                       const double* qvel) noexcept;
  /// Writes one task row (data must hold fresh kinematics).
  void on_control_tick(const Simulation& simulation, const Reference& reference) noexcept;
  /// @throws Error when this recorder was built for another simulation or before a controller
  ///         was added.
  void check_layout(const Simulation& simulation) const;
  /// Remembers how the last run ended: a recorder destroyed without `finalize` (and without an
  /// exception unwinding) then finalizes with that status instead of "aborted".
  void on_run_end(const RunResult& result);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool finalized_ = false;
  int uncaught_at_construction_ = 0;
  std::string last_run_status_;  // empty until a run ended
  std::string last_run_message_;
};

}  // namespace mjarm
