#pragma once
/// @file
/// The interactive viewer: a GLFW window showing a `ViewerSession` with MuJoCo's renderer, a
/// side panel (viewer_ui.hpp) and text overlays (viewer_overlay.hpp).
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
#include "mjarm/teleop/viewer_panel.hpp"
#include "mjarm/teleop/viewer_schedule.hpp"
#include "mjarm/teleop/viewer_script.hpp"
#include "mjarm/teleop/viewer_session.hpp"

namespace mjarm {

/// How the viewer runs.
struct ViewerOptions {
  ViewerSessionOptions session;        ///< frame, initial state and mode, controller limits
  ViewerRates rates;                   ///< render / input rates, speed, catch-up cap
  int width = 1280;                    ///< window width [screen pixels] (≥ 320)
  int height = 800;                    ///< window height [screen pixels] (≥ 240)
  std::optional<ViewerScript> script;  ///< scripted session (virtual clock) when set
  /// Panel values set before the first frame, as (name, value) for `set_panel_value`
  /// ("mode" switches the mode).
  std::vector<std::pair<std::string, std::string>> set;
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
};

/// What a viewer session did.
struct ViewerReport {
  /// "window closed", "escape", "interrupted" (SIGINT/SIGTERM), "quit", "end of script"
  std::string ended_by;
  std::int64_t frames = 0;    ///< frames drawn
  std::int64_t polls = 0;     ///< input polls
  std::int64_t ticks = 0;     ///< control ticks simulated
  double wall_seconds = 0.0;  ///< real time the session lasted [s]
  double dropped = 0.0;       ///< simulated time dropped to keep up with the wall clock [s]
  ViewerStats stats;          ///< the session's statistics at the end
  PanelState panel;           ///< the panel at the end
  std::vector<ViewerScreenshot> screenshots;
  std::string gl;  ///< OpenGL vendor, renderer and version
};

/// The message given when there is no display (DISPLAY unset or empty).
extern const char* const kNoDisplayMessage;

/// @throws Error with `kNoDisplayMessage` when the environment names no X display.
void require_display();

/// Opens the window and runs the viewer on @p robot until the window is closed, escape is
/// pressed, SIGINT or SIGTERM arrives (an `InterruptGuard` is held meanwhile) or the script ends.
/// @throws Error when there is no display (`kNoDisplayMessage`), GLFW or the window cannot be
///         initialised (with GLFW's message), the session cannot be built (unknown site, …), a
///         script command fails (naming its line), or a screenshot cannot be written.
ViewerReport run_viewer(const Robot& robot, const ViewerOptions& options);

}  // namespace mjarm
