#pragma once
/// @file
/// `run_shelf_pick`: the shelf-pick scenario end to end — plan, simulate under a controller,
/// measure, record. See docs/tasks.md for the scenario, its metrics and the measured figures.

#include <cstdint>
#include <filesystem>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/pick_monitor.hpp"
#include "mjarm/tasks/shelf_pick/plan.hpp"
#include "mjarm/tasks/shelf_pick/video.hpp"

namespace mjarm {

/// How to run one shelf pick.
struct ShelfPickOptions {
  ShelfPickRequest request;      ///< robot, controller, pick point, seed, criteria
  std::filesystem::path record;  ///< recording directory; empty: no recording
  /// Control period [s]; 0 = one physics step (2 ms on the bundled models). Must be a whole
  /// multiple of the timestep.
  double control_period = 0.0;
  /// Divergence bound on |q̈| [rad/s²] (`SimulationOptions::max_acceleration`).
  double max_acceleration = 1e6;
  /// Time allowed after the approach for entering the tolerance and holding [s] (> 0): the run
  /// stops at approach_time + settle_time + hold_time at the latest.
  double settle_time = 1.0;
  /// The controller's gains scaled from the tuned ones (`make_shelf_pick_controller`): every
  /// stiffness × s, every damping × √s, so the damping ratio stays (> 0).
  double gain_scale = 1.0;
  int state_decimation = 1;  ///< one state row every N physics steps when recording
  ShelfPickVideo video;      ///< MP4 of the run; empty path: no video
};

/// How a shelf pick ended.
enum class PickOutcome {
  held,         ///< the tip entered the tolerance and held; released
  not_held,     ///< the time limit came first
  diverged,     ///< the simulation diverged (recording kept up to the fault)
  bad_command,  ///< the controller produced NaN/inf
  interrupted   ///< SIGINT/SIGTERM (see mjarm/interrupt.hpp)
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const PickOutcome*) {
  using E = PickOutcome;
  return std::array{EnumName{E::held, "held"}, EnumName{E::not_held, "not_held"},
                    EnumName{E::diverged, "diverged"}, EnumName{E::bad_command, "bad_command"},
                    EnumName{E::interrupted, "interrupted"}};
}

/// What a shelf pick did.
struct ShelfPickReport {
  ShelfPickPlan plan;     ///< robot, chain, pick point, start, targets, approach time
  RunResult run{};        ///< the simulation's account (status, end time, message)
  PickMetrics metrics{};  ///< time to tolerance, overshoot, steady state, hold
  PickOutcome outcome = PickOutcome::not_held;
  PickPhase final_phase = PickPhase::approach;
  double time_limit = 0.0;      ///< simulated time allowed [s]
  double control_period = 0.0;  ///< [s]
  /// The most control ticks any one motor was clipped to its torque limit.
  std::int64_t saturated_ticks = 0;
  std::filesystem::path recording{};  ///< the recording directory (empty when not recorded)
  /// Why the recording could not be completed (a write failed: full disk), naming the file, the
  /// reason and the staging folder that keeps the rows written; empty when it was. Nothing is
  /// then moved into `recording`. The run and its figures are unaffected.
  std::string recording_error{};
  std::filesystem::path video{};  ///< the MP4 written (empty when no video)
  std::int64_t video_frames = 0;  ///< frames in it: ⌊(end − start)·fps⌋ + 1
  std::string video_camera{};     ///< the camera, described (`CameraSpec::describe`)
  /// Why no video was written (ffmpeg died, disk full, the run was interrupted; empty when it
  /// was). The run and its figures are unaffected.
  std::string video_error{};
  /// Whether a complete, playable MP4 of the run is at `video` (false when ffmpeg failed or the
  /// run was interrupted: no video is written then, and an old file at the path keeps its
  /// content).
  bool video_written = false;
  bool ok() const noexcept { return outcome == PickOutcome::held; }
};

/// Plans (`plan_shelf_pick`), builds the simulation in torque mode at the seeded start, runs the
/// `ShelfPickTask` under the chosen controller and returns the figures. With a recording
/// directory, a `Recorder` is opened before the first step (so a directory that cannot be
/// written fails before anything runs), gets the phase events and a final "result" event, and is
/// finalized with the run's status — also when the run diverges. With a video path, a
/// `RunVideo` (camera from `shelf_pick_camera`, the pick point drawn as a green ball) is opened
/// before the recorder and watches every control tick through `ShelfPickTask::set_observer`;
/// the MP4 is finalized with the frames up to the end of the run whatever the outcome (a
/// complete video or none: `video_written`), and the figures are the same as without a video.
/// @throws Error for bad options (see `plan_shelf_pick`, a control period that is not a whole
///         multiple of the timestep, a non-positive settle time or bound), a recording
///         directory that cannot be created or written, or a video that cannot start (see
///         `RunVideo`, `shelf_pick_camera`); all before the first step.
ShelfPickReport run_shelf_pick(const ShelfPickOptions& options);

}  // namespace mjarm
