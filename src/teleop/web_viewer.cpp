#include "mjarm/teleop/web_viewer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/web/live_page.hpp"
#include "teleop/web_frame.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

/// The most simulated time one frame catches up [s]; beyond, it is dropped.
constexpr double kMaxCatchUp = 0.25;

/// Fills @p frame with the session's state; allocates nothing.
void write_frame(const ViewerSession& session, WebFrame& frame) {
  const ViewerStats& s = session.stats();
  frame.set_bodies(s.time, session.simulation().data());
  frame.set_panel(s.X_WE, s.X_WT, s.gripper);
}

}  // namespace

std::string web_viewer_greeting(const ViewerSession& session, const PanelState& panel) {
  const PanelRanges& r = session.ranges();
  const std::vector<std::string>& names = panel_value_names();
  Json sliders = Json::array();
  for (int k = 0; k < 6; ++k)
    sliders.push_back({{"name", names[static_cast<std::size_t>(k)]},
                       {"lower", r.lower[k]},
                       {"upper", r.upper[k]},
                       {"value", panel.target[k]}});
  sliders.push_back(
      {{"name", "gripper"}, {"lower", 0.0}, {"upper", 1.0}, {"value", panel.gripper}});
  Json modes = Json::array();
  for (SimulationMode mode :
       {SimulationMode::kinematic, SimulationMode::position, SimulationMode::torque})
    if (session.available(mode)) modes.push_back(to_string(mode));
  Json greeting = web_greeting(session.robot(), WebFrame(session.robot().model(), true));
  greeting["site"] = session.site();
  greeting["sliders"] = sliders;
  greeting["mode"] = to_string(session.mode());
  greeting["modes"] = modes;
  return greeting.dump();
}

std::string apply_web_message(ViewerSession& session, PanelState& panel,
                              const std::string& message) {
  const Json doc = Json::parse(message, nullptr, false);
  if (doc.is_discarded() || !doc.is_object())
    return "not a JSON object: {\"set\": NAME, \"value\": V} or {\"reset\": true}";
  if (doc.contains("reset")) {
    session.reset();
    return {};
  }
  if (!doc.contains("set") || !doc["set"].is_string() || !doc.contains("value"))
    return "a message sets one value: {\"set\": NAME, \"value\": V}";
  const Json& value = doc["value"];
  std::string text;
  if (value.is_string()) {
    text = value.get<std::string>();
  } else if (value.is_number()) {
    text = Json(value.get<double>()).dump();
  } else {
    return "the value of '" + doc["set"].get<std::string>() + "' is neither a number nor a string";
  }
  PanelState next = panel;
  try {
    set_panel_value(next, session.ranges(), doc["set"].get<std::string>(), text);
    const SimulationMode mode = panel_mode(next);
    if (mode != session.mode()) session.set_mode(mode);
  } catch (const Error& e) {
    return e.what();
  }
  panel = next;
  session.set_target(panel);
  return {};
}

WebViewerReport run_web_viewer(ViewerSession& session, const WebViewerOptions& options,
                               const std::function<void(const LiveServer&)>& on_start) {
  check_fields(options);
  PanelState panel = session.initial_panel();
  panel.mode = static_cast<int>(session.mode());
  LiveServer server(live_page_html("view --web"), options.server);
  server.set_greeting(web_viewer_greeting(session, panel));
  if (on_start) on_start(server);

  WebFrame frame(session.robot().model(), true);
  std::string message;
  WebViewerReport report;
  double simulated = 0.0;  // since start, across resets
  const Clock::time_point start = Clock::now();
  const auto frame_period = std::chrono::duration<double>(1.0 / options.frame_rate);
  Clock::time_point next = start;
  for (;;) {
    if (interrupt_requested()) {
      report.ended_by = "signal";
      report.signal = interrupt_signal();
      break;
    }
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    if (options.duration > 0.0 && wall >= options.duration) {
      report.ended_by = "duration";
      break;
    }
    while (server.poll(message)) {
      std::string refusal = apply_web_message(session, panel, message);
      if (refusal.empty()) {
        ++report.applied;
      } else {
        ++report.refused;
        report.last_refusal = std::move(refusal);
      }
    }
    // the ticks that bring the simulated time to speed × wall (a quarter second at most)
    const double period = session.control_period();
    const double behind = options.speed * wall - report.dropped - simulated;
    const double catch_up = std::min(behind, kMaxCatchUp);
    if (behind > kMaxCatchUp) report.dropped += behind - kMaxCatchUp;
    const int ticks = static_cast<int>(std::floor(catch_up / period + 1e-9));
    if (ticks > 0) {
      const int done = session.step(ticks);
      report.ticks += done;
      simulated += done * period;
      if (done < ticks) report.dropped += (ticks - done) * period;  // a fault stopped it
    }
    write_frame(session, frame);
    server.publish(frame.bytes());
    ++report.frames;
    next += std::chrono::duration_cast<Clock::duration>(frame_period);
    const Clock::time_point now = Clock::now();
    if (next < now) next = now;  // late frames are not made up for
    std::this_thread::sleep_until(next);
  }
  report.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  report.sim_time = simulated;
  report.server = server.stats();
  report.stats = session.stats();
  return report;
}

}  // namespace mjarm
