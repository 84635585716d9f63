// `mjarm run shelf-pick`: one pick or every robot × controller (--all), its figures and video
// (docs/tasks.md). The demo prints a pick with the same functions.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "mjarm/scenarios/shelf_pick_scenario.hpp"
#include "mjarm/tasks/shelf_pick/shelf_pick.hpp"
#include "output.hpp"
#include "parameter_options.hpp"
#include "run_subcommands.hpp"

namespace mjarm::cli {

namespace {

std::string controller_title(const std::string& name) {
  if (name == "ct") return "computed torque (ct)";
  if (name == "osc") return "operational-space impedance (osc)";
  if (name == "task-pd") return "task-space PD (task-pd)";
  if (name == "accel") return "acceleration control through inverse dynamics (accel)";
  return name;
}

std::string point_text(const Eigen::Vector3d& p) {
  return "(" + fixed(p.x(), 4) + ", " + fixed(p.y(), 4) + ", " + fixed(p.z(), 4) + ")";
}

/// Millimetres with 4 decimals, "—" for NaN (the event did not happen).
std::string mm(double metres) { return std::isnan(metres) ? "—" : fixed(metres * 1e3, 4); }
std::string sec(double seconds) { return std::isnan(seconds) ? "—" : fixed(seconds, 3); }

/// Throws UsageError (exit 2) for an unknown robot or controller, with the choices.
void check_names(const std::string& robot, const std::string& controller) {
  try {
    shelf_pick_robot(robot);
    check_shelf_pick_controller(controller);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

Json shelf_pick_json(const ShelfPickReport& r) {
  const ShelfPickPlan& p = r.plan;
  const PickMetrics& m = r.metrics;
  Json doc{{"scenario", "shelf-pick"},
           {"robot", p.robot->name},
           {"model", p.model.name()},
           {"controller", p.controller},
           {"seed", p.seed},
           {"pick", vector_json(p.pick)},
           {"pick_drawn", p.pick_drawn},
           {"start_q", vector_json(p.goal.q_start)},
           {"target_q", vector_json(p.goal.q_target)},
           {"distance", (p.pick - p.goal.X_WS.p).norm()},
           {"approach_time", p.goal.approach_time},
           {"control_period", r.control_period},
           {"time_limit", r.time_limit},
           {"tolerance", p.goal.criteria.tolerance},
           {"hold_time", p.goal.criteria.hold_time},
           {"outcome", to_string(r.outcome)},
           {"held", m.held},
           {"status", to_string(r.run.status)},
           {"message", r.run.message},
           {"end_time", r.run.end_time}};
  doc["metrics"] = fields_to_json(m);
  doc["saturated_ticks"] = r.saturated_ticks;
  doc["recording"] = r.recording.empty() ? Json(nullptr) : Json(r.recording.string());
  doc["recording_error"] = r.recording_error.empty() ? Json(nullptr) : Json(r.recording_error);
  doc["video"] = nullptr;
  if (!r.video.empty())
    doc["video"] = Json{{"path", r.video.string()},
                        {"frames", r.video_frames},
                        {"camera", r.video_camera},
                        {"written", r.video_written},
                        {"error", r.video_error.empty() ? Json(nullptr) : Json(r.video_error)}};
  return doc;
}

void print_shelf_pick(std::ostream& os, const ShelfPickReport& r,
                      const std::vector<std::pair<std::string, std::string>>& outputs) {
  const ShelfPickPlan& p = r.plan;
  const PickMetrics& m = r.metrics;
  os << "shelf pick on " << p.robot->name << " (" << p.model.name() << "), "
     << controller_title(p.controller) << ", seed " << p.seed << '\n';
  print_fields(os,
               {{"pick point [m]",
                 point_text(p.pick) + (p.pick_drawn ? "  (drawn from the seed)" : "  (--pick)")},
                {"start q [rad]", vector_text(p.goal.q_start)},
                {"distance [m]", fixed((p.pick - p.goal.X_WS.p).norm(), 4)},
                {"approach [s]", fixed(p.goal.approach_time, 3) + " (minimum jerk)"},
                {"control period [s]", compact(r.control_period)}},
               2);
  os << "result: " << to_string(r.outcome) << " — " << r.run.message << '\n';
  const std::string tol = compact(p.goal.criteria.tolerance * 1e3) + " mm";
  std::vector<std::pair<std::string, std::string>> fields{
      {"time to " + tol + " [s]", sec(m.time_to_tolerance)},
      {"first entry [s]", sec(m.first_entry_time)},
      {"overshoot [mm]", mm(m.overshoot)},
      {"steady state [mm]", "mean " + mm(m.steady_state_mean) + ", max " + mm(m.steady_state_max) +
                                " (last " + compact(p.goal.criteria.steady_window * 1e3) +
                                " ms of the hold)"},
      {"whole hold [mm]", "mean " + mm(m.hold_mean) + ", max " + mm(m.hold_max)},
      {"hold", m.held ? "held " + compact(p.goal.criteria.hold_time * 1e3) +
                            " ms, released at t = " + fixed(m.hold_end_time, 3) + " s"
                      : "not held (error at the end " + mm(m.final_error) + " mm)"},
      {"exits from tolerance", std::to_string(m.exits)},
      {"saturated ticks", std::to_string(r.saturated_ticks)}};
  if (!p.goal.position_only)
    fields.insert(fields.begin() + 5,
                  {"orientation [mrad]", "max " + mm(m.orientation_error_max) + " over the hold"});
  if (!r.recording.empty())
    fields.push_back({"recording", r.recording.string() +
                                       (r.recording_error.empty()
                                            ? " (state.csv, task.csv, events.csv, summary.json)"
                                            : " (not written: see the error)")});
  if (!r.video.empty())
    fields.push_back({"video", r.video.string() + " (" +
                                   (r.video_written ? std::to_string(r.video_frames) + " frames"
                                                    : std::string("not written: see the error")) +
                                   "; " + r.video_camera + ")"});
  fields.insert(fields.end(), outputs.begin(), outputs.end());
  print_fields(os, fields, 2);
}

std::string run_outputs_text(const ShelfPickReport& r) {
  std::string text;
  if (!r.recording_error.empty())
    text += "; " + r.recording_error;
  else if (!r.recording.empty())
    text += "; the recording is in " + r.recording.string();
  if (!r.video_error.empty())
    text += "; " + r.video_error;
  else if (r.video_written)
    text += "; the video is in " + r.video.string();
  return text;
}

namespace {

/// Every robot × controller, each over @p seeds seeds from @p first: worst figures per row.
void run_all(const ShelfPickOptions& base, int seeds, bool json) {
  struct Row {
    std::string robot, controller;
    int held = 0, runs = 0;
    double time = 0.0, overshoot = 0.0, steady_mean = 0.0, steady_max = 0.0, hold_mean = 0.0;
    std::int64_t saturated = 0;
  };
  std::vector<Row> rows;
  const auto& robots = shelf_pick_robots();
  const auto& controllers = shelf_pick_controllers();
  const std::int64_t planned =
      static_cast<std::int64_t>(robots.size() * controllers.size()) * seeds;
  Progress progress("shelf picks", planned);
  std::int64_t done = 0;
  // Ctrl-C or SIGTERM: stop at the next tick, report the rows done so far (mjarm/interrupt.hpp)
  bool interrupted = false;
  for (const auto& robot : robots) {
    for (const auto& controller : controllers) {
      Row row{robot.name, controller};
      for (int k = 0; k < seeds && !interrupted; ++k) {
        ShelfPickOptions options = base;
        options.request.robot = robot.name;
        options.request.controller = controller;
        options.request.seed = base.request.seed + static_cast<std::uint64_t>(k);
        const ShelfPickReport r = run_shelf_pick(options);
        interrupted = interrupt_requested() || r.outcome == PickOutcome::interrupted;
        if (interrupted) break;  // a run cut short is not a row's figure
        const PickMetrics& m = r.metrics;
        ++row.runs;
        row.saturated = std::max(row.saturated, r.saturated_ticks);
        progress.update(++done);
        if (!r.ok()) continue;
        ++row.held;
        row.time = std::max(row.time, m.time_to_tolerance);
        row.overshoot = std::max(row.overshoot, m.overshoot);
        row.steady_mean = std::max(row.steady_mean, m.steady_state_mean);
        row.steady_max = std::max(row.steady_max, m.steady_state_max);
        row.hold_mean = std::max(row.hold_mean, m.hold_mean);
      }
      if (row.runs > 0) rows.push_back(row);
      if (interrupted) break;
    }
    if (interrupted) break;
  }
  progress.finish();
  const std::string stopped = "interrupted after " + std::to_string(done) + " of " +
                              std::to_string(planned) + " shelf picks";
  // the exit code says whether every pick held, whatever the output format
  const bool all_held =
      std::all_of(rows.begin(), rows.end(), [](const Row& row) { return row.held == row.runs; });
  const char* const not_held = "some shelf picks did not hold (see the 'held' column)";
  if (json) {
    Json doc = Json::array();
    for (const Row& row : rows)
      doc.push_back({{"robot", row.robot},
                     {"controller", row.controller},
                     {"runs", row.runs},
                     {"held", row.held},
                     {"worst_time_to_tolerance", row.time},
                     {"worst_overshoot", row.overshoot},
                     {"worst_steady_state_mean", row.steady_mean},
                     {"worst_steady_state_max", row.steady_max},
                     {"worst_hold_mean", row.hold_mean},
                     {"worst_saturated_ticks", row.saturated}});
    print_json({{"scenario", "shelf-pick"},
                {"first_seed", base.request.seed},
                {"seeds", seeds},
                {"interrupted", interrupted},
                {"runs", done},
                {"rows", doc}});
    if (interrupted) throw InterruptedError(stopped, interrupt_signal());
    if (!all_held) throw Error(not_held);
    return;
  }
  if (seeds == 1) {
    std::cout << "shelf pick, seed " << base.request.seed << '\n';
  } else {
    std::cout << "shelf pick, seeds " << base.request.seed << "–"
              << base.request.seed + static_cast<std::uint64_t>(seeds) - 1
              << ": the worst figure of the held runs in each row\n";
  }
  Table table({{"robot", Table::Align::left},
               {"controller", Table::Align::left},
               {"held"},
               {"time to 1 mm [s]"},
               {"overshoot [mm]"},
               {"steady mean [mm]"},
               {"steady max [mm]"},
               {"hold mean [mm]"},
               {"saturated ticks"}});
  for (const Row& row : rows)
    table.add_row({row.robot, row.controller,
                   std::to_string(row.held) + "/" + std::to_string(row.runs), fixed(row.time, 3),
                   fixed(row.overshoot * 1e3, 4), fixed(row.steady_mean * 1e3, 4),
                   fixed(row.steady_max * 1e3, 4), fixed(row.hold_mean * 1e3, 4),
                   std::to_string(row.saturated)});
  table.print(std::cout, 0);
  if (interrupted) {
    std::cout << stopped << ": the rows above hold the runs done\n";
    throw InterruptedError(stopped, interrupt_signal());
  }
  if (!all_held) throw Error(not_held);
}

}  // namespace

/// `mjarm run shelf-pick`: one pick, or every robot × controller (--all).
Command add_shelf_pick_subcommand(CLI::App& run) {
  struct Options {
    std::string robot = "panda", controller = "osc", record;
    std::vector<double> pick;
    SimulationCli sim;
    VideoCli video;
    bool all = false, json = false;
    int seeds = 1;
    std::unique_ptr<ParameterOptions> parameters;
  };
  auto o = std::make_shared<Options>();
  const Scenario& scenario = find_scenario("shelf-pick");
  CLI::App* app =
      run.add_subcommand("shelf-pick", std::string(scenario.doc()) + " (docs/tasks.md)");
  app->allow_extras();
  app->add_option("--robot", o->robot, "planar2 | panda")->capture_default_str();
  app->add_option("--controller", o->controller, "ct | osc | task-pd | accel")
      ->capture_default_str();
  CLI::Option* pick = app->add_option("--pick", o->pick,
                                      "pick point x y z in the world [m] "
                                      "(default: drawn from the seed)")
                          ->expected(3)
                          ->check(finite_number());
  add_simulation_options(*app, o->sim,
                         "seed: draws the pick point when --pick is absent and perturbs the start "
                         "(same seed, same run bit for bit)",
                         "time allowed after the approach to enter the tolerance and hold [s]");
  CLI::Option* record =
      app->add_option("--record", o->record, "record state, task and events into DIR");
  CLI::Option* video = add_video_options(
      *app, o->video, "the run",
      "video camera: a camera of the model, or 'follow' (the tool tip); default: a free camera "
      "framing the robot and the pick point");
  app->add_flag("--all", o->all, "every robot × controller (a table of the worst figures)")
      ->excludes(pick)
      ->excludes(record)
      ->excludes(video);
  app->add_option("--seeds", o->seeds, "with --all: run seeds K … K+N−1 per row")
      ->check(count_in(1, 10000))
      ->capture_default_str();
  add_json_flag(*app, o->json);
  o->parameters = std::make_unique<ParameterOptions>(*app, scenario);
  return {app, [o, app] {
            refuse_extras(*app);
            if (o->seeds != 1 && !o->all) throw UsageError("--seeds needs --all");
            // the outputs are checked before the work
            if (!o->record.empty()) check_output_folder(o->record, "--record");
            if (!o->video.path.empty()) check_output_file(o->video.path, "--video");
            ShelfPickOptions options;
            options.request.robot = o->robot;
            options.request.controller = o->controller;
            options.request.seed = o->sim.seed;
            if (!o->pick.empty())
              options.request.pick = Eigen::Vector3d(o->pick[0], o->pick[1], o->pick[2]);
            options.record = o->record;
            options.control_period = o->sim.control_period;
            options.max_acceleration = o->sim.max_acceleration;
            options.settle_time = o->sim.settle_time;
            apply_parameters(shelf_pick_scenario(), o->parameters->values(), options,
                             shelf_pick_parameters);
            if (!o->video.path.empty()) {
              // the work before it starts: the run lasts the approach (a second or two) plus
              // --settle-time, and every simulated second films --fps frames
              const double frames = o->video.fps * o->sim.settle_time;
              if (frames > kMaxVideoFrames)
                throw UsageError("--video at --fps " + readable(o->video.fps) +
                                 " with --settle-time " + readable(o->sim.settle_time) +
                                 " s would film up to " + readable(std::ceil(frames)) +
                                 " frames after the approach; at most " +
                                 readable(kMaxVideoFrames) + " (lower --fps or --settle-time)");
              const PixelSize size = parse_pixel_size(o->video.size);
              options.video.path = o->video.path;
              options.video.camera = o->video.camera;
              options.video.options.width = size.width;
              options.video.options.height = size.height;
              options.video.options.fps = o->video.fps;
            }
            const InterruptGuard interrupts;  // Ctrl-C ends the run with a finalized recording
            if (o->all) return run_all(options, o->seeds, o->json);

            check_names(o->robot, o->controller);
            const ShelfPickReport report = run_shelf_pick(options);
            if (o->json) {
              print_json(shelf_pick_json(report));
            } else {
              print_shelf_pick(std::cout, report, {});
            }
            // every failure is named: the run's, the recording's and the video's
            const std::string outputs = run_outputs_text(report);
            if (report.outcome == PickOutcome::interrupted)
              throw InterruptedError("the shelf pick was interrupted at t = " +
                                         fixed(report.run.end_time, 3) + " s" + outputs,
                                     interrupt_signal());
            if (!report.ok())
              throw Error("the shelf pick ended " + std::string(to_string(report.outcome)) + ": " +
                          report.run.message + outputs);
            if (!report.recording_error.empty() || !report.video_error.empty())
              throw Error(outputs.substr(2));  // without the leading "; "
          }};
}

}  // namespace mjarm::cli
