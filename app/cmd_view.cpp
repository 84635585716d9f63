// `mjarm view [MODEL]`: the interactive viewer (a GLFW window), or a scripted session of it.

#include <iostream>
#include <memory>
#include <numbers>

#include "commands.hpp"
#include "field_options.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/teleop/viewer.hpp"
#include "mjarm/teleop/web_viewer.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

struct ViewOptions {
  std::string model = "panda";
  std::string site;
  std::string key;
  std::string mode = "kinematic";
  std::string script;
  std::int64_t frames = -1;
  std::string screenshot;
  std::string record_session;
  std::vector<std::string> set;
  std::string size = "1280x800";
  double render_hz = 60.0;
  double input_hz = 20.0;
  double speed = 1.0;
  bool web = false;
  std::string host = "127.0.0.1";
  int port = 0;
  bool token = false;
  double duration = 0.0;
  bool json = false;
};

Json pose_summary(const Pose& X) {
  return {{"position", vector_json(X.p)}, {"rpy", vector_json(rpy_from_rotation(X.R))}};
}

// what every viewer report holds
Json common_report_json(const Robot& robot, const ViewerReport& report, SimulationMode mode,
                        double sim_time) {
  Json doc;
  doc["model"] = robot.name();
  doc["ended_by"] = report.ended_by;
  doc["mode"] = to_string(mode);
  doc["frames"] = report.frames;
  doc["input_polls"] = report.polls;
  doc["control_ticks"] = report.ticks;
  doc["sim_time"] = sim_time;
  doc["wall_seconds"] = report.wall_seconds;
  doc["dropped_sim_time"] = report.dropped;
  return doc;
}

// a screenshot: the end effector and its target (one arm), or the lift and each hand
Json screenshots_json(const ViewerReport& report) {
  Json shots = Json::array();
  for (const ViewerScreenshot& shot : report.screenshots) {
    Json j{{"path", shot.path},     {"frame", shot.frame},
           {"sim_time", shot.time}, {"mode", to_string(shot.mode)},
           {"width", shot.width},   {"height", shot.height}};
    if (report.teleop) {
      Json hands = Json::array();
      for (const ViewerHandShot& h : shot.hands) {
        hands.push_back({{"name", h.name},
                         {"position", vector_json(h.p_WE)},
                         {"target", vector_json(h.p_WT)},
                         {"gripper", h.gripper}});
      }
      j["lift"] = shot.lift;
      j["hands"] = hands;
    } else {
      j["end_effector"] = vector_json(shot.p_WE);
      j["target"] = vector_json(shot.p_WT);
    }
    shots.push_back(j);
  }
  return shots;
}

Json report_json(const Robot& robot, const ViewerReport& report, const std::string& site) {
  const ViewerStats& s = report.stats;
  Json doc = common_report_json(robot, report, s.mode, s.time);
  doc["site"] = site;
  doc["end_effector"] = pose_summary(s.X_WE);
  doc["target"] = pose_summary(s.X_WT);
  doc["reference"] = pose_summary(s.X_WR);
  doc["tracking_error"] = {{"position", s.tracking_position},
                           {"orientation", s.tracking_orientation}};
  doc["to_target"] = {{"position", s.target_position}, {"orientation", s.target_orientation}};
  doc["gripper"] = report.panel.gripper;
  doc["saturated"] = s.saturated;
  doc["contacts"] = s.contacts.contacts;
  doc["fault"] = s.faulted ? Json(s.fault) : Json(nullptr);
  doc["screenshots"] = screenshots_json(report);
  doc["gl"] = report.gl;
  return doc;
}

Json hands_report_json(const Robot& robot, const ViewerReport& report) {
  const TeleopViewerReport& t = *report.teleop;
  const TeleopStats& s = t.stats;
  static constexpr const char* kPriorities[3] = {"equal", "right-over-left", "left-over-right"};
  Json doc = common_report_json(robot, report, s.mode, s.time);
  doc["lift"] = {{"position", s.lift}, {"reference", s.lift_reference}, {"panel", t.panel.lift}};
  doc["priority"] = t.panel.priority >= 0 && t.panel.priority < 3
                        ? Json(kPriorities[t.panel.priority])
                        : Json(nullptr);
  doc["selected_hand"] = t.hands.at(static_cast<std::size_t>(t.panel.selected)).name;
  Json hands = Json::array();
  for (std::size_t i = 0; i < t.hands.size(); ++i) {
    const HandStats& h = s.hands[i];
    hands.push_back({{"name", t.hands[i].name},
                     {"frame", t.hands[i].frame},
                     {"hand", pose_summary(h.X_WE)},
                     {"target", pose_summary(h.X_WT)},
                     {"reference", pose_summary(h.X_WR)},
                     {"tracking_error",
                      {{"position", h.tracking_position}, {"orientation", h.tracking_orientation}}},
                     {"ik_status", to_string(h.ik_status)},
                     {"saturated", h.saturated},
                     {"contacts", h.contacts},
                     {"grasp_force", h.grasp_force},
                     {"touching", h.touching},
                     {"gripper", h.gripper},
                     {"panel_gripper", t.panel.hands[i].gripper}});
  }
  doc["hands"] = hands;
  const CameraPanel& c = t.panel.camera;
  doc["camera"] = {{"azimuth", c.azimuth},
                   {"elevation", c.elevation},
                   {"distance", c.distance},
                   {"lookat", {c.lookat[0], c.lookat[1], c.lookat[2]}}};
  doc["session"] = {{"file", t.session_file.empty() ? Json(nullptr) : Json(t.session_file)},
                    {"events", t.session_events},
                    {"ticks", t.session_ticks},
                    {"digest", t.session_digest}};
  doc["fault"] = s.faulted ? Json(s.fault) : Json(nullptr);
  doc["screenshots"] = screenshots_json(report);
  doc["gl"] = report.gl;
  return doc;
}

void print_hands_report(const Robot& robot, const ViewerReport& report) {
  const TeleopViewerReport& t = *report.teleop;
  const TeleopStats& s = t.stats;
  print_fields(std::cout,
               {{"model", robot.name()},
                {"ended by", report.ended_by},
                {"mode", to_string(s.mode)},
                {"frames", std::to_string(report.frames)},
                {"simulated", fixed(s.time, 3) + " s in " + fixed(report.wall_seconds, 2) + " s"},
                {"lift", fixed(s.lift, 4) + " m"}});
  for (std::size_t i = 0; i < t.hands.size(); ++i) {
    std::cout << t.hands[i].name << " hand: " << vector_text(s.hands[i].X_WE.p) << " (target "
              << vector_text(s.hands[i].X_WT.p) << ", grasp force "
              << fixed(s.hands[i].grasp_force, 1) << " N)\n";
  }
  if (!t.session_file.empty()) {
    std::cout << "session: " << t.session_file << " (" << t.session_events << " events, "
              << t.session_ticks << " ticks; mjarm replay " << t.session_file << ")\n";
  }
  for (const ViewerScreenshot& shot : report.screenshots) {
    std::cout << "screenshot " << shot.path << " (" << shot.width << "x" << shot.height << ")\n";
  }
}

/// `mjarm view MODEL --web`: the session in real time behind the live server until --duration or
/// Ctrl-C; the address (with its token) is printed once on stderr when the server listens.
void run_web_view(const ViewOptions& o, const Robot& robot, const ViewerSessionOptions& session) {
  ViewerSession viewer(robot, session);
  WebViewerOptions options;
  options.server.host = o.host;
  options.server.port = o.port;
  options.server.require_token = o.token;
  options.speed = o.speed;
  options.frame_rate = o.render_hz;
  options.duration = o.duration;
  const InterruptGuard interrupts;
  const WebViewerReport r = run_web_viewer(viewer, options, [&](const LiveServer& server) {
    std::cerr << "mjarm view: " << robot.name() << " live at " << server.url()
              << (server.token().empty() ? "" : " (the token is needed: keep the address private)")
              << (o.duration > 0.0 ? "" : "; Ctrl-C stops") << std::endl;
  });
  const ViewerStats& s = r.stats;
  if (o.json) {
    print_json(
        {{"model", robot.name()},
         {"ended_by", r.ended_by},
         {"mode", to_string(s.mode)},
         {"frames", r.frames},
         {"control_ticks", r.ticks},
         {"sim_time", r.sim_time},
         {"wall_seconds", r.wall_seconds},
         {"real_time_factor", r.real_time_factor()},
         {"dropped_sim_time", r.dropped},
         {"messages",
          {{"applied", r.applied}, {"refused", r.refused}, {"last_refusal", r.last_refusal}}},
         {"server",
          {{"pages", r.server.pages},
           {"connections", r.server.connections},
           {"clients", r.server.clients},
           {"published", r.server.published},
           {"sent", r.server.sent},
           {"skipped", r.server.skipped},
           {"refused", r.server.refused},
           {"received", r.server.received},
           {"inbox_dropped", r.server.inbox_dropped}}},
         {"end_effector", pose_summary(s.X_WE)},
         {"target", pose_summary(s.X_WT)},
         {"fault", s.faulted ? Json(s.fault) : Json(nullptr)}});
  } else {
    print_fields(
        std::cout,
        {{"model", robot.name()},
         {"ended by", r.ended_by},
         {"mode", to_string(s.mode)},
         {"simulated", fixed(r.sim_time, 3) + " s in " + fixed(r.wall_seconds, 2) +
                           " s (real-time factor " + fixed(r.real_time_factor(), 3) + ")"},
         {"frames", std::to_string(r.frames) + " published, " + std::to_string(r.server.sent) +
                        " sent, " + std::to_string(r.server.skipped) + " skipped"},
         {"browsers", std::to_string(r.server.connections) + " connected, " +
                          std::to_string(r.server.refused) + " refused"},
         {"messages", std::to_string(r.applied) + " applied, " + std::to_string(r.refused) +
                          " refused" + (r.last_refusal.empty() ? "" : " (" + r.last_refusal + ")")},
         {"end effector", vector_text(s.X_WE.p)},
         {"target", vector_text(s.X_WT.p)}});
  }
  if (r.signal != 0)
    throw InterruptedError("view: interrupted after " + std::to_string(r.frames) + " frames",
                           r.signal);
}

void run_view(const ViewOptions& o) {
  if (o.web && (!o.script.empty() || o.frames >= 0 || !o.screenshot.empty() ||
                !o.record_session.empty() || !o.set.empty()))
    throw UsageError(
        "view: --web is driven from the browser: --script, --frames, --screenshot, "
        "--record-session and --set belong to the window");
  if (!o.web && (o.port != 0 || o.token || o.duration != 0.0 || o.host != "127.0.0.1"))
    throw UsageError("view: --host, --port, --token and --duration go with --web");
  if (!o.screenshot.empty()) check_output_file(o.screenshot, "--screenshot");
  if (!o.record_session.empty()) check_output_file(o.record_session, "--record-session");
  const Robot robot = load_model(o.model);
  ViewerOptions options;
  options.session.site = o.site;
  options.session.keyframe = o.key;
  options.session.mode = parse_enum<SimulationMode>(o.mode, "mode", "--mode");
  options.several_hands = has_several_hands(robot);
  if (!o.record_session.empty() && !options.several_hands) {
    throw UsageError("view: --record-session records sessions of several hands (e.g. dual_arm); '" +
                     robot.name() + "' has one end effector");
  }
  if (o.web) {
    if (options.several_hands)
      throw UsageError("view: --web drives one arm's panel; '" + robot.name() +
                       "' has several hands");
    return run_web_view(o, robot, options.session);
  }
  if (options.several_hands && !o.site.empty()) {
    throw UsageError("view: --site chooses the end effector of one arm; '" + robot.name() +
                     "' has several hands (its '<name>_tcp' sites)");
  }
  options.teleop.keyframe = o.key;
  options.teleop.mode = options.session.mode;
  options.record_session = o.record_session;
  const PixelSize size = parse_pixel_size(o.size);
  options.width = size.width;
  options.height = size.height;
  options.rates.render_hz = o.render_hz;
  options.rates.input_hz = o.input_hz;
  options.rates.speed = o.speed;
  for (const std::string& item : o.set) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw UsageError("view: --set takes NAME=VALUE (e.g. x=0.4, mode=torque), got '" + item +
                       "'");
    }
    options.set.emplace_back(item.substr(0, eq), item.substr(eq + 1));
  }
  // any of --script, --frames, --screenshot makes a scripted session on the virtual clock
  if (!o.script.empty() || o.frames >= 0 || !o.screenshot.empty()) {
    ViewerScript script = o.script.empty() ? ViewerScript{} : ViewerScript::load(o.script);
    ScriptCommand wait;
    wait.action = ScriptAction::wait;
    wait.frames = static_cast<int>(std::max<std::int64_t>(o.frames, o.screenshot.empty() ? 0 : 1));
    script.commands.push_back(wait);
    if (!o.screenshot.empty()) {
      ScriptCommand shot;
      shot.action = ScriptAction::screenshot;
      shot.name = o.screenshot;
      script.commands.push_back(shot);
    }
    options.script = std::move(script);
  }

  const ViewerReport report = run_viewer(robot, options);
  // Ctrl-C quits with the report printed (and the session written), then exits 130 (SIGTERM:
  // 143) as every command stopped by a signal does
  const auto stopped = [&] {
    if (report.signal != 0)
      throw InterruptedError(
          "view: interrupted after " + std::to_string(report.frames) + " frames" +
              (o.record_session.empty() ? std::string()
                                        : "; the session is in " + o.record_session),
          report.signal);
  };
  if (report.teleop) {
    if (o.json) {
      print_json(hands_report_json(robot, report));
    } else {
      print_hands_report(robot, report);
    }
    return stopped();
  }
  const std::string site =
      options.session.site.empty() ? default_viewer_site(robot) : options.session.site;
  if (o.json) {
    print_json(report_json(robot, report, site));
    return stopped();
  }
  const ViewerStats& s = report.stats;
  print_fields(std::cout,
               {{"model", robot.name()},
                {"ended by", report.ended_by},
                {"mode", to_string(s.mode)},
                {"frames", std::to_string(report.frames)},
                {"simulated", fixed(s.time, 3) + " s in " + fixed(report.wall_seconds, 2) + " s"},
                {"end effector", vector_text(s.X_WE.p)},
                {"target", vector_text(s.X_WT.p)},
                {"to target", fixed(s.target_position * 1000.0, 1) + " mm"}});
  for (const ViewerScreenshot& shot : report.screenshots) {
    std::cout << "screenshot " << shot.path << " (" << shot.width << "x" << shot.height << ")\n";
  }
  stopped();
}

}  // namespace

Command add_view_command(CLI::App& root) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* app = root.add_subcommand(
      "view",
      "Interactive viewer: a window with the model, a panel of end-effector target sliders, "
      "gripper and simulation mode (kinematic, position, torque), and overlays. A model with "
      "several hands (dual_arm) gets a section per hand, the lift, the task priority and a "
      "camera section; W/S A/D R/F nudge the selected hand (shift: turn it), G its gripper, TAB "
      "selects the next. Mouse: left drag rotates, right drag moves, scroll zooms; keys: space "
      "pause, right arrow step, backspace reset, escape quit. Needs a display (DISPLAY, or "
      "xvfb-run).");
  app->add_option("MODEL", options->model,
                  "bundled model name (see `mjarm models`) or path to an MJCF file; default panda");
  app->add_option("--site", options->site,
                  "end-effector site (or body); default: 'tcp' when the model has that site, "
                  "else its only named site");
  app->add_option("--key", options->key, "initial keyframe; default 'home' when the model has it");
  app->add_option("--mode", options->mode, "initial mode")
      ->check(name_of<SimulationMode>("mode"));
  app->add_option("--script", options->script,
                  "run a script of synthetic input and screenshots (see docs/viewer.md), then exit")
      ->check(CLI::ExistingFile);
  app->add_option("--frames", options->frames,
                  "scripted: draw N frames (after the script), then exit")
      ->check(count_in(0, 1000000));
  app->add_option("--screenshot", options->screenshot, "scripted: save the last frame as this PNG");
  app->add_option("--record-session", options->record_session,
                  "models with several hands (dual_arm): record the session to FILE, written when "
                  "the viewer ends (window closed, escape, Ctrl-C, end of script, or an error); "
                  "replay it with `mjarm replay FILE`");
  app->add_option("--set", options->set,
                  "panel value before the first frame, NAME=VALUE (x y z [m], roll pitch yaw "
                  "[rad], gripper 0..1, mode; with several hands left.z, right.gripper, lift, "
                  "camera.preset, priority, hand, ...); repeatable");
  app->add_option("--size", options->size, "window size WIDTHxHEIGHT [pixels]; default 1280x800")
      ->check(pixel_size({1, 1}, false, {7680, 4320}));
  app->add_option("--render-hz", options->render_hz, "frames per second, 1 to 240; default 60")
      ->check(number_in(1.0, 240.0));
  app->add_option("--input-hz", options->input_hz, "input polls per second, 1 to 1000; default 20")
      ->check(number_in(1.0, 1000.0));
  app->add_option("--speed", options->speed,
                  "simulated seconds per wall-clock second, 0.01 to 100; default 1")
      ->check(number_in(0.01, 100.0));
  app->add_flag("--web", options->web,
                "no window: serve the viewer to a browser (a page at http://127.0.0.1:PORT/, the "
                "state streamed over a WebSocket, the sliders sent back) while the simulation "
                "runs in real time; the address is printed on stderr");
  app->add_option("--host", options->host,
                  "--web: the interface to listen on; default 127.0.0.1 (reach it through an SSH "
                  "tunnel); any other needs the access token printed at start");
  app->add_option("--port", options->port, "--web: the TCP port; default 0, a free one")
      ->check(CLI::Range(0, 65535));
  app->add_flag("--token", options->token, "--web: require the access token on 127.0.0.1 too");
  app->add_option("--duration", options->duration,
                  "--web: wall-clock seconds to serve, 0 to 10⁶; default 0, until Ctrl-C")
      ->check(number_in(0.0, 1e6));
  add_json_flag(*app, options->json);
  return {app, [options] { run_view(*options); }};
}

}  // namespace mjarm::cli
