#pragma once
/// @file
/// The viewer for machines without a display: a `ViewerSession` simulated in real time, its
/// state streamed to browsers by a `LiveServer` and its panel (target sliders, gripper, mode)
/// set from them (`mjarm view MODEL --web`, docs/viewer.md "In a browser").
///
/// Each frame (at `frame_rate`) the loop applies the browsers' messages, simulates the control
/// ticks that bring the simulated time to speed × the wall time since start (at most a quarter
/// second of them: a slower machine drops simulated time, counted), and publishes the state.
/// Publishing never waits for a browser (see `LiveServer`).
///
/// A message is one JSON object: {"set": NAME, "value": V} with NAME and V as `set_panel_value`
/// takes them (x y z [m], roll pitch yaw [rad], gripper 0..1, mode kinematic|position|torque; V a
/// number or a string), or {"reset": true}. A message that is not one, or a value out of range,
/// is refused: counted, with the last refusal's reason kept, and the panel unchanged.
///
/// The page is the replay page's script in live mode (web/live_page.hpp): the greeting gives it
/// the model as a replay file describes it, the panel (sliders, modes) and the frame's layout.
/// The state frame is binary, little-endian float32: the simulated time [s], the tool (end
/// effector) pose and the target pose (x y z [m], quaternion w x y z, 7 each), the gripper
/// command, then every body's position (3 per body, the world's first) and every body's
/// quaternion (w x y z, 4 per body) in body id order: the `pos` and `quat` of one replay frame.

#include <cstdint>
#include <functional>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/teleop/viewer_session.hpp"
#include "mjarm/web/live_server.hpp"

namespace mjarm {

/// Settings of `run_web_viewer`.
struct WebViewerOptions {
  LiveServerOptions server;
  double speed = 1.0;        ///< simulated seconds per wall-clock second
  double frame_rate = 60.0;  ///< frames published per second [Hz]
  double duration = 0.0;     ///< wall-clock time to run [s]; 0: until Ctrl-C
};

constexpr auto declared_fields(const WebViewerOptions*) {
  using S = WebViewerOptions;
  return declare<S>("web viewer", field("server", &S::server, "the live server"),
                    field("speed", &S::speed, "", Range::closed(0.01, 100.0),
                          "simulated seconds per wall-clock second"),
                    field("frame_rate", &S::frame_rate, "Hz", Range::closed(1.0, 240.0),
                          "frames published per second"),
                    field("duration", &S::duration, "s", Range::closed(0.0, 1e6),
                          "wall-clock time to run; 0: until Ctrl-C"));
}

/// What a web viewer run did.
struct WebViewerReport {
  std::string ended_by;  ///< "duration" or "signal"
  int signal = 0;        ///< the signal that ended it (0: none)
  std::int64_t frames = 0;
  std::int64_t ticks = 0;
  double sim_time = 0.0;      ///< simulated [s]
  double wall_seconds = 0.0;  ///< [s]
  double dropped = 0.0;       ///< simulated time skipped to keep up [s]
  std::int64_t applied = 0;   ///< browser messages applied
  std::int64_t refused = 0;   ///< browser messages refused
  std::string last_refusal;   ///< why the last was refused
  LiveServerStats server;
  ViewerStats stats;  ///< the session's at the end
  /// Simulated time per wall-clock second.
  double real_time_factor() const noexcept {
    return wall_seconds > 0.0 ? sim_time / wall_seconds : 0.0;
  }
};

/// The greeting a browser gets on connecting: the model as the replay page draws it (`live_scene`:
/// bodies, drawn geoms, meshes, textures, cameras), its name, the frame's layout ("frame": where
/// time, tool, target, gripper, pos and quat start, in floats), the slider names with their ranges
/// and current values, the mode and the available modes.
std::string web_viewer_greeting(const ViewerSession& session, const PanelState& panel);

/// Applies one browser @p message to @p panel and @p session.
/// @return "" when applied, else why it was refused (panel and session unchanged)
std::string apply_web_message(ViewerSession& session, PanelState& panel,
                              const std::string& message);

/// Runs @p session in real time behind a `LiveServer` until @p options' duration or a signal;
/// @p on_start is called once the server listens (to print its address).
/// @throws Error for invalid options, when the build holds no page (MJARM_WEB: "view --web: this
///         mjarm was built without the replay page …", the words of `replay-html`), or as
///         `LiveServer`
WebViewerReport run_web_viewer(ViewerSession& session, const WebViewerOptions& options,
                               const std::function<void(const LiveServer&)>& on_start);

}  // namespace mjarm
