// `mjarm demo`: the main job — the shelf pick on the panda under operational-space control,
// recorded, filmed, plotted and written as a replay page (one HTML file) — then a short tour of the
// library on a bundled arm: model, forward kinematics at the home keyframe, a seeded workspace
// analysis and a pose-IK round trip.

#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "mjarm/plot/plots.hpp"
#include "mjarm/tasks/shelf_pick/shelf_pick.hpp"
#include "mjarm/web/replay_html_json.hpp"
#include "output.hpp"
#include "run_replay.hpp"

namespace mjarm::cli {

// the shelf pick's printing, shared with `mjarm run` (defined in cmd_run.cpp)
Json shelf_pick_json(const ShelfPickReport& report);
/// @p outputs: more of the run's outputs, listed after its video (the demo's replay page).
void print_shelf_pick(std::ostream& os, const ShelfPickReport& report,
                      const std::vector<std::pair<std::string, std::string>>& outputs);
/// "; the recording is in …; <why the video failed>": every output of the run and its failure.
std::string run_outputs_text(const ShelfPickReport& report);

namespace {

/// IK back to the pose FK gave at the configuration, started from the middle of the ranges.
struct RoundTrip {
  Eigen::VectorXd seed;
  IkResult result;
  double seconds = 0.0;
};

RoundTrip ik_round_trip(const Chain& chain, const Configuration& config, const Pose& X_WT) {
  RoundTrip trip;
  trip.seed = chain.center();
  PoseIk ik(chain);
  ik.set_fixed_qpos(config.qpos);
  const auto start = std::chrono::steady_clock::now();
  trip.result = ik.solve(X_WT, trip.seed);
  trip.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trip;
}

struct DemoOptions {
  std::string model = "panda";
  std::string site;
  std::string key = "home";
  std::size_t samples = 20000;
  std::uint64_t seed = 1;
  std::string record = "out/demo";
  std::string video = "out/demo.mp4";
  std::string html = "out/demo.html";
  bool html_given = false;  ///< --html on the command line: a build without the page fails
  bool json = false;
};

void run_demo(const DemoOptions& options) {
  // every argument and output is checked before the work: a typo fails in milliseconds, not
  // after the shelf pick
  const Robot robot = load_model(options.model);
  const Chain chain(robot, resolve_site(robot, options.site));
  const Configuration config = resolve_configuration(chain, {}, options.key);
  check_output_folder(options.record, "--record");
  if (!options.video.empty()) check_output_file(options.video, "--video", true);
  // the replay page: by default only where this build holds it (it says why not), on demand
  // always
  std::string html_missing;
  if (!options.html.empty()) {
    if (options.html_given) check_replay_available("--html");
    html_missing = replay_html_missing();
    if (html_missing.empty()) check_output_file(options.html, "--html", true);
  }
  plot::find_gnuplot();  // the plots of the recording need it (names the package to install)

  // with --json one document at the end; it holds the parts done when a later one fails
  Json doc;
  std::ostream& os = std::cout;
  const auto fail = [&](const std::string& why) {
    if (options.json) print_json(doc);
    if (interrupt_requested()) throw InterruptedError(why, interrupt_signal());
    throw Error(why);
  };
  const InterruptGuard interrupts;  // Ctrl-C ends the current part with its report

  // the main job: the shelf pick (a finalized recording even on Ctrl-C)
  ShelfPickOptions pick;
  pick.request.robot = "panda";
  pick.request.controller = "osc";
  pick.request.seed = options.seed;
  pick.record = options.record;
  pick.video.path = options.video;
  if (pick.video.path.has_parent_path())
    std::filesystem::create_directories(pick.video.path.parent_path());
  const ShelfPickReport report = run_shelf_pick(pick);
  // the recording's replay page next to the video: one HTML file to open in a browser
  std::optional<ReplayHtmlReport> page;
  std::string page_error;
  const bool recorded =
      !report.recording.empty() && report.recording_error.empty() && !interrupt_requested();
  if (recorded && !options.html.empty() && html_missing.empty()) {
    try {
      const std::filesystem::path folder = std::filesystem::path(options.html).parent_path();
      if (!folder.empty()) std::filesystem::create_directories(folder);
      page = write_run_replay(report.recording, options.html);
    } catch (const Error& e) {
      page_error = "replay page " + options.html + ": " + e.what();
    }
  }
  if (options.json) {
    doc["shelf_pick"] = shelf_pick_json(report);
    doc["replay"] = page ? replay_html_json(*page, report.recording) : Json(nullptr);
    if (!html_missing.empty() && !options.html.empty()) doc["replay_missing"] = html_missing;
  } else {
    print_heading(os, "shelf pick");
    std::vector<std::pair<std::string, std::string>> outputs;
    if (page)
      outputs.push_back({"replay page", page->path.string() + " (" + std::to_string(page->bytes) +
                                            " bytes, " + std::to_string(page->frames) +
                                            " frames; open it in a browser)"});
    else if (recorded && !options.html.empty())
      outputs.push_back(
          {"replay page",
           "not written: " + (page_error.empty() ? html_missing : std::string("see the error"))});
    print_shelf_pick(os, report, outputs);
    os.flush();
  }
  if (!page_error.empty()) fail(page_error);
  // a failed recording or video fails the demo too, after the report (issue 16, items 6, 8)
  const std::string outputs = run_outputs_text(report);
  if (!report.ok())
    fail("the shelf pick ended " + std::string(to_string(report.outcome)) + ": " +
         report.run.message + outputs);
  if (!report.recording_error.empty() || !report.video_error.empty())
    fail(outputs.substr(2));  // without the leading "; "
  // plots of the recording, beside it (docs/plot.md)
  std::vector<std::filesystem::path> plots;
  try {
    plots = plot::write_plots(report.recording, report.recording / "plots");
  } catch (const Error& e) {
    fail(e.what());  // with --json, the shelf pick's figures still reach stdout
  }
  for (auto& p : plots) p = std::filesystem::proximate(p);  // as given: relative
  if (options.json) {
    doc["plots"] = Json::array();
    for (const auto& p : plots) doc["plots"].push_back(p.string());
  } else {
    os << "plots\n";
    for (const auto& p : plots) os << "  " << p.string() << "\n";
    os.flush();
  }
  if (interrupt_requested()) fail("interrupted after the shelf pick");

  // the tour
  ChainKinematics kin(chain);
  kin.set_fixed_qpos(config.qpos);
  const Pose X_WE = kin.update(config.q);
  if (options.json) {
    doc["model"] = model_json(robot);
    doc["fk"] = pose_json(kin, config, false);
  } else {
    print_heading(os, "model");
    os << robot.name() << ": " << robot.joints().size() << " joints, " << robot.nu()
       << " actuators, frame " << chain.frame().name << " (mjarm info " << options.model
       << " for the tables)\n";
    print_heading(os, "forward kinematics");
    print_pose(os, kin, config, false);
    os.flush();
  }

  const WorkspaceResult workspace = run_workspace(chain, options.samples, options.seed, false);
  if (options.json) {
    doc["workspace"] = workspace_json(chain, workspace);
  } else {
    print_heading(os, "workspace");
    print_workspace(os, chain, workspace);
    os.flush();
  }
  if (workspace.status != SamplingStatus::complete)
    fail("interrupted after " + std::to_string(workspace.samples) + " of " +
         std::to_string(options.samples) + " workspace samples");

  const RoundTrip trip = ik_round_trip(chain, config, X_WE);
  if (options.json) {
    doc["ik"] = Json{{"target", options.key},
                     {"seed", vector_json(trip.seed)},
                     {"q", vector_json(trip.result.q)},
                     {"status", to_string(trip.result.status)},
                     {"position_error", trip.result.position_error},
                     {"orientation_error", trip.result.orientation_error},
                     {"iterations", trip.result.iterations},
                     {"seconds", trip.seconds}};
    print_json(doc);
    return;
  }
  print_heading(os, "inverse kinematics round trip");
  os << "target: the pose above (keyframe '" << options.key
     << "'); seed: the middle of the joint ranges\n";
  print_fields(os,
               {{"status", to_string(trip.result.status)},
                {"iterations", std::to_string(trip.result.iterations)},
                {"position error [m]", general(trip.result.position_error, 3)},
                {"orientation error [rad]", general(trip.result.orientation_error, 3)},
                {"time [ms]", fixed(trip.seconds * 1e3, 3)},
                {"seed q [rad or m]", vector_text(trip.seed)},
                {"solution q [rad or m]", vector_text(trip.result.q)},
                {"keyframe q [rad or m]", vector_text(config.q)}},
               2);
}

}  // namespace

Command add_demo_command(CLI::App& root) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* app = root.add_subcommand(
      "demo",
      "the shelf pick on the panda under operational-space control (recorded), then a tour: "
      "model, FK at home, seeded workspace analysis, pose-IK round trip");
  app->add_option("--model", options->model, "bundled model name or path")->capture_default_str();
  add_site_option(*app, options->site);
  app->add_option("--key", options->key, "keyframe for FK and the IK target")
      ->capture_default_str();
  app->add_option("--samples", options->samples, "workspace samples")
      ->check(count_in(1, kMaxWorkspaceSamples))
      ->capture_default_str();
  app->add_option("--seed", options->seed, "seed of the shelf pick and of the workspace sampling")
      ->check(non_negative_integer())
      ->capture_default_str();
  app->add_option("--record", options->record,
                  "where the shelf pick's recording goes (relative to the current directory)")
      ->capture_default_str();
  app->add_option("--video", options->video,
                  "where the shelf pick's video goes (MP4, rendered headless; '' for none)")
      ->capture_default_str();
  CLI::Option* html =
      app->add_option("--html", options->html,
                      "where the shelf pick's replay page goes (one HTML file, docs/replay.md; '' "
                      "for none; by default written where this build holds the page)")
          ->capture_default_str();
  add_json_flag(*app, options->json);

  return {app, [options, html] {
            options->html_given = html->count() > 0;
            run_demo(*options);
          }};
}

}  // namespace mjarm::cli
