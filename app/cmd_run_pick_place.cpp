// `mjarm run pick-place`: randomized pick-and-place trials (docs/pick_place.md) — one trial with
// its details, or a batch in parallel with the table of success rate, failure reasons and
// figures; a failing trial replays alone by its seed, with video.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/scenarios/pick_place_scenario.hpp"
#include "mjarm/tasks/pick_place/trials.hpp"
#include "mjarm/web/replay_html_json.hpp"
#include "parameter_options.hpp"
#include "run_replay.hpp"

namespace mjarm::cli {

namespace {

/// Most trials one command runs: about an hour on two cores.
constexpr std::uint64_t kMaxPickPlaceTrials = 10000;
/// Most frames a pick-and-place video films (--fps × the machine's duration, per camera).
constexpr double kMaxPickPlaceVideoFrames = 20000.0;

std::string millimetres(double metres, int decimals = 3) {
  return std::isnan(metres) ? "—" : fixed(metres * 1e3, decimals);
}
std::string figure_text(double v, int decimals = 3) {
  return std::isnan(v) ? "—" : fixed(v, decimals);
}

/// A trial's replay page (--html): what was written, or why not.
struct TrialPage {
  std::optional<ReplayHtmlReport> report;
  std::string error;  ///< "replay page FILE: why"; empty when written or not asked for
};

/// Writes the page of @p r's recording to @p page, also for a failed trial (what a page is most
/// wanted for); none for a trial without a complete recording or cut short by Ctrl-C.
TrialPage write_trial_page(const PickPlaceReport& r, const std::filesystem::path& page) {
  TrialPage out;
  if (page.empty() || r.recording.empty() || !r.recording_error.empty() ||
      r.failure == PickPlaceFailure::interrupted)
    return out;
  try {
    out.report = write_run_replay(r.recording, page);
  } catch (const Error& e) {
    out.error = "replay page " + page.string() + ": " + e.what();
  }
  return out;
}

std::string pick_place_title(const PickPlaceOptions& o) {
  return "pick and place on " + o.robot + ", " + to_string(o.grasp) + " grasp, " +
         to_string(o.mode) + " mode" + (o.classic ? ", classic scene" : "");
}

/// The command that replays one trial alone, with a video.
std::string replay_command(const PickPlaceCliOptions& cli, std::uint64_t seed) {
  std::string command = "mjarm run pick-place --robot " + cli.options.robot + " --grasp " +
                        to_string(cli.options.grasp) + " --mode " + to_string(cli.options.mode) +
                        (cli.options.classic ? " --classic" : "") + " --seed " +
                        std::to_string(seed) + " --video seed_" + std::to_string(seed) + ".mp4";
  return command;
}

Json pick_place_stat_json(const PickPlaceStat& s, double scale = 1.0) {
  return Json{{"count", s.count},
              {"mean", number_or_null(s.mean * scale)},
              {"max", number_or_null(s.max * scale)}};
}

Json pick_place_trial_json(const PickPlaceReport& r) {
  const PickPlaceObject& o = r.trial.object;
  return Json{{"seed", r.trial.seed},
              {"success", r.success},
              {"failure", to_string(r.failure)},
              {"reason", r.reason},
              {"object", Json{{"position", {o.position[0], o.position[1]}},
                              {"yaw", o.yaw},
                              {"half_size", o.size[0]},
                              {"mass", o.mass},
                              {"friction", o.friction}}},
              {"target", {r.trial.target[0], r.trial.target[1]}},
              {"placement_error", number_or_null(r.placement_error)},
              {"tilt", number_or_null(r.tilt)},
              {"final_speed", number_or_null(r.final_speed)},
              {"cycle_time", number_or_null(r.cycle_time)},
              {"grasp_force", number_or_null(r.trace.transport_force_mean)},
              {"grasp_force_max", number_or_null(r.trace.transport_force_max)},
              {"weld_jump", number_or_null(r.trace.weld_jump)},
              {"weld_settle", number_or_null(r.trace.weld_settle)},
              {"max_slip", r.trace.max_slip},
              {"closed", r.trace.closed},
              {"slipped", r.trace.slipped},
              {"table_contact", r.trace.table_contact},
              {"longest_saturation_ticks", r.trace.longest_saturation},
              {"status", to_string(r.run.status)},
              {"message", r.run.message}};
}

void print_pick_place_trial(std::ostream& os, const PickPlaceOptions& options,
                            const PickPlaceReport& r, const TrialPage& page) {
  const PickPlaceObject& o = r.trial.object;
  os << pick_place_title(options) << ", seed " << r.trial.seed << '\n';
  print_fields(
      os,
      {{"object", "cube " + millimetres(o.size[0], 1) + " mm half size, " + figure_text(o.mass, 3) +
                      " kg, friction " + figure_text(o.friction, 2) + ", at (" +
                      figure_text(o.position[0]) + ", " + figure_text(o.position[1]) + ") m, yaw " +
                      figure_text(o.yaw * 180.0 / M_PI, 1) + "°"},
       {"target",
        "(" + figure_text(r.trial.target[0]) + ", " + figure_text(r.trial.target[1]) + ") m"},
       {"control period [s]", compact(r.control_period)}},
      2);
  os << "result: " << (r.success ? "success" : std::string(to_string(r.failure)) + " — " + r.reason)
     << '\n';
  std::vector<std::pair<std::string, std::string>> fields{
      {"placement error [mm]", millimetres(r.placement_error) + " (horizontal, allowed " +
                                   millimetres(options.criteria.placement_tolerance, 1) + ")"},
      {"tilt [deg]", figure_text(r.tilt * 180.0 / M_PI, 2)},
      {"final speed [mm/s]", millimetres(r.final_speed, 4)},
      {"cycle time [s]", figure_text(r.cycle_time) + " (start to DONE)"},
      {"grasp force [N]", "mean " + figure_text(r.trace.transport_force_mean) + ", max " +
                              figure_text(r.trace.transport_force_max) + " (transport)"},
      {"largest slip [mm]", millimetres(r.trace.max_slip)}};
  if (r.grasp == GraspKind::weld)
    fields.push_back(
        {"weld jump [mm]", millimetres(r.trace.weld_jump, 5) + " (first " +
                               compact(kWeldJumpWindow * 1e3) + " ms after switching it on; " +
                               millimetres(r.trace.weld_settle, 5) + " over DWELL_C)"});
  if (!r.recording.empty())
    fields.push_back(
        {"recording", r.recording.string() +
                          (r.recording_error.empty() ? "" : " (not written: see the error)")});
  for (const auto& path : r.videos) {
    const bool written =
        std::find(r.videos_written.begin(), r.videos_written.end(), path) != r.videos_written.end();
    fields.push_back({"video", path.string() + " (" +
                                   (written ? std::to_string(r.video_frames) + " frames"
                                            : std::string("not written: see the error")) +
                                   ")"});
  }
  if (page.report)
    fields.push_back({"replay page", page.report->path.string() + " (" +
                                         std::to_string(page.report->bytes) + " bytes, " +
                                         std::to_string(page.report->frames) +
                                         " frames; open it in a browser)"});
  print_fields(os, fields, 2);
}

void print_pick_place_batch(std::ostream& os, const PickPlaceCliOptions& cli,
                            const PickPlaceBatch& batch, int threads) {
  const PickPlaceOptions& o = cli.options;
  const PickPlaceSummary& s = batch.summary;
  os << pick_place_title(o) << ": " << s.trials << " trials (seeds " << o.seed << "–"
     << o.seed + static_cast<std::uint64_t>(cli.trials) - 1 << ") on " << threads << " threads\n";
  std::string failures;
  for (std::size_t f = 1; f < s.failures.size(); ++f) {
    if (s.failures[f] == 0) continue;
    failures += (failures.empty() ? "" : ", ") +
                std::string(to_string(static_cast<PickPlaceFailure>(f))) + " " +
                std::to_string(s.failures[f]);
  }
  print_fields(os,
               {{"success", std::to_string(s.successes) + "/" + std::to_string(s.trials) + " (" +
                                figure_text(100.0 * s.success_rate(), 1) + " %)"},
                {"failures", failures.empty() ? "none" : failures}},
               2);
  Table table({{"figure", Table::Align::left}, {"trials"}, {"mean"}, {"max"}});
  const auto row = [&](const std::string& name, const PickPlaceStat& stat, double scale,
                       int decimals) {
    table.add_row({name, std::to_string(stat.count), figure_text(stat.mean * scale, decimals),
                   figure_text(stat.max * scale, decimals)});
  };
  row("placement error [mm]", s.placement_error, 1e3, 3);
  row("cycle time [s]", s.cycle_time, 1.0, 2);
  row("grasp force [N]", s.grasp_force, 1.0, 2);
  if (o.grasp == GraspKind::weld) {
    row("weld jump [mm]", s.weld_jump, 1e3, 5);
    row("weld settle [mm]", s.weld_settle, 1e3, 5);
  }
  row("largest slip [mm]", s.max_slip, 1e3, 3);
  table.print(os, 2);
  os << "  (placement, cycle time and grasp force over the successful trials)\n";
  bool first = true;
  for (const PickPlaceReport& r : batch.reports) {
    if (r.success) continue;
    if (first)
      os << "failed trials (replay one alone with its seed, e.g. `"
         << replay_command(cli, r.trial.seed) << "`):\n";
    first = false;
    os << "  seed " << r.trial.seed << ": " << to_string(r.failure) << " — " << r.reason << '\n';
  }
}

}  // namespace

void add_pick_place_options(CLI::App& app, PickPlaceCliOptions& o) {
  const auto grasp = [&o](const std::string& name) { o.grasp = name; };
  app.add_option_function<std::string>("--grasp", grasp,
                                       "pick-place: weld | friction (default weld)");
  app.add_option("--mode", o.mode, "pick-place: position | torque (default position)");
  app.add_option("--trials", o.trials, "pick-place: number of trials, seeds K … K+N−1")
      ->check(count_in(1, kMaxPickPlaceTrials));
  app.add_option("--threads", o.threads, "pick-place: worker threads (0: one per core)")
      ->check(count_in(0, 256));
  app.add_flag("--classic", o.options.classic,
               "pick-place: the classic scene edits (7.5 mm cube, finger travel [0, 0.012] m, "
               "finger servo gain 3200)");
  app.add_option("--object", o.object, "pick-place: object centre x y on the table [m]")
      ->expected(2)
      ->check(finite_number());
  app.add_option("--target", o.target, "pick-place: target x y on the table [m]")
      ->expected(2)
      ->check(finite_number());
  app.add_option("--object-size", o.object_size, "pick-place: cube half size [m]")
      ->check(number_in(0.002, 0.05));
  app.add_option("--grasp-force", o.options.grasp_force,
                 "pick-place: finger squeeze once touching [N]")
      ->check(number_in(0.1, 100.0))
      ->capture_default_str();
  app.add_option("--weld-solref", o.solref,
                 "pick-place: weld time constant [s] and damping ratio (default 0.002 1)")
      ->expected(2)
      ->check(number_in(1e-6, 10.0));
  app.add_option("--noslip", o.options.noslip_iterations,
                 "pick-place: MuJoCo noslip iterations (0: off; stops soft-contact creep)")
      ->check(count_in(0, 1000))
      ->capture_default_str();
  PickPlaceMotion& m = o.options.motion;
  const auto height = [&app](const char* name, double& value, const char* what) {
    app.add_option(name, value, std::string("pick-place: ") + what + " [m]")
        ->check(number_in(0.0, 0.5))
        ->capture_default_str();
  };
  height("--approach-height", m.approach_height, "tool above the object before DESCEND");
  height("--descend-height", m.descend_height, "tool above the object's centre at GRASP");
  height("--lift-height", m.lift_height, "tool above the object's start after LIFT");
  height("--move-height", m.move_height, "tool above the target during MOVE");
  height("--place-height", m.place_height, "tool above the target at RELEASE");
  app.add_option("--dwell", m.dwell_time, "pick-place: each DWELL state [s]")
      ->check(number_in(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--grip-time", m.grip_time, "pick-place: fingers close (smoothstep) [s]")
      ->check(number_in(0.01, 10.0))
      ->capture_default_str();
  app.add_option("--release-time", m.release_time, "pick-place: fingers open (smoothstep) [s]")
      ->check(number_in(0.01, 10.0))
      ->capture_default_str();
  app.add_option("--max-speed", m.limits.max_velocity,
                 "pick-place: trapezoid cruise speed of the Cartesian segments [m/s]")
      ->check(number_in(0.001, 2.0))
      ->capture_default_str();
  app.add_option("--max-accel", m.limits.max_acceleration,
                 "pick-place: trapezoid acceleration [m/s²]")
      ->check(number_in(0.01, 50.0))
      ->capture_default_str();
  app.add_option("--cameras", o.cameras,
                 "pick-place video: cameras to film, tiled into one picture (front, side, top, "
                 "follow; default front)")
      ->delimiter(',');
  app.add_flag("--video-per-camera", o.separate,
               "pick-place video: one file per camera (FILE's stem + _CAMERA) instead of tiles");
}

void run_pick_place_scenario(PickPlaceCliOptions cli, const RunCommonOptions& common) {
  PickPlaceOptions& o = cli.options;
  try {
    o.robot = common.robot.empty() ? "arm6" : common.robot;
    pick_place_robot(o.robot);
    o.grasp = grasp_kind(cli.grasp);
    if (cli.mode == "position") {
      o.mode = SimulationMode::position;
    } else if (cli.mode == "torque") {
      o.mode = SimulationMode::torque;
    } else {
      throw Error("unknown mode '" + cli.mode + "'; choices: position, torque");
    }
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  o.seed = common.seed;
  o.control_period = common.control_period;
  o.max_acceleration = common.max_acceleration;
  o.motion.settle_time = common.settle_time;
  if (cli.object.size() == 2)
    o.object_position = std::array<double, 2>{cli.object[0], cli.object[1]};
  if (cli.target.size() == 2)
    o.target_position = std::array<double, 2>{cli.target[0], cli.target[1]};
  if (cli.object_size > 0.0) o.object_half_size = cli.object_size;
  if (cli.solref.size() == 2) o.weld = {cli.solref[0], cli.solref[1]};
  // the registry's parameters that have no option of their own here
  apply_parameters(pick_place_scenario(), cli.parameters, o, pick_place_parameters);
  const bool batch = cli.trials > 1;
  if (batch && !common.video.empty())
    throw UsageError("--video films one trial: replay it alone with --seed K (and no --trials)");
  if (batch && common.html && !common.html_file.empty())
    throw UsageError("--html " + common.html_file +
                     " names one page; with --trials each trial gets its own beside its "
                     "recording (" +
                     common.record + "/seed_K.html): give --html without FILE");
  if ((!cli.cameras.empty() || cli.separate) && common.video.empty())
    throw UsageError("--cameras and --video-per-camera need --video FILE");
  for (const std::string& camera : cli.cameras) {
    if (camera != "front" && camera != "side" && camera != "top" && camera != "follow")
      throw UsageError("unknown camera '" + camera + "'; choices: front, side, top, follow");
  }
  // the outputs are checked before the work
  if (!common.record.empty()) check_output_folder(common.record, "--record");
  // the replay pages (--html): one trial's to FILE or beside its recording; a batch's beside
  // each trial's recording, in the folder just checked
  std::filesystem::path page;
  if (common.html && batch) check_replay_available("--html");
  if (common.html && !batch) {
    page = common.html_file.empty() ? replay_page_beside(common.record)
                                    : std::filesystem::path(common.html_file);
    check_run_replay("--html", page);
  }
  if (!common.video.empty()) {
    const std::vector<std::string> cameras =
        cli.cameras.empty() ? std::vector<std::string>{"front"} : cli.cameras;
    if (cli.separate && cameras.size() > 1) {
      for (const std::string& camera : cameras)
        check_output_file(camera_video_path(common.video, camera).string(), "--video");
    } else {
      check_output_file(common.video, "--video");
    }
    // a trial lasts 15–30 s of simulated time: bound the frames before the work starts
    const double frames = common.fps * 40.0 * static_cast<double>(cameras.size());
    if (frames > kMaxPickPlaceVideoFrames)
      throw UsageError("--video at --fps " + readable(common.fps) + " with " +
                       std::to_string(cameras.size()) + " cameras would render up to " +
                       readable(frames) + " pictures; at most " +
                       readable(kMaxPickPlaceVideoFrames) + " (lower --fps)");
    const PixelSize size = parse_pixel_size(common.size);
    o.video.path = common.video;
    o.video.cameras = cameras;
    o.video.tiled = !cli.separate;
    o.video.options.width = size.width;
    o.video.options.height = size.height;
    o.video.options.fps = common.fps;
  }
  const InterruptGuard interrupts;  // Ctrl-C: every trial stops at its next tick

  if (!batch) {
    o.record = common.record;
    const PickPlaceReport r = run_pick_place(o);
    const TrialPage replay = write_trial_page(r, page);
    if (common.json) {
      Json doc = pick_place_trial_json(r);
      doc = Json{{"scenario", "pick-place"},  {"robot", o.robot},     {"grasp", to_string(o.grasp)},
                 {"mode", to_string(o.mode)}, {"classic", o.classic}, {"trial", doc}};
      doc["recording"] = r.recording.empty() ? Json(nullptr) : Json(r.recording.string());
      doc["recording_error"] = r.recording_error.empty() ? Json(nullptr) : Json(r.recording_error);
      doc["replay"] = replay.report ? replay_html_json(*replay.report, r.recording) : Json(nullptr);
      doc["replay_error"] = replay.error.empty() ? Json(nullptr) : Json(replay.error);
      Json videos = Json::array(), written = Json::array();
      for (const auto& path : r.videos) videos.push_back(path.string());
      for (const auto& path : r.videos_written) written.push_back(path.string());
      doc["video"] =
          r.videos.empty()
              ? Json(nullptr)
              : Json{{"paths", videos},
                     {"written", written},
                     {"frames", r.video_frames},
                     {"error", r.video_error.empty() ? Json(nullptr) : Json(r.video_error)}};
      print_json(doc);
    } else {
      print_pick_place_trial(std::cout, o, r, replay);
    }
    if (r.failure == PickPlaceFailure::interrupted) {
      // the recording is kept (its status says interrupted); a video cut short is not written
      std::string outputs;
      if (!r.recording_error.empty())
        outputs += "; " + r.recording_error;
      else if (!r.recording.empty())
        outputs += "; the recording is in " + r.recording.string();
      if (!r.video_error.empty()) outputs += "; " + r.video_error;
      throw InterruptedError(
          "the pick and place was interrupted at t = " + fixed(r.run.end_time, 3) + " s" + outputs,
          interrupt_signal());
    }
    std::string problem = r.success ? "" : "the pick and place failed: " + r.reason;
    if (!r.recording_error.empty()) problem += (problem.empty() ? "" : "; ") + r.recording_error;
    if (!r.video_error.empty()) problem += (problem.empty() ? "" : "; ") + r.video_error;
    if (!replay.error.empty()) problem += (problem.empty() ? "" : "; ") + replay.error;
    if (!problem.empty()) throw Error(problem);
    return;
  }

  PickPlaceBatchOptions batch_options;
  batch_options.base = o;
  batch_options.trials = static_cast<int>(cli.trials);
  batch_options.threads = static_cast<int>(cli.threads);
  batch_options.record = common.record;
  const int threads = std::min<int>(
      batch_options.trials,
      cli.threads > 0 ? static_cast<int>(cli.threads)
                      : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  Progress progress("pick and place", cli.trials);
  batch_options.on_progress = [&progress](int done) { progress.update(done); };
  const PickPlaceBatch result = run_pick_place_trials(batch_options);
  progress.finish();
  // each recorded trial's page beside its recording (failed ones too); none after Ctrl-C
  std::vector<TrialPage> pages(result.reports.size());
  std::string page_errors;
  std::size_t pages_done = 0;  // Ctrl-C while writing them stops before the next
  if (common.html && !result.interrupted) {
    Progress writing("replay pages", static_cast<std::int64_t>(pages.size()));
    for (; pages_done < pages.size() && !interrupt_requested(); ++pages_done) {
      const std::size_t k = pages_done;
      const PickPlaceReport& r = result.reports[k];
      pages[k] =
          write_trial_page(r, r.recording.empty() ? r.recording : replay_page_beside(r.recording));
      if (!pages[k].error.empty())
        page_errors += (page_errors.empty() ? "" : "; ") + pages[k].error;
      writing.update(static_cast<std::int64_t>(k) + 1);
    }
    writing.finish();
  }
  const PickPlaceSummary& s = result.summary;
  const std::string stopped = "interrupted after " + std::to_string(s.trials) + " of " +
                              std::to_string(cli.trials) + " trials";
  const std::string failed = std::to_string(s.trials - s.successes) + " of " +
                             std::to_string(s.trials) + " trials failed (see the table)";
  if (common.json) {
    Json failures = Json::object();
    for (std::size_t f = 1; f < s.failures.size(); ++f)
      failures[to_string(static_cast<PickPlaceFailure>(f))] = s.failures[f];
    Json trials = Json::array();
    for (std::size_t k = 0; k < result.reports.size(); ++k) {
      Json trial = pick_place_trial_json(result.reports[k]);
      trial["replay"] = pages[k].report ? Json(pages[k].report->path.string()) : Json(nullptr);
      trials.push_back(trial);
    }
    print_json({{"scenario", "pick-place"},
                {"robot", o.robot},
                {"grasp", to_string(o.grasp)},
                {"mode", to_string(o.mode)},
                {"classic", o.classic},
                {"first_seed", o.seed},
                {"trials_asked", cli.trials},
                {"threads", threads},
                {"interrupted", result.interrupted},
                {"summary",
                 {{"trials", s.trials},
                  {"successes", s.successes},
                  {"success_rate", number_or_null(s.success_rate())},
                  {"failures", failures},
                  {"placement_error", pick_place_stat_json(s.placement_error)},
                  {"cycle_time", pick_place_stat_json(s.cycle_time)},
                  {"grasp_force", pick_place_stat_json(s.grasp_force)},
                  {"weld_jump", pick_place_stat_json(s.weld_jump)},
                  {"weld_settle", pick_place_stat_json(s.weld_settle)},
                  {"max_slip", pick_place_stat_json(s.max_slip)}}},
                {"recording", common.record.empty() ? Json(nullptr) : Json(common.record)},
                {"trials", trials}});
  } else {
    print_pick_place_batch(std::cout, cli, result, threads);
    if (!common.record.empty())
      std::cout << "recordings: " << common.record << "/seed_K (one folder per trial)\n";
    if (std::any_of(pages.begin(), pages.end(),
                    [](const TrialPage& p) { return p.report.has_value(); }))
      std::cout << "replay pages: " << common.record
                << "/seed_K.html (one beside each recording; open one in a browser)\n";
    if (result.interrupted) std::cout << stopped << ": the figures above are of the trials done\n";
  }
  if (result.interrupted) throw InterruptedError(stopped, interrupt_signal());
  if (common.html && pages_done < pages.size())
    throw InterruptedError("interrupted after " + std::to_string(pages_done) + " of " +
                               std::to_string(pages.size()) + " replay pages",
                           interrupt_signal());
  if (s.successes < s.trials) throw Error(failed + (page_errors.empty() ? "" : "; " + page_errors));
  if (!page_errors.empty()) throw Error(page_errors);
}

}  // namespace mjarm::cli
