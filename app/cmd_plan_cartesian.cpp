// `mjarm plan ROBOT --waypoints FILE --cartesian`: the tool follows straight lines through the
// waypoints in small Cartesian steps (docs/planning.md, "Cartesian paths") and the command prints
// how far it got: status, fraction, knots.

#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/planning/waypoint_file.hpp"

namespace mjarm::cli {

void add_cartesian_options(CLI::App& app, CartesianCliOptions& o) {
  CLI::Option* flag = app.add_flag(
      "--cartesian", o.on,
      "follow straight lines through the waypoints in small steps (MoveIt's Cartesian path): "
      "prints the status and the fraction followed");
  CartesianPathOptions& p = o.path;
  const auto cartesian = [&](CLI::Option* option) {
    option->needs(flag)->capture_default_str()->check(finite_number());
  };
  cartesian(app.add_option("--max-step", p.max_step,
                           "with --cartesian: largest tool motion between two steps [m]"));
  cartesian(app.add_option("--max-rotation-step", p.max_rotation_step,
                           "with --cartesian: largest tool rotation between two steps [rad]"));
  cartesian(app.add_option(
      "--jump-factor", p.jump_factor,
      "with --cartesian: a step moving the joints more than this × the mean step so far is a "
      "jump (0: off)"));
  cartesian(app.add_option("--jump-revolute", p.jump_revolute,
                           "with --cartesian: a revolute joint moving more than this in one step "
                           "is a jump [rad] (0: off)"));
  cartesian(app.add_option("--jump-prismatic", p.jump_prismatic,
                           "with --cartesian: a prismatic joint moving more than this in one step "
                           "is a jump [m] (0: off)"));
  app.add_flag("--no-collisions", o.no_collisions,
               "with --cartesian: do not judge contacts with the scene")
      ->needs(flag);
  // the options of the timed plan mean nothing for a path of knots
  for (const char* other : {"--velocity-limit", "--acceleration-limit", "--torque-limit", "--seed",
                            "--out", "--plot", "--rate", "--size"})
    if (CLI::Option* option = app.get_option_no_throw(other)) flag->excludes(option);
}

namespace {

struct CartesianRun {
  Robot robot;
  std::optional<Chain> chain;
  Configuration start;
  std::vector<Pose> poses;
  CartesianPathOptions options;
  CartesianPathResult result;
};

CartesianRun follow_path(const PlanCliOptions& o, const CartesianCliOptions& c) {
  CartesianRun run{load_model(o.model), std::nullopt, {}, {}, c.path, {}};
  run.options.check_collisions = !c.no_collisions;
  run.options.checks.min_singular_value = o.min_sigma;
  try {
    check(run.options);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  const WaypointPath file = load_waypoints(o.waypoints);
  const std::string site = o.site.empty() && file.frame ? *file.frame : o.site;
  run.chain.emplace(run.robot, resolve_site(run.robot, site));
  std::string key = o.key;
  if (key.empty() && o.q.empty() && run.robot.model().nkey > 0) {
    const std::vector<std::string> keys = run.robot.keyframe_names();
    if (std::find(keys.begin(), keys.end(), "home") != keys.end()) key = "home";
  }
  run.start = resolve_configuration(*run.chain, o.q, key, "--q", false,
                                    "a Cartesian path starts inside the joint ranges");
  CartesianPathPlanner planner(*run.chain, run.options);
  planner.set_fixed_qpos(run.start.qpos);
  ChainKinematics kin(*run.chain);
  kin.set_fixed_qpos(run.start.qpos);
  run.poses = file.poses(kin.update(run.start.q).R);
  run.result = planner.follow(run.start.q, run.poses);
  return run;
}

Json cartesian_json(const CartesianRun& run) {
  const CartesianPathResult& r = run.result;
  Json positions = Json::array();
  for (const Pose& X : r.poses) positions.push_back(vector_json(X.p));
  return Json{{"model", run.robot.name()},
              {"frame", run.chain->frame().name},
              {"start", run.start.source},
              {"start_q", vector_json(run.start.q)},
              {"waypoints", run.poses.size()},
              {"status", to_string(r.status)},
              {"fraction", r.fraction},
              {"steps", r.steps},
              {"stopped_at_step", r.stopped_at_step},
              {"stopped_at_waypoint", r.stopped_at_waypoint},
              {"message", r.message},
              {"check", to_string(r.check.failure)},
              {"knot_count", r.knot_count()},
              {"max_position_error", r.max_position_error},
              {"max_orientation_error", r.max_orientation_error},
              {"max_joint_step", r.max_joint_step},
              {"options", fields_to_json(run.options)},
              {"knots", matrix_json(r.knots.transpose())},
              {"positions", positions}};
}

void print_cartesian(std::ostream& os, const CartesianRun& run) {
  const CartesianPathResult& r = run.result;
  os << "cartesian path on " << run.robot.name() << ", frame '" << run.chain->frame().name
     << "', from " << run.start.source << ", " << run.poses.size() << " waypoints\n";
  print_fields(
      os,
      {{"steps", std::to_string(r.steps) + " (at most " + compact(run.options.max_step * 1e3) +
                     " mm, " + compact(run.options.max_rotation_step) + " rad each)"},
       {"status", to_string(r.status)},
       {"fraction", fixed(r.fraction, 3)},
       {"knots", std::to_string(r.knot_count())},
       {"reached [m]", r.poses.empty() ? "—" : vector_text(r.poses.back().p, 3)},
       {"max IK error", fixed(r.max_position_error * 1e3, 4) + " mm, " +
                            fixed(r.max_orientation_error * 1e3, 4) + " mrad"},
       {"largest joint step", fixed(r.max_joint_step, 4) + " rad or m"}},
      2);
  os << "result: " << to_string(r.status) << " — " << r.message << '\n';
}

}  // namespace

void run_cartesian_plan(const PlanCliOptions& options, const CartesianCliOptions& cartesian,
                        bool json) {
  const CartesianRun run = follow_path(options, cartesian);
  if (json)
    print_json(cartesian_json(run));
  else
    print_cartesian(std::cout, run);
  if (!run.result.complete())
    throw Error("cartesian path " + std::string(to_string(run.result.status)) + " at fraction " +
                fixed(run.result.fraction, 3) + ": " + run.result.message);
}

}  // namespace mjarm::cli
