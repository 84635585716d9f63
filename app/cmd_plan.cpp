// `mjarm plan ROBOT --waypoints FILE`: plans a checked, timed joint trajectory through Cartesian
// waypoints (docs/planning.md) and prints the per-waypoint checks; `--out` writes it as CSV.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/planning/waypoint_file.hpp"
#include "mjarm/planning/waypoint_path_plan.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "mjarm/plot/trajectory_plot.hpp"

namespace mjarm::cli {

namespace {

/// One value for every joint, or one per joint.
Eigen::VectorXd per_joint(const std::vector<double>& values, int n, const char* option) {
  if (values.empty()) return {};
  if (values.size() == 1) return Eigen::VectorXd::Constant(n, values[0]);
  if (static_cast<int>(values.size()) != n)
    throw UsageError(std::string(option) + " takes 1 value or " + std::to_string(n) +
                     " (one per joint), got " + std::to_string(values.size()));
  for (double v : values)
    if (!(v > 0.0)) throw UsageError(std::string(option) + " values must be > 0");
  return Eigen::Map<const Eigen::VectorXd>(values.data(), n);
}

std::string plan_mm(double metres) { return fixed(metres * 1e3, 3); }

/// Most CSV rows `--out` writes (as `mjarm traj`): a rate × duration beyond it is a usage error.
constexpr double kMaxCsvRows = 1e6;

/// Writes t, q, q̇, q̈ and the tool position every @p period seconds, row by row.
void write_csv(const std::string& path, const Chain& chain, const JointSpline& s, double period) {
  FileWriter out(path, FileWriter::Mode::replace, "trajectory CSV");
  const int n = chain.size();
  std::string header = "t";
  for (const char* kind : {"q", "qd", "qdd"})
    for (int i = 0; i < n; ++i) header += std::string(",") + kind + "_" + chain.joint_names()[i];
  out.write(header + ",x,y,z\n");
  ChainKinematics kin(chain);
  Eigen::VectorXd q(n), qd(n), qdd(n);
  const auto steps = static_cast<std::int64_t>(std::ceil(s.duration() / period - 1e-9));
  char number[32];
  const auto put = [&](const char* format, double value) {
    out.write(number,
              static_cast<std::size_t>(std::snprintf(number, sizeof number, format, value)));
  };
  for (std::int64_t k = 0; k <= steps; ++k) {
    // Ctrl-C: stop at once, the partial CSV removed and the old file kept
    if (k % 1024 == 0) stop_writing_if_interrupted("plan", path);
    const double t = std::min(s.duration(), static_cast<double>(k) * period);
    s.at(t, q, qd, qdd);
    put("%.10g", t);
    for (const Eigen::VectorXd* v : {&q, &qd, &qdd})
      for (int i = 0; i < n; ++i) put(",%.10g", (*v)[i]);
    const Eigen::Vector3d p = kin.update(q).p;
    for (int i = 0; i < 3; ++i) put(",%.10g", p[i]);
    out.write("\n");
  }
  stop_writing_if_interrupted("plan", path);
  out.commit();  // the whole CSV or the old file: a write error names the file and the reason
}

/// Draws @p dir/trajectory.png: q, q̇, q̈ and the jerk of every joint sampled every @p period
/// seconds, with the plan's velocity and acceleration limits dashed. Returns the PNG's path.
std::string plot_plan(const std::string& dir, const PlannedPath& p, double period,
                      const std::string& size_text) {
  const JointSpline& s = p.result.trajectory;
  const Chain& chain = *p.chain;
  const int n = chain.size();
  plot::TrajectorySeries series;
  series.title = "plan on " + p.robot.name() + ", " + std::to_string(p.poses.size()) +
                 " waypoints, T = " + compact(s.duration()) + " s";
  series.unit = "rad";
  for (int i = 0; i < n; ++i) series.axes.push_back(chain.joint_names()[i]);
  const auto steps = static_cast<std::int64_t>(std::ceil(s.duration() / period - 1e-9));
  for (std::int64_t k = 0; k <= steps; ++k)
    series.t.push_back(std::min(s.duration(), static_cast<double>(k) * period));
  for (auto& v : series.values)
    v.assign(static_cast<std::size_t>(n), std::vector<double>(series.t.size()));
  Eigen::VectorXd x[4] = {Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n),
                          Eigen::VectorXd(n)};
  for (std::size_t j = 0; j < series.t.size(); ++j) {
    s.at(series.t[j], x[0], x[1], x[2], x[3]);
    for (std::size_t k = 0; k < 4; ++k)
      for (int i = 0; i < n; ++i) series.values[k][static_cast<std::size_t>(i)][j] = x[k][i];
  }
  const Eigen::VectorXd& v = p.result.limits.max_velocity;
  const Eigen::VectorXd& a = p.result.limits.max_acceleration;
  series.limits[1].assign(v.data(), v.data() + v.size());
  series.limits[2].assign(a.data(), a.data() + a.size());
  const PixelSize size = parse_pixel_size(size_text);
  plot::PlotOptions options;
  options.width = size.width;
  options.height = size.height;
  return plot::plot_trajectory(series, dir, options).path.string();
}

}  // namespace

PlannedPath plan_path(const PlanCliOptions& o, std::optional<Robot> model) {
  const WaypointPath file = load_waypoints(o.waypoints);
  PlannedPath out{model ? std::move(*model) : load_model(o.model), std::nullopt, {}, {}, {}};
  std::string site = o.site.empty() && file.frame ? *file.frame : o.site;
  out.chain.emplace(out.robot, resolve_site(out.robot, site));
  const Chain& chain = *out.chain;
  std::string key = o.key;
  if (key.empty() && o.q.empty() && out.robot.model().nkey > 0) {
    const std::vector<std::string> keys = out.robot.keyframe_names();
    if (std::find(keys.begin(), keys.end(), "home") != keys.end()) key = "home";
  }
  out.start = resolve_configuration(chain, o.q, key, "--q", false,
                                    "a plan starts inside the joint ranges");
  const int n = chain.size();
  PlanOptions options;
  options.limits.max_velocity = per_joint(o.max_velocity, n, "--velocity-limit");
  options.limits.max_acceleration = per_joint(o.max_acceleration, n, "--acceleration-limit");
  options.limits.max_torque = per_joint(o.max_torque, n, "--torque-limit");
  options.checks.min_singular_value = o.min_sigma;
  options.seed = o.seed;
  // ompl:NAME: a waypoint the straight joint motion from the previous knot to the local IK
  // solution does not reach is reached by OMPL's NAME, instead of other IK branches and the
  // random detour (PlanOptions::ompl_fallback)
  if (o.planner.rfind("ompl:", 0) == 0) {
    options.ompl.planner = parse_enum<OmplPlannerType>(o.planner.substr(5), "OMPL planner");
    options.ik_branches = 0;
    options.detour_samples = 0;
    options.ompl_fallback = true;
  } else if (o.planner != "waypoint") {
    throw UsageError("--planner: '" + o.planner +
                     "' is not waypoint, ompl:rrtconnect, ompl:prm, ompl:rrtstar or "
                     "ompl:bitstar");
  }
  WaypointPathPlan plan = plan_waypoint_path(chain, out.start.qpos, file, options);
  out.poses = std::move(plan.poses);
  out.result = std::move(plan.result);
  return out;
}

Json plan_json(const PlannedPath& p) {
  const PlanResult& r = p.result;
  Json waypoints = Json::array();
  for (const WaypointReport& w : r.waypoints)
    waypoints.push_back({{"index", w.index},
                         {"position", vector_json(w.X_WT.p)},
                         {"q", vector_json(w.q)},
                         {"ik", to_string(w.ik)},
                         {"position_error", w.position_error},
                         {"orientation_error", w.orientation_error},
                         {"branch", w.branch},
                         {"detour", w.detour},
                         {"ompl_knots", w.ompl_knots},
                         {"check", to_string(w.check.failure)},
                         {"sigma_min", w.check.sigma_min},
                         {"segment_min_sigma", w.min_sigma},
                         {"segment_max_torque_ratio", w.max_torque_ratio},
                         {"time", w.time},
                         {"message", w.message}});
  Json torque = Json::array();
  for (Eigen::Index i = 0; i < r.limits.max_torque.size(); ++i)
    torque.push_back(number_or_null(r.limits.max_torque[i]));
  return Json{{"model", p.robot.name()},
              {"frame", p.chain->frame().name},
              {"start", p.start.source},
              {"start_q", vector_json(p.start.q)},
              {"status", to_string(r.status)},
              {"failed_waypoint", r.failed_waypoint},
              {"message", r.message},
              {"duration", r.trajectory.duration()},
              {"sample_spacing", r.sample_spacing},
              {"samples", r.samples},
              {"limits",
               {{"max_velocity", vector_json(r.limits.max_velocity)},
                {"max_acceleration", vector_json(r.limits.max_acceleration)},
                {"max_torque", torque}}},
              {"waypoints", waypoints}};
}

void print_plan(std::ostream& os, const PlannedPath& p) {
  const PlanResult& r = p.result;
  os << "plan on " << p.robot.name() << ", frame '" << p.chain->frame().name << "', from "
     << p.start.source << ", " << p.poses.size() << " waypoints\n";
  Table table({{"#"},
               {"x y z [m]", Table::Align::left},
               {"branch"},
               {"detour"},
               {"IK error [mm]"},
               {"σmin"},
               {"min σ on the way"},
               {"max torque [%]"},
               {"at [s]"},
               {"result", Table::Align::left}});
  for (const WaypointReport& w : r.waypoints)
    table.add_row({std::to_string(w.index), vector_text(w.X_WT.p, 3),
                   w.branch == 0 ? "local" : "global " + std::to_string(w.branch),
                   w.detour ? "yes" : "no", plan_mm(w.position_error), fixed(w.check.sigma_min, 3),
                   r.ok() ? fixed(w.min_sigma, 3) : "—",
                   r.ok() ? fixed(w.max_torque_ratio * 100.0, 1) : "—",
                   r.ok() ? fixed(w.time, 3) : "—", w.message});
  table.print(os, 2);
  os << "result: " << to_string(r.status) << " — " << r.message << '\n';
  if (r.ok())
    print_fields(os,
                 {{"duration [s]", fixed(r.trajectory.duration(), 3)},
                  {"checked every [s]", compact(r.sample_spacing)},
                  {"max velocity [rad/s]", vector_text(r.limits.max_velocity, 3)},
                  {"max acceleration [rad/s²]", vector_text(r.limits.max_acceleration, 2)}},
                 2);
}

void add_plan_options(CLI::App& app, PlanCliOptions& o, bool with_seed) {
  app.add_option("--waypoints", o.waypoints,
                 "waypoint file: JSON ({\"waypoints\": [{\"position\": [x, y, z]}, …]}) or CSV "
                 "rows x,y,z[,qw,qx,qy,qz] (docs/planning.md)")
      ->required();
  app.add_option("--q", o.q, "start joint values [rad or m] (default: keyframe 'home', else qpos0)")
      ->check(finite_number());
  app.add_option("--key", o.key, "start at this keyframe");
  app.add_option("--velocity-limit", o.max_velocity,
                 "joint velocity limits [rad/s]: one value or one per joint (default 1)")
      ->check(finite_number());
  app.add_option("--acceleration-limit", o.max_acceleration,
                 "joint acceleration limits [rad/s²]: one or one per joint (default: from the "
                 "actuators' torque limits and the inertia at the start)")
      ->check(finite_number());
  app.add_option("--torque-limit", o.max_torque,
                 "joint torque limits [N·m]: one or one per joint (default: the actuators')")
      ->check(finite_number());
  app.add_option("--min-sigma", o.min_sigma, "smallest accepted singular value of the 6×n Jacobian")
      ->check(finite_number())
      ->capture_default_str();
  app.add_option("--planner", o.planner,
                 "waypoint: IK branches, then a random detour, then OMPL's RRT-Connect; "
                 "ompl:rrtconnect|prm|rrtstar|bitstar: the local IK solution, reached by the "
                 "straight joint motion or else by OMPL's planner (docs/planning.md)")
      ->capture_default_str();
  if (with_seed)
    app.add_option("--seed", o.seed, "seed of the IK branches and detours")
        ->check(non_negative_integer())
        ->capture_default_str();
}

Command add_plan_command(CLI::App& root) {
  auto o = std::make_shared<PlanCliOptions>();
  auto out = std::make_shared<std::string>();
  auto rate = std::make_shared<double>(500.0);
  auto json = std::make_shared<bool>(false);
  auto plot_dir = std::make_shared<std::string>();
  auto size = std::make_shared<std::string>("1280x1200");
  CLI::App* app = root.add_subcommand(
      "plan",
      "plan a checked joint trajectory through Cartesian waypoints, or with --cartesian "
      "follow straight lines through them (docs/planning.md)");
  add_model_argument(*app, o->model);
  add_site_option(*app, o->site);
  add_plan_options(*app, *o, true);
  app->add_option("--out", *out, "write the trajectory as CSV (t, q, qd, qdd, tool x y z)");
  app->add_option("--rate", *rate, "CSV rows (and plot samples) per second [Hz]")
      ->check(finite_number())
      ->capture_default_str();
  app->add_option("--plot", *plot_dir,
                  "draw DIR/trajectory.png: joint position, velocity, acceleration and jerk "
                  "against the plan's limits (needs gnuplot)");
  app->add_option("--size", *size, "plot size WIDTHxHEIGHT [pixels]")
      ->capture_default_str()
      ->check(pixel_size({200, 300}));
  add_json_flag(*app, *json);
  auto cartesian = std::make_shared<CartesianCliOptions>();
  add_cartesian_options(*app, *cartesian);
  return {app, [o, out, rate, json, plot_dir, size, cartesian] {
            if (cartesian->on) {
              if (o->min_sigma < 0.0) throw UsageError("--min-sigma must be >= 0");
              run_cartesian_plan(*o, *cartesian, *json);
              return;
            }
            if (!(*rate > 0.0) || *rate > 1e5)
              throw UsageError("--rate must be in (0, 100000] Hz, got " + compact(*rate));
            if (o->min_sigma < 0.0) throw UsageError("--min-sigma must be >= 0");
            if (!out->empty()) check_output_file(*out, "--out");  // before the work
            if (!plot_dir->empty()) {
              check_output_folder(*plot_dir, "--plot");
              plot::find_gnuplot();
            }
            const PlannedPath p = plan_path(*o);
            // Ctrl-C or SIGTERM while gnuplot draws or the CSV is written: nothing half-written
            // is left, an old CSV is kept (exit 130/143); a signal during the planning ends the
            // process with nothing written yet
            std::optional<InterruptGuard> interrupts;
            if (p.result.ok() && (!plot_dir->empty() || !out->empty())) interrupts.emplace();
            std::string plot_path, plot_stopped;
            if (p.result.ok() && !plot_dir->empty()) {
              try {
                plot_path = plot_plan(*plot_dir, p, 1.0 / *rate, *size);
              } catch (const Error& e) {
                if (!interrupt_requested()) throw;
                plot_stopped = e.what();  // the plan is printed first, then the interrupt
              }
            }
            if (*json) {
              Json document = plan_json(p);
              if (!plot_path.empty()) document["plot"] = plot_path;
              print_json(document);
            } else {
              print_plan(std::cout, p);
            }
            if (!p.result.ok()) throw Error("no plan: " + p.result.message);
            if (!plot_stopped.empty())
              throw InterruptedError(
                  "plan: interrupted; " + plot_stopped +
                      (out->empty() ? "" : "; '" + *out + "' was not written"),
                  interrupt_signal());
            const double duration = p.result.trajectory.duration();
            if (!out->empty() && std::ceil(duration * *rate) + 1 > kMaxCsvRows)
              throw UsageError("the trajectory lasts " + compact(duration) + " s: at --rate " +
                               compact(*rate) + " Hz the CSV would have " +
                               compact(std::ceil(duration * *rate) + 1) +
                               " rows, more than 10⁶: lower --rate");
            if (!out->empty()) {
              write_csv(*out, *p.chain, p.result.trajectory, 1.0 / *rate);
              if (!*json) std::cout << "  trajectory written to " << *out << '\n';
            }
            if (!plot_path.empty() && !*json) std::cout << "  plot: " << plot_path << '\n';
            if (interrupts) report_interrupt_after_writing("plan", out->empty() ? plot_path : *out);
          }};
}

}  // namespace mjarm::cli
