#pragma once
/// @file
/// Recorded teleoperation sessions: what a person (or a script) did to a `TeleopSession`, tick
/// by tick — target changes, mode switches, task changes, resets — so that the session can be
/// replayed headless and gives the same motion bit for bit (the session is deterministic for
/// the same inputs at the same ticks).
///
/// File format (text, one record a line, numbers with 17 significant digits):
///
///     mjarm-teleop-session 1
///     model dual_arm_box
///     fingerprint 26 25 19 9d1f0c2a6b7e4f31   (nq nv nu, FNV-1a of joint and actuator names)
///     hands left:left_tcp right:right_tcp      (name:frame; fingers found on the model)
///     lift lift 0                                  (lift joint, lift_in_ik; "-" for none)
///     keyframe home
///     mode position
///     periods 0.01 0                               (kinematic period, control period [s])
///     tasks pose:0 pose:0
///     events 3
///     0 targets <lift> then per hand: x y z, R_WT row by row (9), gripper
///     250 mode torque
///     900 reset
///     end 1500 <digest of the final qpos and qvel>
///
/// A file that stops before its `end` line, or holds fewer events than it announced, is
/// truncated; one recorded on a model with another fingerprint is refused.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/file_writer.hpp"
#include "mjarm/teleop/teleop_session.hpp"

namespace mjarm {

/// One thing done to a session, before the control tick numbered `tick` (0 = before the first).
struct SessionEvent {
  enum class Kind { targets, mode, task, reset };
  std::int64_t tick = 0;
  Kind kind = Kind::targets;
  TeleopTargets targets;                           ///< targets
  SimulationMode mode = SimulationMode::position;  ///< mode
  int hand = 0;                                    ///< task
  HandTask task;                                   ///< task
};

/// A recorded session.
struct SessionLog {
  std::string model;        ///< model name
  std::string fingerprint;  ///< `model_fingerprint` of the model it ran on
  TeleopOptions options;    ///< hands, lift, keyframe, initial mode, periods, tasks
  std::vector<SessionEvent> events;
  std::int64_t ticks = 0;  ///< control ticks simulated in all
  std::string digest;      ///< `state_digest` of the final state
};

/// "nq nv nu hash": the sizes of @p robot and an FNV-1a hash of its joint and actuator names.
std::string model_fingerprint(const Robot& robot);

/// A 64-bit FNV-1a hash (hex) of the bytes of qpos and qvel of @p session's simulation.
std::string state_digest(const TeleopSession& session);

/// Writes @p log to @p path through `FileWriter`.
/// @throws Error when the file cannot be written (naming it and why).
void write_session_log(const SessionLog& log, const std::filesystem::path& path);

/// Writes @p log to @p out and commits it (a writer opened early, e.g. before a window opens,
/// so that an unwritable path is reported before the session starts).
/// @throws Error when the file cannot be written (naming it and why).
void write_session_log(const SessionLog& log, FileWriter& out);

/// The most control ticks a session may have: 10⁷ (27.8 h at the default 10 ms tick, 5.6 h at a
/// 2 ms one; a replay simulates about 20 000 ticks a second, so 10⁷ take some 8 minutes). A
/// larger tick count in a file is refused when it is read, before any work.
inline constexpr std::int64_t kMaxSessionTicks = 10'000'000;

/// Reads a session file (through `read_user_file`).
/// @throws Error naming the file and line: not a session file, a malformed or unknown record,
///         a number that is not finite, a tick out of order or beyond `kMaxSessionTicks`, or a
///         truncated file (no `end` line, fewer events than announced).
SessionLog read_session_log(const std::filesystem::path& path);

/// Reads session text; @p file names it in errors ("session file 'FILE' line 7: ...").
/// @throws Error as `read_session_log`.
SessionLog parse_session_log(std::string_view text, const std::string& file);

/// A `TeleopSession` whose inputs are recorded: use it in place of the session's own setters.
class SessionRecorder {
 public:
  /// Starts recording @p session from its current state (its model, options and targets).
  explicit SessionRecorder(TeleopSession& session);
  TeleopSession& session() noexcept { return session_; }
  void set_targets(const TeleopTargets& targets);
  void set_mode(SimulationMode mode);
  void set_task(int hand, const HandTask& task);
  void reset();
  /// Simulates @p ticks ticks; returns those done.
  int step(int ticks) noexcept;
  /// The log so far, with the final digest.
  SessionLog log() const;

 private:
  TeleopSession& session_;
  SessionLog log_;
  std::int64_t ticks_ = 0;
};

/// What a replay did.
struct ReplayResult {
  std::int64_t ticks = 0;
  std::string digest;    ///< of the final state
  bool matches = false;  ///< the digest equals the recorded one
  TeleopStats stats;     ///< at the end
};

/// A replay in progress: a new session with the recorded options, the events applied at their
/// ticks. `step` until it returns false; the session can be drawn in between.
class SessionReplay {
 public:
  /// @throws Error when @p robot's fingerprint is not the recorded one (naming both models), or
  ///         the session cannot be built.
  SessionReplay(const Robot& robot, const SessionLog& log);
  const TeleopSession& session() const noexcept { return *session_; }
  /// Applies the events due and simulates one tick; false (nothing done) once every recorded
  /// tick is done or after a fault.
  bool step();
  /// Ticks replayed so far.
  std::int64_t ticks() const noexcept { return tick_; }
  /// The outcome so far (the digest of the current state).
  ReplayResult result() const;

 private:
  const SessionLog& log_;
  std::unique_ptr<TeleopSession> session_;
  std::size_t next_ = 0;
  std::int64_t tick_ = 0;
  bool stopped_ = false;
  void apply_due();
};

/// Replays @p log on @p robot to its end.
/// @throws Error as `SessionReplay`.
ReplayResult replay_session(const Robot& robot, const SessionLog& log);

}  // namespace mjarm
