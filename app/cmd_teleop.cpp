// `mjarm replay FILE`: replays a recorded teleoperation session headless (optionally to a video);
// `mjarm bimanual`: the scripted bimanual lift through the same session code (docs/teleop.md).

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "field_options.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/tasks/run_video.hpp"
#include "mjarm/teleop/bimanual_lift.hpp"

namespace mjarm::cli {

namespace {

// the video of a session: frames on the simulation clock, from a camera framing the robot
class TeleopVideo {
 public:
  TeleopVideo(const TeleopSession& session, const VideoCli& o) {
    const PixelSize size = parse_pixel_size(o.size);
    RunVideoOptions options;
    options.width = size.width;
    options.height = size.height;
    options.fps = o.fps;
    const mjData& d = session.simulation().data();
    // from the front and above, looking at the middle between the hands
    Eigen::Vector3d lookat = Eigen::Vector3d::Zero();
    for (const auto& h : session.stats().hands) lookat += h.X_WE.p;
    lookat /= static_cast<double>(session.stats().hands.size());
    lookat.z() -= 0.1;
    const CameraSpec camera = CameraSpec::free_camera(lookat, 2.2, 155.0, -30.0);
    video_ = std::make_unique<RunVideo>(session.robot(), d, o.path, camera, options);
  }
  void on_tick(const TeleopSession& session) { video_->on_tick(session.simulation().data()); }
  /// Finalizes the video: "" when written, else why not (after an interrupt: not written, an
  /// old file kept; see VideoWriter).
  std::string finish(const TeleopSession& session) {
    try {
      video_->finish(session.simulation().data());
    } catch (const Error& e) {
      return e.what();
    }
    return {};
  }
  std::int64_t frames() const { return video_->frames(); }
  bool complete() const { return video_->complete(); }

 private:
  std::unique_ptr<RunVideo> video_;
};

// "video: F (N frames)" or "video: F (not written: see the error)"
std::string video_line(const std::string& path, const TeleopVideo& video) {
  return "video: " + path + " (" +
         (video.complete() ? std::to_string(video.frames()) + " frames"
                           : std::string("not written: see the error")) +
         ")";
}

Json video_json(const std::string& path, const TeleopVideo& video, const std::string& error) {
  return {{"path", path},
          {"frames", video.frames()},
          {"written", video.complete()},
          {"error", error.empty() ? Json(nullptr) : Json(error)}};
}

Json hand_stats_json(const TeleopSession& session, const TeleopStats& s) {
  Json hands = Json::array();
  for (std::size_t i = 0; i < s.hands.size(); ++i) {
    const HandStats& h = s.hands[i];
    hands.push_back({{"name", session.hands()[i].name},
                     {"position", vector_json(h.X_WE.p)},
                     {"tracking_error", h.tracking_position},
                     {"touching", h.touching},
                     {"grasp_force", h.grasp_force},
                     {"gripper", h.gripper}});
  }
  return hands;
}

}  // namespace

Command add_replay_command(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "replay", "replay a recorded teleoperation session headless, deterministically");
  struct Options {
    std::string file;
    std::string model;
    VideoCli video;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  app->add_option("FILE", o->file,
                  "session file (mjarm view --record-session, mjarm bimanual "
                  "--record-session)")
      ->required();
  app->add_option("--model", o->model,
                  "model to replay on (default: the one the file names); it must be the model "
                  "the session was recorded on");
  add_video_options(*app, o->video, "the session");
  add_json_flag(*app, o->json);
  return {app, [o] {
            if (!o->video.path.empty()) check_output_file(o->video.path, "--video");
            const SessionLog log = read_session_log(o->file);
            const Robot robot = load_model(o->model.empty() ? log.model : o->model);
            const InterruptGuard interrupts;
            SessionReplay replay(robot, log);
            std::optional<TeleopVideo> video;
            if (!o->video.path.empty()) video.emplace(replay.session(), o->video);
            Progress progress("replay", std::max<std::int64_t>(1, log.ticks),
                              !o->json && stderr_is_terminal());
            while (replay.step()) {
              if (video) video->on_tick(replay.session());
              if (replay.ticks() % 100 == 0) progress.update(replay.ticks());
              if (interrupt_requested()) break;
            }
            progress.finish();
            // a video cut by Ctrl-C is not written (VideoWriter): the message says so
            const std::string video_error = video ? video->finish(replay.session()) : "";
            const ReplayResult r = replay.result();
            if (interrupt_requested())
              throw InterruptedError("replay stopped after " + std::to_string(r.ticks) + " of " +
                                         std::to_string(log.ticks) + " ticks" +
                                         (video_error.empty() ? "" : "; " + video_error),
                                     interrupt_signal());
            const TeleopSession& session = replay.session();
            if (o->json) {
              Json doc{{"file", o->file},
                       {"model", robot.name()},
                       {"ticks", r.ticks},
                       {"recorded_ticks", log.ticks},
                       {"sim_time", r.stats.time},
                       {"mode", to_string(r.stats.mode)},
                       {"digest", r.digest},
                       {"recorded_digest", log.digest},
                       {"deterministic", r.matches},
                       {"hands", hand_stats_json(session, r.stats)},
                       {"video",
                        video ? video_json(o->video.path, *video, video_error) : Json(nullptr)}};
              print_json(doc);
            } else {
              print_fields(
                  std::cout,
                  {{"session", o->file},
                   {"model", robot.name()},
                   {"ticks", std::to_string(r.ticks) + " of " + std::to_string(log.ticks) + " (" +
                                 fixed(r.stats.time, 3) + " s simulated, " +
                                 to_string(r.stats.mode) + " mode at the end)"},
                   {"final state", r.digest + (r.matches ? " (the recorded one)"
                                                         : " (recorded: " + log.digest + ")")}});
              if (video) std::cout << video_line(o->video.path, *video) << '\n';
            }
            if (!r.matches)
              throw Error("the replay did not reach the recorded state" +
                          std::string(r.stats.faulted ? ": " + r.stats.fault : "") +
                          (video_error.empty() ? "" : "; " + video_error));
            if (!video_error.empty()) throw Error(video_error);
          }};
}

Command add_bimanual_command(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "bimanual",
      "the scripted bimanual task: both hands grasp the bar of dual_arm_box by its "
      "ends and lift it 0.2 m, through the teleoperation session");
  struct Options {
    std::string model = "dual_arm_box";
    std::string mode = "position";
    std::string record;
    double lift_height = 0.2;
    VideoCli video;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  app->add_option("--model", o->model, "scene with two hands and a free body 'bar'")
      ->capture_default_str();
  app->add_option("--mode", o->mode, "simulation mode (torque: motors)")
      ->check(name_of<SimulationMode>("mode"))
      ->capture_default_str();
  app->add_option("--lift", o->lift_height, "how high to lift the bar [m]")
      ->check(number_in(0.0, 0.5))
      ->capture_default_str();
  app->add_option("--record-session", o->record, "write the session to FILE (mjarm replay FILE)");
  add_video_options(*app, o->video, "the session");
  add_json_flag(*app, o->json);
  return {
      app, [o] {
        if (!o->record.empty()) check_output_file(o->record, "--record-session");
        if (!o->video.path.empty()) check_output_file(o->video.path, "--video");
        const Robot robot = load_model(o->model);
        TeleopOptions options;
        options.mode = parse_enum<SimulationMode>(o->mode, "mode", "--mode");
        const InterruptGuard interrupts;
        TeleopSession session(robot, options);
        SessionRecorder recorder(session);
        std::optional<TeleopVideo> video;
        if (!o->video.path.empty()) video.emplace(session, o->video);
        BimanualLiftOptions lift;
        lift.lift_height = o->lift_height;
        // the script's ticks, phase by phase as run_bimanual_lift counts them
        std::int64_t planned = 0;
        for (const double t : {lift.approach_time, lift.descend_time, lift.close_time,
                               lift.lift_time, lift.hold_time})
          planned += std::lround(t / session.control_period());
        Progress progress("bimanual lift (ticks)", planned, !o->json && stderr_is_terminal());
        std::int64_t ticks = 0;
        // Ctrl-C: the lift stops at its next tick; the video cut short and the session are not
        // written (an old file at either path is kept), and the message says so
        std::optional<BimanualLiftResult> lifted;
        try {
          lifted = run_bimanual_lift(recorder, lift, [&](const TeleopSession& s) {
            if (video) video->on_tick(s);
            progress.update(++ticks);
            if (interrupt_requested())
              throw InterruptedError("bimanual lift stopped at " + fixed(s.stats().time, 3) + " s",
                                     interrupt_signal());
          });
        } catch (const InterruptedError& e) {
          progress.finish();
          const std::string video_error = video ? video->finish(session) : "";
          throw InterruptedError(
              e.what() + (video_error.empty() ? "" : "; " + video_error) +
                  (o->record.empty() ? "" : "; the session was not written to " + o->record),
              interrupt_signal());
        }
        progress.finish();
        const BimanualLiftResult& r = *lifted;
        const std::string video_error = video ? video->finish(session) : "";
        if (!o->record.empty()) write_session_log(recorder.log(), o->record);
        if (o->json) {
          print_json(
              {{"model", robot.name()},
               {"mode", o->mode},
               {"success", r.success},
               {"failure", r.failure.empty() ? Json(nullptr) : Json(r.failure)},
               {"start_z", r.start_z},
               {"end_z", r.end_z},
               {"lifted", r.lifted},
               {"sag", r.sag},
               {"grasp_force", {r.grasp_force[0], r.grasp_force[1]}},
               {"ticks", r.ticks},
               {"sim_time", session.stats().time},
               {"hands", hand_stats_json(session, session.stats())},
               {"session", o->record.empty() ? Json(nullptr) : Json(o->record)},
               {"video", video ? video_json(o->video.path, *video, video_error) : Json(nullptr)}});
        } else {
          print_fields(std::cout,
                       {{"scene", robot.name() + " (" + o->mode + " mode)"},
                        {"outcome", r.success ? "lifted" : "failed: " + r.failure},
                        {"bar height [m]", fixed(r.start_z, 4) + " → " + fixed(r.end_z, 4) +
                                               " (lifted " + fixed(r.lifted, 4) + ")"},
                        {"sag while held [mm]", fixed(r.sag * 1e3, 2)},
                        {"grasp force [N]", fixed(r.grasp_force[0], 1) + " left, " +
                                                fixed(r.grasp_force[1], 1) + " right"},
                        {"simulated", fixed(session.stats().time, 3) + " s, " +
                                          std::to_string(r.ticks) + " ticks"}});
          if (!o->record.empty()) std::cout << "session: " << o->record << '\n';
          if (video) std::cout << video_line(o->video.path, *video) << '\n';
        }
        if (!r.success)
          throw Error("bimanual lift failed: " + r.failure +
                      (video_error.empty() ? "" : "; " + video_error));
        if (!video_error.empty()) throw Error(video_error);
      }};
}

}  // namespace mjarm::cli
