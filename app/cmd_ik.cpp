// `mjarm ik MODEL --site S --pos x y z [--quat w x y z | --rpy r p y]`: inverse kinematics.

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
  std::string solver;
  double timeout_ms = 5.0;
  std::uint64_t seed = 0;
  bool json = false;
};

/// Runs the chosen solver and times it.
IkResult solve(const IkOptions& options, const Chain& chain, const Configuration& start,
               const Pose& X_WT, bool has_orientation, double& seconds) {
  const auto begin = std::chrono::steady_clock::now();
  IkResult result;
  if (options.solver == "dls") {
    if (has_orientation)
      throw UsageError(
          "solver 'dls' reaches a position only; use --solver pose or global for --quat/--rpy");
    PositionIk ik(chain);
    ik.set_fixed_qpos(start.qpos);
    result = ik.solve(X_WT.p, start.q);
  } else if (options.solver == "pose") {
    PoseIk ik(chain);
    ik.set_fixed_qpos(start.qpos);
    result = ik.solve(X_WT, start.q);
  } else {
    GlobalIkOptions global;
    global.timeout = std::chrono::duration<double, std::milli>(options.timeout_ms);
    global.seed = options.seed;
    GlobalIk ik(chain, global);
    ik.set_fixed_qpos(start.qpos);
    result = ik.solve(X_WT, start.q);
  }
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return result;
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
      app->add_option("--from", options->from, "start configuration (chain joints, root first)")
          ->expected(1, -1)
          ->check(finite_number());
  app->add_option("--key", options->key, "start from this keyframe (e.g. home)")->excludes(from);
  app->add_option("--solver", options->solver,
                  "dls (position only), pose (local, SE(3) log error) or global (restarts); "
                  "default: global with an orientation, dls without")
      ->check(CLI::IsMember({"dls", "pose", "global"}));
  app->add_option("--timeout-ms", options->timeout_ms, "time budget of the global solver [ms]")
      ->check(CLI::PositiveNumber);
  app->add_option("--seed", options->seed, "seed of the global solver's restarts")
      ->check(non_negative_integer());
  add_json_flag(*app, options->json);

  return {app, [options] {
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            const Configuration start = resolve_configuration(chain, options->from, options->key);
            const bool has_orientation = !options->quat.empty() || !options->rpy.empty();
            if (options->solver.empty()) options->solver = has_orientation ? "global" : "dls";
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
            double seconds = 0.0;
            const IkResult result = solve(*options, chain, start, X_WT, has_orientation, seconds);

            if (options->json) {
              print_json({{"model", robot.name()},
                          {"frame", chain.frame().name},
                          {"solver", options->solver},
                          {"joints", chain.joint_names()},
                          {"q", vector_json(result.q)},
                          {"status", to_string(result.status)},
                          {"position_error", result.position_error},
                          {"orientation_error", has_orientation || options->solver != "dls"
                                                    ? Json(result.orientation_error)
                                                    : Json(nullptr)},
                          {"iterations", result.iterations},
                          {"time_ms", seconds * 1e3}});
            } else {
              print_fields(std::cout, {{"model", robot.name()},
                                       {"frame", chain.frame().name},
                                       {"solver", options->solver},
                                       {"start", start.source},
                                       {"target position [m]", vector_text(X_WT.p, 4)}});
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
              if (has_orientation || options->solver != "dls")
                fields.push_back({"orientation error [rad]", general(result.orientation_error, 3)});
              fields.push_back({"iterations", std::to_string(result.iterations)});
              fields.push_back({"time [ms]", fixed(seconds * 1e3, 3)});
              print_fields(std::cout, fields);
            }
            if (!result.ok()) {
              throw Error(std::string("no solution within tolerance (") + to_string(result.status) +
                          "); the printed q is the closest configuration found");
            }
          }};
}

}  // namespace mjarm::cli
