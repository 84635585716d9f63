// `mjarm ik MODEL --site S --pos x y z [--quat w x y z | --rpy r p y]`: inverse kinematics.

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/global_ik.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"
#include "mjarm/lie/rotation.hpp"
#include "output.hpp"

namespace mjarm::cli {
namespace {

struct IkOptions {
  std::string model;
  std::string site;
  std::vector<double> pos;
  std::vector<double> quat;
  std::vector<double> rpy;
  std::vector<double> from;
  std::string key;
  bool allow_outside_range = false;
  std::string solver;
  bool solver_is_default = false;  // no --solver: a position target may fall back to restarts
  double timeout_ms = 100.0;
  std::uint64_t seed = 0;
  int trace = 0;
  bool json = false;
};

/// One traced iterate of the local solver.
struct TracedIterate {
  int iteration = 0;
  double position_error = 0.0;
  double orientation_error = 0.0;
};

/// What `solve_ik` did.
struct IkRun {
  IkResult result;
  bool restarts_needed = false;  // the default position solve fell back to global restarts
  int global_attempts = 0;       // local runs of the global solver (0 when it did not run)
  std::vector<TracedIterate> trace;
  double seconds = 0.0;
};

/// The start of a solve: --from or --key when given, else the model's `home` keyframe, else the
/// middle of the joint ranges (qpos0 may lie outside the limits: the panda's does).
Configuration ik_start(const Chain& chain, const std::vector<double>& from,
                       const std::string& key, bool allow_outside_range) {
  if (!from.empty() || !key.empty()) {
    Configuration start = resolve_configuration(chain, from, key, "--from", allow_outside_range);
    if (!start.outside_range.empty()) start.source += " (outside the joint ranges)";
    return start;
  }
  const std::vector<std::string> keys = chain.robot().keyframe_names();
  if (std::find(keys.begin(), keys.end(), "home") != keys.end()) {
    Configuration start = resolve_configuration(chain, {}, "home");
    start.source += " (default)";
    return start;
  }
  Configuration start = resolve_configuration(chain, {}, "");
  start.q = chain.center();
  chain.scatter(start.q, start.qpos.data());
  start.source = "middle of the joint ranges (default)";
  return start;
}

/// The global solver's options from the command line.
GlobalIkOptions global_options(const IkOptions& options) {
  GlobalIkOptions global;
  global.timeout = std::chrono::duration<double, std::milli>(options.timeout_ms);
  global.seed = options.seed;
  return global;
}

/// Runs the chosen solver and times it. The default for a position target is the local DLS
/// solver, then, when it ends not_converged (a local minimum at the joint limits, a stall), the
/// global solver's restarts from the same start.
IkRun solve_ik(const IkOptions& options, const Chain& chain, const Configuration& start,
               const Pose& X_WT, bool has_orientation) {
  const auto begin = std::chrono::steady_clock::now();
  IkRun run;
  IkIterationCallback trace;
  if (options.trace > 0) {
    trace = [&run, every = options.trace](const IkIteration& it) {
      if (it.iteration % every == 0)
        run.trace.push_back({it.iteration, it.position_error, it.orientation_error});
    };
  }
  if (options.solver == "dls") {
    if (has_orientation)
      throw UsageError(
          "solver 'dls' reaches a position only; use --solver pose or global for --quat/--rpy");
    PositionIkOptions local;
    local.on_iteration = trace;
    PositionIk ik(chain, local);
    ik.set_fixed_qpos(start.qpos);
    run.result = ik.solve(X_WT.p, start.q);
    if (options.solver_is_default && run.result.status == IkStatus::not_converged) {
      GlobalIk global(chain, global_options(options));
      global.set_fixed_qpos(start.qpos);
      const int local_iterations = run.result.iterations;
      run.result = global.solve_position(X_WT.p, start.q);
      run.result.iterations += local_iterations;
      run.restarts_needed = true;
      run.global_attempts = global.stats().attempts;
    }
  } else if (options.solver == "pose") {
    PoseIkOptions local;
    local.on_iteration = trace;
    PoseIk ik(chain, local);
    ik.set_fixed_qpos(start.qpos);
    run.result = ik.solve(X_WT, start.q);
  } else {
    GlobalIk ik(chain, global_options(options));
    ik.set_fixed_qpos(start.qpos);
    run.result = ik.solve(X_WT, start.q);
    run.global_attempts = ik.stats().attempts;
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return run;
}

/// "1 attempt", "4 attempts".
std::string attempts_text(int attempts) {
  return std::to_string(attempts) + (attempts == 1 ? " attempt" : " attempts");
}

/// The "restarts" line of the text report.
std::string restarts_text(const IkOptions& options, const IkRun& run) {
  if (options.solver == "global")
    return std::to_string(run.global_attempts - 1) + " (" + attempts_text(run.global_attempts) +
           ")";
  if (run.restarts_needed)
    return std::string("needed: dls ended not_converged, global restarts ") +
           (run.result.ok() ? "solved it" : "found no solution") + " in " +
           attempts_text(run.global_attempts);
  if (options.solver_is_default) return "not needed";
  return "none (--solver " + options.solver + " runs alone)";
}

}  // namespace

Command add_ik_command(CLI::App& root) {
  auto options = std::make_shared<IkOptions>();
  CLI::App* app = root.add_subcommand(
      "ik", "inverse kinematics: joint values that put a site at a position (and orientation)");
  add_model_argument(*app, options->model)->required();
  add_site_option(*app, options->site);
  app->add_option("--pos", options->pos, "target position x y z in the world [m]")
      ->required()
      ->expected(3)
      ->check(finite_number());
  auto* quat =
      app->add_option("--quat", options->quat, "target orientation as a quaternion w x y z")
          ->expected(4)
          ->check(finite_number());
  app->add_option("--rpy", options->rpy, "target orientation as roll pitch yaw [rad], R = Rz·Ry·Rx")
      ->expected(3)
      ->check(finite_number())
      ->excludes(quat);
  auto* from =
      app->add_option("--from", options->from,
                      "start configuration (chain joints, root first); default: the 'home' "
                      "keyframe when the model has one, else the middle of the joint ranges")
          ->expected(1, -1)
          ->check(finite_number());
  app->add_option("--key", options->key, "start from this keyframe (e.g. home)")->excludes(from);
  add_allow_outside_range_flag(*app, options->allow_outside_range);
  auto* solver =
      app->add_option("--solver", options->solver,
                      "dls (position only), pose (local, SE(3) log error) or global (restarts); "
                      "default: global with an orientation, else dls followed by global "
                      "restarts when dls does not converge")
          ->check(CLI::IsMember({"dls", "pose", "global"}));
  app->add_option("--timeout-ms", options->timeout_ms,
                  "time budget of the global solver [ms]; default 100")
      ->check(timeout_ms());
  app->add_option("--seed", options->seed, "seed of the global solver's restarts")
      ->check(non_negative_integer());
  app->add_option("--trace", options->trace,
                  "print the error every N iterations of the local solver (dls, pose)")
      ->check(count_in(1, 1000000));
  add_json_flag(*app, options->json);

  return {app, [options, solver] {
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            const Configuration start = ik_start(chain, options->from, options->key,
                                                   options->allow_outside_range);
            const bool has_orientation = !options->quat.empty() || !options->rpy.empty();
            options->solver_is_default = solver->count() == 0;
            if (options->solver.empty()) options->solver = has_orientation ? "global" : "dls";
            if (options->trace > 0 && options->solver == "global")
              throw UsageError(
                  "--trace follows the local solvers (dls, pose); the global solver has none");
            Pose X_WT;
            X_WT.p = Eigen::Vector3d(options->pos[0], options->pos[1], options->pos[2]);
            if (!options->quat.empty()) {
              X_WT.R = rotation_from_quaternion(Eigen::Vector4d(
                  options->quat[0], options->quat[1], options->quat[2], options->quat[3]));
            } else if (!options->rpy.empty()) {
              X_WT.R = rotation_from_rpy(options->rpy[0], options->rpy[1], options->rpy[2]);
            } else {
              // position-only solvers ignore it; pose solvers keep the start orientation
              ChainKinematics kin(chain);
              kin.set_fixed_qpos(start.qpos);
              X_WT.R = kin.update(start.q).R;
            }
            const IkRun run = solve_ik(*options, chain, start, X_WT, has_orientation);
            const IkResult& result = run.result;
            const bool show_orientation = has_orientation || options->solver != "dls";

            if (options->json) {
              Json doc{{"model", robot.name()},
                       {"frame", chain.frame().name},
                       {"solver", options->solver},
                       {"start", start.source},
                       {"start_outside_range", start.outside_range},
                       {"restarts_needed", run.restarts_needed},
                       {"global_attempts", run.global_attempts},
                       {"joints", chain.joint_names()},
                       {"q", vector_json(result.q)},
                       {"status", to_string(result.status)},
                       {"position_error", result.position_error},
                       {"orientation_error",
                        show_orientation ? Json(result.orientation_error) : Json(nullptr)},
                       {"iterations", result.iterations},
                       {"time_ms", run.seconds * 1e3}};
              if (options->trace > 0) {
                Json trace = Json::array();
                for (const TracedIterate& t : run.trace) {
                  trace.push_back({{"iteration", t.iteration},
                                   {"position_error", t.position_error},
                                   {"orientation_error", t.orientation_error}});
                }
                doc["trace"] = trace;
              }
              print_json(doc);
            } else {
              print_fields(std::cout, {{"model", robot.name()},
                                       {"frame", chain.frame().name},
                                       {"solver", options->solver},
                                       {"start", start.source},
                                       {"target position [m]", vector_text(X_WT.p, 4)}});
              if (options->trace > 0) {
                std::cout << "\ntrace (" << options->solver << ", every " << options->trace
                          << (options->trace == 1 ? " iteration)\n" : " iterations)\n");
                std::vector<Table::Column> columns{{"iteration"}, {"position error [m]"}};
                if (show_orientation) columns.push_back({"orientation error [rad]"});
                Table table(columns);
                for (const TracedIterate& t : run.trace) {
                  std::vector<std::string> row{std::to_string(t.iteration),
                                               general(t.position_error, 3)};
                  if (show_orientation) row.push_back(general(t.orientation_error, 3));
                  table.add_row(row);
                }
                table.print(std::cout);
              }
              std::cout << "\nsolution\n";
              Table table({{"joint", Table::Align::left}, {"value [rad or m]"}});
              for (int i = 0; i < chain.size(); ++i)
                table.add_row(
                    {chain.joint_names()[static_cast<std::size_t>(i)], fixed(result.q[i], 6)});
              table.print(std::cout);
              std::cout << '\n';
              std::vector<std::pair<std::string, std::string>> fields = {
                  {"status", to_string(result.status)},
                  {"position error [m]", general(result.position_error, 3)}};
              if (show_orientation)
                fields.push_back({"orientation error [rad]", general(result.orientation_error, 3)});
              fields.push_back({"restarts", restarts_text(*options, run)});
              fields.push_back({"iterations", std::to_string(result.iterations)});
              fields.push_back({"time [ms]", fixed(run.seconds * 1e3, 3)});
              print_fields(std::cout, fields);
            }
            if (!result.ok()) {
              throw Error(std::string("no solution within tolerance (") + to_string(result.status) +
                          "); the printed q is the closest configuration found");
            }
          }};
}

}  // namespace mjarm::cli
