#include "mjarm/tasks/shelf_pick/plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/random.hpp"
#include "mjarm/tasks/approach_timing.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {

const std::vector<ShelfPickRobot>& shelf_pick_robots() {
  static const std::vector<ShelfPickRobot> robots = [] {
    std::vector<ShelfPickRobot> list;
    ShelfPickRobot planar2;
    planar2.name = "planar2";
    planar2.model = "planar2_torque";
    planar2.frame = "tip";
    planar2.position_only = true;
    planar2.plane_normal = Eigen::Vector3d::UnitY();
    // below and in front of the home tip (0.658, 0, 0.976): moves of 0.05–0.35 m
    planar2.pick_center = Eigen::Vector3d(0.50, 0.0, 0.80);
    planar2.pick_half_width = Eigen::Vector3d(0.10, 0.0, 0.10);
    planar2.start_perturbation = 0.02;
    planar2.max_speed = 2.0;
    planar2.max_acceleration = 20.0;
    planar2.min_approach_time = 0.15;
    list.push_back(planar2);

    ShelfPickRobot panda;
    panda.name = "panda";
    panda.model = "panda_torque";
    panda.frame = "attachment_site";
    panda.position_only = false;
    // a shelf in front of the robot, below the home flange (0.307, 0, 0.59)
    panda.pick_center = Eigen::Vector3d(0.40, 0.0, 0.45);
    panda.pick_half_width = Eigen::Vector3d(0.08, 0.12, 0.08);
    panda.start_perturbation = 0.02;
    panda.max_speed = 2.0;
    panda.max_acceleration = 20.0;
    panda.min_approach_time = 0.15;
    list.push_back(panda);
    return list;
  }();
  return robots;
}

namespace {

std::string choices(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string point_text(const Eigen::Vector3d& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.4g, %.4g, %.4g)", p.x(), p.y(), p.z());
  return buffer;
}

std::string metres(double v, const char* format = "%.3f") {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

/// The message for a pick point the arm cannot reach.
[[noreturn]] void out_of_reach(const ShelfPickRobot& robot, const Chain& chain,
                               const Eigen::Vector3d& pick, const std::string& why) {
  const ArmReach reach = arm_reach(chain);
  throw Error("pick point " + point_text(pick) + " m is out of reach of " + robot.name + ": " +
              metres((pick - reach.p_WS).norm()) + " m from the shoulder " +
              point_text(reach.p_WS) + "; " + robot.name + " reaches " +
              metres(reach.min_distance, "%.2f") + "–" + metres(reach.max_distance, "%.2f") +
              " m from it (sampled within its joint limits)" + why);
}

}  // namespace

const ShelfPickRobot& shelf_pick_robot(std::string_view name) {
  std::vector<std::string> names;
  for (const auto& robot : shelf_pick_robots()) {
    if (robot.name == name) return robot;
    names.push_back(robot.name);
  }
  throw Error("unknown robot '" + std::string(name) +
              "' for the shelf pick; choices: " + choices(names));
}

const std::vector<std::string>& shelf_pick_controllers() {
  static const std::vector<std::string> names{"ct", "osc", "task-pd", "accel"};
  return names;
}

void check_shelf_pick_controller(std::string_view name) {
  for (const auto& n : shelf_pick_controllers())
    if (n == name) return;
  throw Error("unknown controller '" + std::string(name) +
              "' for the shelf pick; choices: " + choices(shelf_pick_controllers()) +
              " (computed torque, operational space, task-space PD, acceleration control)");
}

Eigen::Vector3d draw_shelf_pick(const ShelfPickRobot& robot, const Chain& chain, Random& rng,
                                std::span<double> qpos) noexcept {
  Eigen::Vector3d pick;
  for (int i = 0; i < 3; ++i)
    pick[i] = robot.pick_center[i] + (2.0 * uniform(rng) - 1.0) * robot.pick_half_width[i];
  for (int i = 0; i < chain.size(); ++i) {
    double& q = qpos[static_cast<std::size_t>(chain.qpos_address(i))];
    q += (2.0 * uniform(rng) - 1.0) * robot.start_perturbation;
    q = std::clamp(q, chain.lower()[i], chain.upper()[i]);
  }
  return pick;
}

namespace {

/// The bundled model called @p name, loaded once per process and shared (its mjModel is
/// immutable): a batch or sweep of short picks would otherwise spend much of each loading it,
/// one thread at a time (MuJoCo's XML loader is not thread-safe).
Robot shared_bundled(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, Robot> loaded;
  const std::lock_guard lock(mutex);
  const auto it = loaded.find(name);
  if (it != loaded.end()) return it->second;
  return loaded.emplace(name, Robot::bundled(name)).first->second;
}

}  // namespace

ShelfPickPlan plan_shelf_pick(const ShelfPickRequest& request) {
  const ShelfPickRobot& robot = shelf_pick_robot(request.robot);
  check_shelf_pick_controller(request.controller);
  check(request.criteria, "shelf pick");

  const Robot model = shared_bundled(robot.model);
  ShelfPickPlan plan{&robot,
                     model,
                     Chain(model, robot.frame),
                     request.controller,
                     request.seed,
                     Eigen::Vector3d::Zero(),
                     false,
                     {},
                     {},
                     {}};
  const Chain& chain = plan.chain;
  const int n = chain.size();

  // the seed: the pick point first (always drawn), then the start perturbation
  Random rng(request.seed);
  plan.qpos_start = model.keyframe_qpos("home");
  const Eigen::Vector3d drawn = draw_shelf_pick(robot, chain, rng, plan.qpos_start);
  plan.pick_drawn = !request.pick.has_value();
  plan.pick = request.pick.value_or(drawn);
  const Eigen::VectorXd q_start = chain.gather(plan.qpos_start.data());

  // the pick point: finite, in the arm's plane, above the floor, reachable
  const Eigen::Vector3d& pick = plan.pick;
  if (!pick.allFinite()) throw Error("pick point " + point_text(pick) + " holds NaN/inf");
  ChainKinematics kin(chain);
  kin.set_fixed_qpos(Eigen::Map<const Eigen::VectorXd>(plan.qpos_start.data(), model.nq()));
  const Pose X_WS = kin.update(q_start);
  if (robot.plane_normal) {
    kin.update(chain.center());
    const Eigen::Vector3d& p_shoulder = kin.anchor(0);
    const double off = robot.plane_normal->dot(pick - p_shoulder);
    if (std::abs(off) > 1e-9)
      out_of_reach(robot, chain, pick,
                   "; it lies " + metres(off, "%.4g") + " m off the arm's plane (" + robot.name +
                       " moves in the plane through the shoulder with normal " +
                       point_text(*robot.plane_normal) + ")");
  }
  if (pick.z() <= 0.0)
    throw Error("pick point " + point_text(pick) + " m is not above the floor (z must be > 0)");

  // the joint target, from the start (same IK branch as the start)
  Pose X_WT;
  X_WT.p = pick;
  plan.ik.q.resize(n);
  if (robot.position_only) {
    X_WT.R = X_WS.R;
    PositionIkOptions options;
    options.tolerance = 1e-9;
    options.max_iterations = 500;
    PositionIk ik(chain, options);
    ik.set_fixed_qpos(Eigen::Map<const Eigen::VectorXd>(plan.qpos_start.data(), model.nq()));
    plan.ik = ik.solve(pick, q_start);
  } else {
    // the tool keeps its home orientation
    const std::vector<double> home = model.keyframe_qpos("home");
    X_WT.R = kin.update(chain.gather(home.data())).R;
    PoseIkOptions options;
    options.position_tolerance = 1e-9;
    options.orientation_tolerance = 1e-8;
    options.max_iterations = 400;
    PoseIk ik(chain, options);
    ik.set_fixed_qpos(Eigen::Map<const Eigen::VectorXd>(plan.qpos_start.data(), model.nq()));
    plan.ik = ik.solve(X_WT, q_start);
  }
  if (!(plan.ik.position_error <= 1e-6) || !(plan.ik.orientation_error <= 1e-5) ||
      !chain.within_limits(plan.ik.q)) {
    out_of_reach(robot, chain, pick,
                 robot.position_only
                     ? "; the closest IK solution ends " +
                           metres(plan.ik.position_error * 1e3, "%.3g") + " mm away"
                     : "; the closest IK solution with the tool at its home orientation ends " +
                           metres(plan.ik.position_error * 1e3, "%.3g") + " mm and " +
                           metres(plan.ik.orientation_error, "%.3g") + " rad away");
  }

  // the approach: minimum jerk (the rest-to-rest quintic, i.e. smootherstep) over the shortest
  // time that keeps the tip's peak speed and acceleration within the robot's bounds
  const double distance = (pick - X_WS.p).norm();
  plan.goal.X_WS = X_WS;
  plan.goal.X_WT = X_WT;
  plan.goal.q_start = q_start;
  plan.goal.q_target = plan.ik.q;
  plan.goal.approach_time = torque_feasible_duration(
      chain, plan.qpos_start, plan.ik.q,
      std::max(robot.min_approach_time,
               SmoothRamp::duration_for(SmoothRamp::Kind::smootherstep, distance, robot.max_speed,
                                        robot.max_acceleration)),
      robot.torque_fraction);
  plan.goal.position_only = robot.position_only;
  plan.goal.criteria = request.criteria;
  return plan;
}

}  // namespace mjarm
