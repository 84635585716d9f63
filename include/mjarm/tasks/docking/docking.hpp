#pragma once
/// @file
/// `run_docking`: one peg-in-hole run end to end — scene, plan, simulation under a docking
/// controller, ground-truth samples, metrics and the seating verdict, with an optional
/// recording and video. docs/docking.md.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/render/camera.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/docking/controller.hpp"
#include "mjarm/tasks/docking/monitor.hpp"
#include "mjarm/tasks/docking/scene.hpp"
#include "mjarm/tasks/docking/task.hpp"
#include "mjarm/tasks/run_video.hpp"

namespace mjarm {

/// A video of a docking run (see `RunVideo`).
struct DockingVideo {
  std::filesystem::path path;  ///< MP4 to write (overwritten); empty: no video
  /// "" (default): a free camera close to the socket from the front right; "follow": one
  /// following the peg tip; anything else: a <camera> of the model, by name.
  std::string camera;
  RunVideoOptions options;  ///< size, frame rate, encoding, render options
};

/// The camera called @p camera for the docking scene (see `DockingVideo`).
/// @throws Error for a name that is neither "", "follow" nor a camera of the model (listing the
///         model's cameras).
CameraSpec docking_camera(const DockingScene& scene, std::string_view camera);

/// How to run one docking.
struct DockingOptions {
  DockingControllerOptions controller;  ///< law, force source, gains
  DockingOffset offset;                 ///< the error of the believed socket pose
  DockingMotion motion;                 ///< reference shape and timing, preload
  DockingCriteria criteria;             ///< the seating criteria
  bool joint_friction = false;          ///< the variant with Franka joint friction
  DockingGeometry geometry;             ///< the peg and the socket
  /// A compiled scene to use (shared between runs: its model is immutable); null: built from
  /// `joint_friction` and `geometry`. Its options must then match them.
  std::shared_ptr<const DockingScene> scene;
  double max_acceleration = 1e6;  ///< divergence bound on |q̈| [rad/s²]
  std::filesystem::path record;   ///< recording directory; empty: none
  DockingVideo video;             ///< MP4 of the run; empty path: none
  bool keep_samples = true;       ///< keep every tick's sample in the report (plots)
};

/// How a docking run ended.
enum class DockingOutcome {
  seated,       ///< every seating criterion held
  not_seated,   ///< the run ended as planned, some criterion failed (see the failures)
  diverged,     ///< the simulation diverged
  bad_command,  ///< the controller wrote NaN/inf
  interrupted,  ///< SIGINT/SIGTERM
  /// a miss, then a search past its radius or timeout without the drop: the run ended there
  search_exhausted
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const DockingOutcome*) {
  using E = DockingOutcome;
  return std::array{
      EnumName{E::seated, "seated"},           EnumName{E::not_seated, "not_seated"},
      EnumName{E::diverged, "diverged"},       EnumName{E::bad_command, "bad_command"},
      EnumName{E::interrupted, "interrupted"}, EnumName{E::search_exhausted, "search_exhausted"}};
}

/// What a docking run did.
struct DockingReport {
  DockingPlan plan;
  std::string controller{};  ///< "cic", "hqp-ac", "se3"
  ForceSource source = ForceSource::sensor;
  bool joint_friction = false;
  RunResult run{};
  DockingMetrics metrics{};
  DockingOutcome outcome = DockingOutcome::not_seated;
  double control_period = 0.0;        ///< [s]
  std::int64_t bad_wrench_ticks = 0;  ///< non-finite sensor readings (taken as zero)
  /// hqp-ac: ticks whose main QP failed (least-squares fallback) and whose null-space QP failed
  /// (its step dropped); 0 for the other laws.
  std::int64_t qp_least_squares = 0;
  std::int64_t qp_null_space_dropped = 0;
  int searches = 0;          ///< misses detected (searches started)
  double search_time = 0.0;  ///< time spent searching [s]
  double miss_time = 0.0;    ///< first miss since the start [s] (NaN: none)
  double drop_time = 0.0;    ///< last drop since the start [s] (NaN: none)
  /// First time the tip reached the bottom (depth ≥ full depth − the depth tolerance) [s];
  /// NaN: never.
  double hold_start =
      0.0;  ///< when the hold began since the start [s] (the plan's without a search)
  double seat_time = 0.0;
  std::vector<DockingSample> samples{};  ///< every tick (when `keep_samples`)
  std::filesystem::path recording{};
  std::string recording_error{};  ///< why the recording is incomplete (empty when fine)
  std::filesystem::path video{};
  std::int64_t video_frames = 0;
  std::string video_camera{};
  std::string video_error{};
  bool video_written = false;  ///< the MP4 is complete at its path (an old file is kept if not)
  bool ok() const noexcept { return outcome == DockingOutcome::seated; }
};

/// Builds (or takes) the scene, plans, runs the `DockingTask` under a `DockingController` in a
/// torque-mode `Simulation` (control period = the physics step, 2 ms), samples the ground truth
/// after every tick (`DockingProbe`: the contacts and kinematics of the step just taken, so a
/// sample's time is the start of that step) and judges it (`evaluate_docking`). The recorder
/// and the video open before the first step; the recording gets the phases, a final "result"
/// event, and is finalized with the run's status, also when it diverges or is interrupted.
/// @throws Error for bad options (offset, motion, criteria, gains), a sensor-based controller
///         on a scene without the F/T sensor (naming the site), an unreachable start, a
///         recording directory or a video that cannot be opened; all before the first step.
DockingReport run_docking(const DockingOptions& options);

/// One line with the figures, for the recording's events and logs.
std::string docking_result_line(const DockingReport& report);

}  // namespace mjarm
