#pragma once
/// @file
/// The interactive viewer: a GLFW window showing a session with MuJoCo's renderer, a side panel
/// (viewer_ui.hpp) and text overlays (viewer_overlay.hpp). One arm is a `ViewerSession`
/// (`PanelState`); a robot with several hands (`dual_arm`) is a `TeleopSession` driven by the
/// bimanual panel (`TeleopPanel`, teleop_ui.hpp), recorded with a `SessionRecorder` and, with
/// `ViewerOptions::record_session`, written as a session file (session_log.hpp) when the
/// viewer ends — by the window, escape, Ctrl-C, the end of a script or an error.
///
/// Controls: left drag rotates the camera, right drag moves it, middle drag or the scroll wheel
/// zooms (shift with a drag: rotate/move in the horizontal plane); space pauses and resumes,
/// the right arrow steps one control tick while paused, backspace resets, escape or closing the
/// window quits. The loop draws at `ViewerRates::render_hz` and polls input at `input_hz` on the
/// wall clock; physics catches up with the wall clock by whole control ticks (`ViewerSchedule`).
///
/// With a `ViewerScript` the session is scripted: synthetic input from the script, a virtual
/// clock (one render period per frame, so the run is deterministic and as fast as the machine
/// draws), screenshots, and the end of the script ends the session.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mjarm/model/robot.hpp"
#include "mjarm/teleop/teleop_panel.hpp"
#include "mjarm/teleop/teleop_session.hpp"
#include "mjarm/teleop/viewer_panel.hpp"
#include "mjarm/teleop/viewer_schedule.hpp"
#include "mjarm/teleop/viewer_script.hpp"
#include "mjarm/teleop/viewer_session.hpp"

namespace mjarm {

/// How the viewer runs.
struct ViewerOptions {
  /// Which session the window drives: one arm (`ViewerSession`, `session`) or several hands
  /// (`TeleopSession`, `teleop`).
  bool several_hands = false;
  ViewerSessionOptions session;  ///< one arm: frame, initial state and mode, limits
  TeleopOptions teleop;          ///< several hands: hands, lift, initial mode, limits
  /// Several hands: write the recorded session to this file when the viewer ends ("" = none).
  /// The file is opened before the window, so an unwritable path fails first.
  std::string record_session;
  ViewerRates rates;                   ///< render / input rates, speed, catch-up cap
  int width = 1280;                    ///< window width [screen pixels] (≥ 320)
  int height = 800;                    ///< window height [screen pixels] (≥ 240)
  std::optional<ViewerScript> script;  ///< scripted session (virtual clock) when set
  /// Panel values set before the first frame, as (name, value) for `set_panel_value` (one arm)
  /// or `set_teleop_value` (several hands); "mode" switches the mode.
  std::vector<std::pair<std::string, std::string>> set;
};

/// A hand in a screenshot (several hands).
struct ViewerHandShot {
  std::string name;
  Eigen::Vector3d p_WE = Eigen::Vector3d::Zero();  ///< hand position [m]
  Eigen::Vector3d p_WT = Eigen::Vector3d::Zero();  ///< its panel target [m]
  double gripper = 0.0;                            ///< gripper command sent (0 open … 1 closed)
};

/// One screenshot taken by a script.
struct ViewerScreenshot {
  std::string path;
  std::int64_t frame = 0;  ///< frames drawn before it
  double time = 0.0;       ///< simulated time [s]
  SimulationMode mode = SimulationMode::kinematic;
  Eigen::Vector3d p_WE = Eigen::Vector3d::Zero();  ///< end-effector position [m]
  Eigen::Vector3d p_WT = Eigen::Vector3d::Zero();  ///< panel target position [m]
  int width = 0;                                   ///< [pixels]
  int height = 0;                                  ///< [pixels]
  std::vector<ViewerHandShot> hands;  ///< several hands: each (p_WE, p_WT above: the first)
  double lift = 0.0;                  ///< several hands: lift position [m]
};

/// What a viewer session of several hands did.
struct TeleopViewerReport {
  std::vector<TeleopHand> hands;
  TeleopStats stats;               ///< at the end
  TeleopPanel panel;               ///< at the end
  std::string session_file;        ///< the recorded session ("" when not recorded)
  std::size_t session_events = 0;  ///< events recorded (targets, mode, task, reset)
  std::int64_t session_ticks = 0;  ///< control ticks recorded
  std::string session_digest;      ///< digest of the final state (`state_digest`)
};

/// What a viewer session did.
struct ViewerReport {
  /// "window closed", "escape", "interrupted" (SIGINT/SIGTERM), "quit", "end of script"
  std::string ended_by;
  /// The signal that ended it (SIGINT or SIGTERM) when `ended_by` is "interrupted", else 0: the
  /// command line exits with 128 + it after printing the report.
  int signal = 0;
  std::int64_t frames = 0;    ///< frames drawn
  std::int64_t polls = 0;     ///< input polls
  std::int64_t ticks = 0;     ///< control ticks simulated
  double wall_seconds = 0.0;  ///< real time the session lasted [s]
  double dropped = 0.0;       ///< simulated time dropped to keep up with the wall clock [s]
  ViewerStats stats;          ///< one arm: the session's statistics at the end
  PanelState panel;           ///< one arm: the panel at the end
  std::optional<TeleopViewerReport> teleop;  ///< several hands
  std::vector<ViewerScreenshot> screenshots;
  std::string gl;  ///< OpenGL vendor, renderer and version
};

/// The message given when there is no display (DISPLAY unset or empty).
extern const char* const kNoDisplayMessage;

/// @throws Error with `kNoDisplayMessage` when the environment names no X display.
void require_display();

/// True when @p robot has several hand frames (`find_teleop_hands`: "<name>_tcp" sites), so
/// that the viewer drives it with a `TeleopSession`.
bool has_several_hands(const Robot& robot);

/// Opens the window and runs the viewer on @p robot until the window is closed, escape is
/// pressed, SIGINT or SIGTERM arrives (an `InterruptGuard` is held meanwhile) or the script ends.
/// @throws Error when there is no display (`kNoDisplayMessage`), GLFW or the window cannot be
///         initialised (with GLFW's message), the session cannot be built (unknown site, …), the
///         session file cannot be created (before the window opens), a script command fails
///         (naming its line), or a screenshot cannot be written. A recorded session is written
///         before an error leaves (what was recorded up to it replays).
ViewerReport run_viewer(const Robot& robot, const ViewerOptions& options);

}  // namespace mjarm
