// `mjarm run docking`: the peg-in-hole evaluation (docs/docking.md) — one run, the 27-offset
// grid per controller in parallel, or the free-space tracking gate.

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <numbers>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/scenarios/docking_scenario.hpp"
#include "mjarm/tasks/docking/grid.hpp"
#include "mjarm/tasks/docking/plot.hpp"
#include "mjarm/tasks/docking/task.hpp"
#include "mjarm/tasks/docking/tracking_gate.hpp"
#include "parameter_options.hpp"

namespace mjarm::cli {

namespace {

constexpr double kDockDeg = std::numbers::pi / 180.0;

/// The laws named by --controller: one, or every law built ("all").
std::vector<DockingLaw> docking_laws_of(const std::string& name) {
  if (name == "all") {
    const std::span<const DockingLaw> all = docking_laws();
    return {all.begin(), all.end()};
  }
  try {
    return {docking_law(name)};
  } catch (const Error& e) {
    throw UsageError(std::string(e.what()) + ", or all");
  }
}

std::string dock_mm(double metres, int decimals = 3) { return fixed(metres * 1e3, decimals); }
std::string dock_deg(double radians, int decimals = 3) {
  return fixed(radians / kDockDeg, decimals);
}

std::string failures_text(const std::vector<std::string>& failures) {
  return failures.empty() ? "none" : join(failures);
}

std::string failure_counts(const std::map<std::string, int>& counts) {
  std::vector<std::string> items;
  for (const auto& [why, n] : counts) items.push_back(why + " ×" + std::to_string(n));
  return items.empty() ? "none" : join(items);
}

DockingOptions base_options(const DockingCliOptions& cli) {
  DockingOptions o;
  o.controller.source = cli.sensorless ? ForceSource::observer : ForceSource::sensor;
  o.joint_friction = cli.friction;
  try {
    o.motion.reference = docking_reference(cli.reference);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  o.motion.insertion_speed = cli.insertion_speed;
  o.motion.preload = cli.preload;
  if (!cli.stiffness.empty()) {
    const Eigen::Map<const Vector6d> k(cli.stiffness.data());
    if (!(k.array() > 0.0).all()) throw UsageError("--stiffness values must be positive");
    o.controller.se3_stiffness = k;
    o.controller.cic_stiffness = k;
    o.controller.hqp_stiffness = k;  // K0
  }
  if (!cli.offset.empty()) {
    o.offset = {cli.offset[0] * 1e-3, cli.offset[1] * 1e-3, cli.offset[2] * kDockDeg};
    try {
      check(o.offset);
    } catch (const Error&) {
      throw UsageError("--offset DX DY DYAW: DX and DY within ±50 mm, DYAW within ±180°, got " +
                       compact(cli.offset[0]) + " " + compact(cli.offset[1]) + " " +
                       compact(cli.offset[2]));
    }
  }
  // the registry's parameters that have no option of their own here
  apply_parameters(docking_scenario(), cli.parameters, o, docking_parameters);
  return o;
}

// ---- one run

void print_docking(std::ostream& os, const DockingReport& r) {
  const DockingPlan& p = r.plan;
  const DockingMetrics& m = r.metrics;
  os << "docking on iiwa14, " << r.controller << " (" << to_string(r.source)
     << (r.joint_friction ? ", joint friction" : "") << ")\n";
  print_fields(os,
               {{"offset", dock_mm(p.offset.dx, 1) + " mm, " + dock_mm(p.offset.dy, 1) + " mm, " +
                               dock_deg(p.offset.dyaw, 1) + "°"},
                {"phases [s]", "approach " + fixed(p.approach_time, 3) + ", insert " +
                                   fixed(p.insert_time, 3) + ", hold " + fixed(p.hold_time, 3)}},
               2);
  os << "result: " << to_string(r.outcome) << " — " << r.run.message << '\n';
  std::vector<std::pair<std::string, std::string>> fields{
      {"failures", failures_text(m.failures)},
      {"peak force [N]", fixed(m.peak_force, 2) + " (axial " + fixed(m.peak_axial_force, 2) + ")"},
      {"peak axial moment [N·m]", fixed(m.peak_axial_moment, 4)},
      {"steady axial force [N]",
       fixed(m.steady_axial_force, 3) + " (wrench norm " + fixed(m.steady_wrench, 3) + ")"},
      {"depth [mm]", dock_mm(m.min_depth) + " of " + dock_mm(p.full_depth, 1)},
      {"lateral [mm]", "max " + dock_mm(m.max_lateral) + ", mean " + dock_mm(m.steady_lateral)},
      {"tilt [°]", "max " + dock_deg(m.max_tilt, 4) + ", mean " + dock_deg(m.steady_tilt, 4)},
      {"settled", "max " + fixed(m.max_speed * 1e3, 3) + " mm/s, " + dock_deg(m.max_angular_speed) +
                      " °/s over the last second"},
      {"in contact", fixed(100.0 * m.contact_fraction, 1) + " % of the last second"},
      {"free-motion RMS", dock_mm(m.position_rms, 4) + " mm, " + dock_deg(m.orientation_rms, 4) +
                              "° (" + std::to_string(m.free_samples) + " ticks)"},
      {"joints", "position " + fixed(m.max_joint_position, 1) + " %, velocity " +
                     fixed(m.max_joint_velocity, 1) + " % of the limits"},
      {"min manipulability", fixed(m.min_manipulability, 4)},
      {"saturation", fixed(100.0 * m.saturation, 2) + " % of the ticks"}};
  if (r.searches > 0)
    fields.push_back(
        {"search", std::to_string(r.searches) + " miss(es), first at " + fixed(r.miss_time, 3) +
                       " s, " + fixed(r.search_time, 3) + " s searching" +
                       (std::isnan(r.drop_time) ? std::string(", no drop")
                                                : ", drop at " + fixed(r.drop_time, 3) + " s")});
  if (r.bad_wrench_ticks > 0)
    fields.push_back({"bad sensor readings", std::to_string(r.bad_wrench_ticks)});
  if (r.controller == "hqp-ac")
    fields.push_back({"QP fallbacks", "least squares " + std::to_string(r.qp_least_squares) +
                                          ", null space dropped " +
                                          std::to_string(r.qp_null_space_dropped) + " ticks"});
  if (!r.recording.empty())
    fields.push_back(
        {"recording", r.recording.string() +
                          (r.recording_error.empty() ? "" : " (not written: see the error)")});
  if (!r.video.empty())
    fields.push_back({"video", r.video.string() + " (" +
                                   (r.video_written ? std::to_string(r.video_frames) + " frames"
                                                    : std::string("not written: see the error")) +
                                   "; " + r.video_camera + ")"});
  print_fields(os, fields, 2);
}

Json docking_json(const DockingReport& r) {
  return Json{
      {"scenario", "docking"},
      {"controller", r.controller},
      {"source", to_string(r.source)},
      {"joint_friction", r.joint_friction},
      {"offset", fields_to_json(r.plan.offset)},
      {"approach_time", r.plan.approach_time},
      {"insert_time", r.plan.insert_time},
      {"hold_time", r.plan.hold_time},
      {"outcome", to_string(r.outcome)},
      {"status", to_string(r.run.status)},
      {"message", r.run.message},
      {"end_time", r.run.end_time},
      {"metrics", fields_to_json(r.metrics)},
      {"search",
       {{"searches", r.searches},
        {"search_time", r.search_time},
        {"miss_time", std::isnan(r.miss_time) ? Json(nullptr) : Json(r.miss_time)},
        {"drop_time", std::isnan(r.drop_time) ? Json(nullptr) : Json(r.drop_time)}}},
      {"bad_wrench_ticks", r.bad_wrench_ticks},
      {"qp_fallbacks",
       {{"least_squares", r.qp_least_squares}, {"null_space_dropped", r.qp_null_space_dropped}}},
      {"recording", r.recording.empty() ? Json(nullptr) : Json(r.recording.string())},
      {"recording_error", r.recording_error.empty() ? Json(nullptr) : Json(r.recording_error)},
      {"video", r.video.empty() ? Json(nullptr)
                                : Json{{"path", r.video.string()},
                                       {"frames", r.video_frames},
                                       {"written", r.video_written},
                                       {"camera", r.video_camera},
                                       {"error", r.video_error.empty() ? Json(nullptr)
                                                                       : Json(r.video_error)}}}};
}

void run_single(const DockingCliOptions& cli, DockingLaw law, const DockingVideo& video,
                const std::string& record, bool json) {
  DockingOptions o = base_options(cli);
  o.controller.law = law;
  o.video = video;
  o.record = record;
  const DockingReport r = run_docking(o);
  std::string plot_error;
  plot::PlotInfo figure;
  if (!cli.plot.empty() && r.outcome != DockingOutcome::interrupted) {
    try {
      figure = plot_docking(r, cli.plot);
    } catch (const Error& e) {
      plot_error = e.what();
    }
  }
  if (json) {
    Json doc = docking_json(r);
    doc["plot"] = figure.path.empty() ? Json(nullptr) : Json(figure.path.string());
    print_json(doc);
  } else {
    print_docking(std::cout, r);
    if (!figure.path.empty())
      std::cout << "  plot                      " << figure.path.string() << '\n';
  }
  if (r.outcome == DockingOutcome::interrupted) {
    // where each output stands: the recording is kept (its status says interrupted), a video
    // cut short is not written, nor is a plot
    std::string outputs;
    if (!r.recording_error.empty())
      outputs += "; " + r.recording_error;
    else if (!r.recording.empty())
      outputs += "; the recording is in " + r.recording.string();
    if (!r.video_error.empty()) outputs += "; " + r.video_error;
    if (!plot_error.empty()) outputs += "; " + plot_error;
    throw InterruptedError(
        "the docking run was interrupted at t = " + fixed(r.run.end_time, 3) + " s" + outputs,
        interrupt_signal());
  }
  if (!plot_error.empty()) throw Error(plot_error);
  if (!r.recording_error.empty()) throw Error(r.recording_error);
  if (!r.video_error.empty()) throw Error(r.video_error);
  if (!r.ok())
    throw Error("the peg did not seat (" + failures_text(r.metrics.failures) +
                "): " + r.run.message);
}

// ---- the grid

void run_grid(const DockingCliOptions& cli, const std::vector<DockingLaw>& laws, bool json) {
  DockingGridOptions grid;
  grid.base = base_options(cli);
  grid.jobs = cli.jobs;
  DockingSceneOptions scene_options;
  scene_options.joint_friction = cli.friction;
  scene_options.geometry = grid.base.geometry;
  grid.base.scene = std::make_shared<const DockingScene>(build_docking_scene(scene_options));
  const int per_law = static_cast<int>(grid.x.size() * grid.y.size() * grid.yaw.size());
  const int planned = per_law * static_cast<int>(laws.size());
  Progress progress("docking runs", planned);
  std::vector<DockingGridResult> results;
  int done_before = 0;
  for (const DockingLaw law : laws) {
    grid.base.controller.law = law;
    results.push_back(
        run_docking_grid(grid, [&](int done, int) { progress.update(done_before + done); }));
    done_before += static_cast<int>(results.back().runs.size());
    if (results.back().interrupted) break;
  }
  progress.finish();
  const bool interrupted = !results.empty() && results.back().interrupted;
  bool all_seated = true;
  for (const DockingGridResult& g : results)
    all_seated = all_seated && g.seated == static_cast<int>(g.runs.size());
  const std::string stopped = "interrupted after " + std::to_string(done_before) + " of " +
                              std::to_string(planned) + " docking runs";
  if (json) {
    Json rows = Json::array();
    for (const DockingGridResult& g : results) {
      Json runs = Json::array();
      for (const DockingGridRun& run : g.runs)
        runs.push_back({{"offset", fields_to_json(run.offset)},
                        {"outcome", to_string(run.outcome)},
                        {"metrics", fields_to_json(run.metrics)}});
      Json failures = Json::object();
      for (const auto& [why, n] : g.failures) failures[why] = n;
      rows.push_back({{"controller", g.controller},
                      {"source", to_string(g.source)},
                      {"joint_friction", g.joint_friction},
                      {"planned", g.planned},
                      {"runs", static_cast<int>(g.runs.size())},
                      {"seated", g.seated},
                      {"max_peak_force", g.max_peak_force},
                      {"max_peak_axial_force", g.max_peak_axial_force},
                      {"max_peak_axial_moment", g.max_peak_axial_moment},
                      {"steady_axial_force", {g.min_steady_axial_force, g.max_steady_axial_force}},
                      {"max_lateral", g.max_lateral},
                      {"max_tilt", g.max_tilt},
                      {"max_position_rms", g.max_position_rms},
                      {"max_orientation_rms", g.max_orientation_rms},
                      {"failures", failures},
                      {"offsets", runs}});
    }
    print_json({{"scenario", "docking"},
                {"grid", true},
                {"interrupted", interrupted},
                {"controllers", rows}});
  } else {
    std::cout << "docking grid: X, Y ∈ {−6, 0, 6} mm × yaw ∈ {−15, 0, 15}°, "
              << (cli.sensorless ? "sensorless (momentum observer)" : "F/T sensor")
              << (cli.friction ? ", joint friction" : "") << ", preload " << compact(cli.preload)
              << " N\n";
    Table table({{"controller", Table::Align::left},
                 {"seated"},
                 {"peak force [N]"},
                 {"peak axial [N]"},
                 {"axial moment [N·m]"},
                 {"steady axial [N]"},
                 {"lateral [mm]"},
                 {"tilt [°]"},
                 {"free RMS [mm]"},
                 {"failures", Table::Align::left}});
    for (const DockingGridResult& g : results)
      table.add_row({g.controller, std::to_string(g.seated) + "/" + std::to_string(g.runs.size()),
                     fixed(g.max_peak_force, 2), fixed(g.max_peak_axial_force, 2),
                     fixed(g.max_peak_axial_moment, 3),
                     fixed(g.min_steady_axial_force, 3) + "–" + fixed(g.max_steady_axial_force, 3),
                     dock_mm(g.max_lateral), dock_deg(g.max_tilt), dock_mm(g.max_position_rms, 4),
                     failure_counts(g.failures)});
    table.print(std::cout, 0);
    std::cout << "(worst over the offsets; failures: reason × runs)\n";
  }
  if (interrupted) throw InterruptedError(stopped, interrupt_signal());
  if (!all_seated) throw Error("some docking runs did not seat (see the 'seated' column)");
}

// ---- the tracking gate

void run_gate(const DockingCliOptions& cli, const std::vector<DockingLaw>& laws, bool json) {
  TrackingGateOptions o;
  const DockingOptions base = base_options(cli);
  if (!same_geometry(base.geometry, DockingGeometry{}))
    throw UsageError("the tracking gate (--gate) runs in free space: --geometry.* does not apply");
  o.controller = base.controller;
  o.joint_friction = cli.friction;
  DockingSceneOptions scene_options;
  scene_options.joint_friction = cli.friction;
  o.scene = std::make_shared<const DockingScene>(build_docking_scene(scene_options));
  const TrackingGateTargets targets;
  Progress progress("tracking gates", static_cast<std::int64_t>(laws.size()));
  std::vector<TrackingGateReport> reports;
  for (const DockingLaw law : laws) {
    o.controller.law = law;
    reports.push_back(run_tracking_gate(o));
    progress.update(static_cast<std::int64_t>(reports.size()));
    if (reports.back().run.status == RunStatus::interrupted) break;
  }
  progress.finish();
  bool all_pass = true;
  for (const TrackingGateReport& r : reports) all_pass = all_pass && passes(r, targets);
  auto errors_json = [](const TrackingErrors& e) {
    return Json{{"position_rms", e.position_rms},
                {"orientation_rms", e.orientation_rms},
                {"max_position", e.max_position},
                {"max_orientation", e.max_orientation},
                {"samples", e.samples}};
  };
  if (json) {
    Json rows = Json::array();
    for (const TrackingGateReport& r : reports)
      rows.push_back({{"controller", r.controller},
                      {"source", to_string(r.source)},
                      {"status", to_string(r.run.status)},
                      {"contact_ticks", r.contact_ticks},
                      {"circle", errors_json(r.loops[0])},
                      {"figure_eight", errors_json(r.loops[1])},
                      {"total", errors_json(r.total)},
                      {"passes", passes(r, targets)}});
    print_json(
        {{"scenario", "docking"},
         {"gate", true},
         {"radius", o.radius},
         {"frequency", o.frequency},
         {"targets",
          {{"position_rms", targets.position_rms}, {"orientation_rms", targets.orientation_rms}}},
         {"controllers", rows}});
  } else {
    std::cout << "tracking gate: circle r = " << compact(o.radius * 1e3) << " mm at "
              << compact(o.frequency) << " Hz, then a figure-eight, y-z plane, no contact ("
              << (cli.sensorless ? "sensorless" : "F/T sensor")
              << (cli.friction ? ", joint friction" : "") << ")\n";
    Table table({{"controller", Table::Align::left},
                 {"circle RMS [mm]"},
                 {"eight RMS [mm]"},
                 {"position RMS [mm]"},
                 {"orientation RMS [°]"},
                 {"max [mm]"},
                 {"contacts"},
                 {"gate", Table::Align::left}});
    for (const TrackingGateReport& r : reports)
      table.add_row({r.controller, dock_mm(r.loops[0].position_rms, 4),
                     dock_mm(r.loops[1].position_rms, 4), dock_mm(r.total.position_rms, 4),
                     dock_deg(r.total.orientation_rms, 4),
                     dock_mm(std::max(r.loops[0].max_position, r.loops[1].max_position), 4),
                     std::to_string(r.contact_ticks), passes(r, targets) ? "pass" : "FAIL"});
    table.print(std::cout, 0);
    std::cout << "(targets: position RMS ≤ " << compact(targets.position_rms * 1e3)
              << " mm, orientation RMS ≤ " << compact(targets.orientation_rms / kDockDeg) << "°)\n";
  }
  if (!reports.empty() && reports.back().run.status == RunStatus::interrupted)
    throw InterruptedError("the tracking gate was interrupted", interrupt_signal());
  if (!all_pass) throw Error("a controller missed the tracking gate (see the 'gate' column)");
}

}  // namespace

void add_docking_options(CLI::App& app, DockingCliOptions& o) {
  app.add_flag("--sensorless", o.sensorless,
               "docking: the momentum observer estimates the contact wrench (no F/T sensor)");
  app.add_flag("--friction", o.friction,
               "docking: the variant with joint friction (Franka frictionloss on joints 1–7)");
  app.add_option("--offset", o.offset,
                 "docking: error of the believed socket pose DX DY [mm] DYAW [°]")
      ->expected(3)
      ->check(finite_number());
  CLI::Option* grid = app.add_flag(
      "--grid", o.grid, "docking: the 27 offsets {−6, 0, 6} mm × {−15, 0, 15}° in parallel");
  CLI::Option* gate = app.add_flag(
      "--gate", o.gate, "docking: the free-space tracking gate (circle, then figure-eight)");
  grid->excludes(gate);
  CLI::Option* map = app.add_flag(
      "--map", o.map,
      "docking: the capture region, radial offset 0–15 mm × 8 directions × yaw 0–25°, in "
      "parallel (with --plot DIR: a polar heat map per law and docking_map.json)");
  map->excludes(grid)->excludes(gate);
  app.add_option("--map-step", o.map_step, "docking --map: radial step [mm]")
      ->check(number_in(0.5, 15.0))
      ->capture_default_str();
  app.add_option("--map-yaw-step", o.map_yaw_step, "docking --map: yaw step [°]")
      ->check(number_in(1.0, 25.0))
      ->capture_default_str();
  app.add_option("--reference", o.reference, "docking: two-phase | single")->capture_default_str();
  app.add_option("--insertion-speed", o.insertion_speed,
                 "docking: cruise speed of the two-phase insertion [m/s]")
      ->check(number_in(0.001, 0.1))
      ->capture_default_str();
  app.add_option("--preload", o.preload, "docking: force pushed in during the hold [N]")
      ->check(number_in(0.0, 30.0))
      ->capture_default_str();
  app.add_option("--stiffness", o.stiffness,
                 "docking: the law's stiffness KX KY KZ [N/m] KRX KRY KRZ [N·m/rad]")
      ->expected(6)
      ->check(finite_number());
  app.add_option("--plot", o.plot, "docking: draw the force and stiffness figure into DIR");
  app.add_option("--jobs", o.jobs, "docking --grid: worker threads (0: one per core)")
      ->check(count_in(0, 64))
      ->capture_default_str();
}

void run_docking_scenario(const DockingCliOptions& cli, const std::string& controller,
                          const DockingVideo& video, const std::string& record, bool json,
                          double max_video_frames) {
  const std::vector<DockingLaw> laws = docking_laws_of(controller);
  if (!video.path.empty()) {
    // the work before it starts: every simulated second of the run films --fps frames
    const std::array<double, 3> t =
        docking_phase_times(base_options(cli).motion, DockingGeometry{});
    const double seconds = t[0] + t[1] + t[2];
    const double frames = std::floor(seconds * video.options.fps) + 1.0;
    if (frames > max_video_frames)
      throw UsageError("--video at --fps " + compact(video.options.fps) + " of a " +
                       fixed(seconds, 1) + " s docking run would film " + compact(frames) +
                       " frames; at most " + compact(max_video_frames) +
                       " (lower --fps or raise --insertion-speed)");
  }
  if ((cli.grid || cli.gate) &&
      (!cli.offset.empty() || !record.empty() || !video.path.empty() || !cli.plot.empty()))
    throw UsageError(
        "--offset, --record, --video and --plot belong to a single docking run, "
        "not to --grid or --gate");
  if (cli.map && (!cli.offset.empty() || !record.empty() || !video.path.empty()))
    throw UsageError("--offset, --record and --video belong to a single docking run, not to --map");
  if (!cli.grid && !cli.gate && !cli.map && laws.size() != 1)
    throw UsageError("--controller all needs --grid, --gate or --map");
  if (!cli.plot.empty()) check_output_folder(cli.plot, "--plot");
  const InterruptGuard interrupts;  // Ctrl-C stops the runs at their next tick
  if (cli.grid) return run_grid(cli, laws, json);
  if (cli.gate) return run_gate(cli, laws, json);
  if (cli.map) return run_docking_map(cli, laws, base_options(cli), json);
  run_single(cli, laws.front(), video, record, json);
}

}  // namespace mjarm::cli
