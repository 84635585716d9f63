#include "mjarm/tasks/pick_place/pick_place.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "mjarm/error.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/random.hpp"
#include "mjarm/scene/free_pose.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/arm_reach.hpp"
#include "mjarm/tasks/pick_place/controllers.hpp"
#include "mjarm/tasks/shelf_pick/plan.hpp"
#include "tasks/run_outputs.hpp"

namespace mjarm {

namespace {

constexpr double kClassicHalfSize = 0.0075;
constexpr double kClassicTravel = 0.012;
constexpr double kClassicServoGain = 3200.0;

void check_range(const std::array<double, 2>& r, const char* what, double lowest) {
  if (!(std::isfinite(r[0]) && std::isfinite(r[1]) && r[0] <= r[1] && r[0] >= lowest))
    throw Error(std::string("pick and place: the ") + what + " range must be finite, increasing " +
                "and ≥ " + number_text(lowest) + ", got [" + number_text(r[0]) + ", " +
                number_text(r[1]) + "]");
}

std::string point_text(double x, double y, double z) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.3f, %.3f, %.3f)", x, y, z);
  return buffer;
}

std::string fixed(double v, const char* format = "%.3f") {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

// every tool pose of the machine, solved one after the other from the home posture
void check_reach(const PickPlaceScene& scene, const Chain& arm, const PickPlaceGoal& goal,
                 const PickPlaceMotion& motion, const Eigen::VectorXd& q_home) {
  PoseIkOptions options;
  options.max_iterations = 300;
  options.position_tolerance = 1e-4;
  options.orientation_tolerance = 1e-3;
  PoseIk ik(arm, options);
  struct Stop {
    const char* what;
    const Eigen::Vector3d& point;
    double height;
  };
  const Stop stops[] = {{"object", goal.object, motion.approach_height},
                        {"object", goal.object, motion.descend_height},
                        {"object", goal.object, motion.lift_height},
                        {"target", goal.target, motion.move_height},
                        {"target", goal.target, motion.place_height}};
  Eigen::VectorXd seed = q_home;
  for (const Stop& stop : stops) {
    Pose X;
    X.R = goal.R_grasp;
    X.p = stop.point + Eigen::Vector3d(0.0, 0.0, stop.height);
    const IkResult r = ik.solve(X, seed);
    if (r.ok()) {
      seed = r.q;
      continue;
    }
    const ArmReach reach = arm_reach(arm);
    const double distance = (X.p - reach.p_WS).norm();
    throw Error(
        std::string(stop.what) + " at " +
        point_text(stop.point.x(), stop.point.y(), stop.point.z()) + " m is out of reach of " +
        scene.robot->name + ": the tool must reach " + point_text(X.p.x(), X.p.y(), X.p.z()) +
        " pointing down, " + fixed(distance) + " m from the shoulder " +
        point_text(reach.p_WS.x(), reach.p_WS.y(), reach.p_WS.z()) + "; " + scene.robot->name +
        " reaches " + fixed(reach.min_distance, "%.2f") + "–" + fixed(reach.max_distance, "%.2f") +
        " m from it (sampled within its joint limits; pointing down, less); its trials "
        "draw from " +
        fixed(scene.robot->min_radius, "%.2f") + "–" + fixed(scene.robot->max_radius, "%.2f") +
        " m from the base axis");
  }
}

PickPlaceFailure failure_of(const RunResult& run) {
  switch (run.status) {
    case RunStatus::diverged:
      return PickPlaceFailure::diverged;
    case RunStatus::bad_command:
      return PickPlaceFailure::bad_command;
    case RunStatus::interrupted:
      return PickPlaceFailure::interrupted;
    case RunStatus::duration_reached:
      return PickPlaceFailure::time_limit;
    case RunStatus::finished:
      return PickPlaceFailure::none;
  }
  return PickPlaceFailure::none;
}

// the verdict: the first failure that applies, with its one-line reason
void judge(PickPlaceReport& r, const PickPlaceCriteria& c, const Simulation& sim) {
  const PickPlaceTrace& t = r.trace;
  const auto fail = [&](PickPlaceFailure f, std::string reason) {
    r.failure = f;
    r.reason = std::move(reason);
  };
  r.failure = failure_of(r.run);
  if (r.failure != PickPlaceFailure::none) {
    r.reason = r.run.message + " (in " + to_string(t.state) + ")";
  } else if (!t.closed) {
    fail(PickPlaceFailure::not_grasped,
         "a finger did not touch the object when GRASP ended (grasp force " +
             fixed(t.closing_force) + " N)");
  } else if (t.dropped) {
    fail(PickPlaceFailure::dropped,
         "the object slipped out of the fingers at t = " + fixed(t.dropped_time) +
             " s (largest slip " + fixed(t.max_slip * 1e3) + " mm)");
  } else if (t.table_contact) {
    fail(PickPlaceFailure::table_contact,
         "the robot touched the table at t = " + fixed(t.table_contact_time) + " s");
  } else if (t.longest_saturation * r.control_period > c.max_saturation_time) {
    const char* name = mj_id2name(&sim.model(), mjOBJ_ACTUATOR, t.saturated_actuator);
    fail(PickPlaceFailure::saturated,
         "actuator '" + std::string(name != nullptr ? name : "?") + "' was clipped for " +
             fixed(static_cast<double>(t.longest_saturation) * r.control_period) +
             " s without a break (allowed " + fixed(c.max_saturation_time) + " s)");
  } else if (!(r.placement_error <= c.placement_tolerance)) {
    fail(PickPlaceFailure::misplaced, "the object ended " + fixed(r.placement_error * 1e3, "%.2f") +
                                          " mm from the target (allowed " +
                                          fixed(c.placement_tolerance * 1e3, "%.1f") + " mm)");
  } else if (!(r.tilt <= c.max_tilt)) {
    fail(PickPlaceFailure::tilted, "the object ended tilted by " +
                                       fixed(r.tilt * 180.0 / M_PI, "%.1f") + "° (allowed " +
                                       fixed(c.max_tilt * 180.0 / M_PI, "%.1f") + "°)");
  } else if (!(r.final_speed < c.rest_speed)) {
    fail(PickPlaceFailure::not_resting,
         "the object still moved at " + fixed(r.final_speed * 1e3, "%.2f") +
             " mm/s at the end (resting: below " + fixed(c.rest_speed * 1e3, "%.2f") + " mm/s)");
  }
  r.success = r.failure == PickPlaceFailure::none;
}

std::string result_line(const PickPlaceReport& r) {
  char buffer[400];
  std::snprintf(buffer, sizeof buffer,
                "%s: placement_error=%.6g m tilt=%.6g rad speed=%.6g m/s cycle_time=%.6g s "
                "grasp_force=%.6g N weld_jump=%.6g m",
                r.success ? "success" : to_string(r.failure), r.placement_error, r.tilt,
                r.final_speed, r.cycle_time, r.trace.transport_force_mean, r.trace.weld_jump);
  return std::string(buffer) + (r.reason.empty() ? "" : "; " + r.reason);
}

}  // namespace

Eigen::Matrix3d grasp_rotation(const Eigen::Matrix3d& R_home, double yaw) {
  Eigen::Vector3d x = R_home.col(0);
  x.z() = 0.0;
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d z(0.0, 0.0, -1.0);
  Eigen::Matrix3d R_down;
  R_down.col(0) = x;
  R_down.col(1) = z.cross(x);
  R_down.col(2) = z;
  return so3::exp(Eigen::Vector3d(0.0, 0.0, yaw)) * R_down;
}

double grasp_yaw(const PickPlaceObject& object) {
  if (object.shape != "box") return 0.0;
  const double period = object.size[0] == object.size[1] ? 0.5 * M_PI : M_PI;
  return object.yaw - period * std::round(object.yaw / period);
}

PickPlaceTrial draw_pick_place_trial(const PickPlaceOptions& options) {
  const PickPlaceRobot& robot = pick_place_robot(options.robot);
  const PickPlaceRanges& g = options.ranges;
  check_range(g.half_size, "half size [m]", 1e-3);
  check_range(g.mass, "mass [kg]", 1e-4);
  check_range(g.friction, "friction", 0.0);
  check_range(g.yaw, "yaw [rad]", -M_PI);
  if (!(std::isfinite(g.min_separation) && g.min_separation >= 0.0))
    throw Error("pick and place: min_separation must be finite and ≥ 0 [m]");
  Random rng(options.seed);
  const auto in_range = [&](const std::array<double, 2>& r) { return uniform(rng, r[0], r[1]); };
  // uniform over the area of the table region
  const auto point = [&] {
    const double r0 = robot.min_radius, r1 = robot.max_radius;
    const double r = std::sqrt(r0 * r0 + (r1 * r1 - r0 * r0) * uniform(rng));
    const double b = robot.max_bearing * (2.0 * uniform(rng) - 1.0);
    return std::array<double, 2>{robot.mount[0] + r * std::cos(b),
                                 robot.mount[1] + r * std::sin(b)};
  };
  PickPlaceTrial trial;
  trial.seed = options.seed;
  PickPlaceObject& o = trial.object;
  o.position = point();
  o.yaw = in_range(g.yaw);
  const double half = in_range(g.half_size);
  o.mass = in_range(g.mass);
  o.friction = in_range(g.friction);
  std::array<double, 2> target = point();
  for (int k = 0; k < 1000; ++k) {
    if (std::hypot(target[0] - o.position[0], target[1] - o.position[1]) >= g.min_separation) break;
    target = point();
  }
  trial.target = target;
  double size = options.classic ? kClassicHalfSize : half;
  if (options.object_half_size) size = *options.object_half_size;
  o.size = {size, size, size};
  if (options.object_position) o.position = *options.object_position;
  if (options.target_position) trial.target = *options.target_position;
  return trial;
}

PickPlaceReport run_pick_place(const PickPlaceOptions& options) {
  check(options.motion);
  const PickPlaceCriteria& criteria = options.criteria;
  check_fields(criteria, "pick and place", "criteria.");
  if (!(std::isfinite(options.grasp_force) && options.grasp_force > 0.0))
    throw Error("pick and place: grasp_force must be positive [N], got " +
                number_text(options.grasp_force));
  PickPlaceReport report;
  report.trial = draw_pick_place_trial(options);
  report.robot = options.robot;
  report.grasp = options.grasp;
  report.mode = options.mode;

  PickPlaceSceneOptions scene_options;
  scene_options.robot = options.robot;
  scene_options.mode = options.mode;
  scene_options.object = report.trial.object;
  scene_options.target = report.trial.target;
  scene_options.noslip_iterations = options.noslip_iterations;
  scene_options.impratio = options.impratio;
  if (options.classic) {
    scene_options.finger_travel = {0.0, kClassicTravel};
    scene_options.finger_servo_gain = kClassicServoGain;
  }
  const PickPlaceScene scene = build_pick_place_scene(scene_options);
  const Robot& model = scene.model;

  SimulationOptions sim_options;
  sim_options.mode = options.mode;
  sim_options.control_period = options.control_period;
  sim_options.max_acceleration = options.max_acceleration;
  Simulation sim(model, sim_options);
  const Chain arm(model, scene.arm_joints, scene.tool);
  const std::unique_ptr<Controller> arm_controller =
      make_pick_place_arm_controller(arm, options.mode);
  const std::unique_ptr<FingerForceController> fingers =
      make_pick_place_fingers(scene, options.mode, options.grasp_force);
  sim.add_controller(*arm_controller);
  sim.add_controller(*fingers);
  report.control_period = sim.control_period();

  // the start: home, fingers open (within a shortened travel), the object where the trial put it
  std::vector<double> qpos = model.keyframe_qpos("home");
  for (const std::string& finger : scene.fingers) {
    const JointInfo j = model.joint_info(model.joint(finger));
    qpos[static_cast<std::size_t>(j.qpos_address)] = j.upper;
  }
  sim.set_state(qpos, std::vector<double>(static_cast<std::size_t>(model.nv()), 0.0));

  std::optional<WeldGrasp> weld;
  if (options.grasp == GraspKind::weld) weld.emplace(sim, scene.weld, options.weld);
  GraspMonitor monitor(sim, scene.hand, scene.object, GeomSet::of_geoms(model, {scene.fingers[0]}),
                       GeomSet::of_geoms(model, {scene.fingers[1]}), criteria.grasp);
  const int table_watch = sim.watch_contacts(GeomSet::of_bodies(model, {scene.robot_root}, true),
                                             GeomSet::of_bodies(model, {scene.table}, false));

  PickPlaceGoal goal;
  goal.X_WS = frame_pose(model.model(), sim.data(), arm.frame());
  const double half_height = object_half_height(report.trial.object);
  const auto& o = report.trial.object;
  goal.object = Eigen::Vector3d(o.position[0], o.position[1], scene.table_height + half_height);
  goal.target = Eigen::Vector3d(report.trial.target[0], report.trial.target[1],
                                scene.table_height + half_height);
  goal.R_grasp = grasp_rotation(goal.X_WS.R, grasp_yaw(o));
  goal.posture = arm.gather(sim.data().qpos);
  goal.grasp = options.grasp;
  goal.velocity_lag = sim.uses_rk4() ? 0.0 : 0.5 * sim.timestep();
  check_reach(scene, arm, goal, options.motion, goal.posture);

  // the video and the recorder open (and fail) before the first step
  std::optional<PickPlaceVideoRun> video;
  if (!options.video.path.empty()) {
    video.emplace(model, sim.data(), options.video, scene.tool, goal.target);
    report.videos = video->paths();
  }
  std::optional<Recorder> recorder;
  if (!options.record.empty()) {
    RecorderOptions recorder_options;
    recorder_options.state_decimation = options.state_decimation;
    recorder_options.channels = {{"grasp.force", monitor.force_value()},
                                 {"grasp.slip", monitor.slip_value()}};
    recorder_options.seed = options.seed;
    recorder.emplace(sim, options.record, recorder_options);
    report.recording = recorder->directory();
  }

  PickPlaceTask task(sim, arm, goal, options.motion, monitor, weld ? &*weld : nullptr, table_watch,
                     recorder ? &*recorder : nullptr);
  if (video) task.set_observer(&*video);
  const double limit = task.schedule().back() + 1.0;
  report.run = sim.run(task, limit, recorder ? &*recorder : nullptr);
  report.trace = task.trace();
  report.cycle_time = report.trace.done_time;

  // the object at the end
  const mjData& d = sim.data();
  const int body = model.body(scene.object);
  const Eigen::Map<const Eigen::Vector3d> p(d.xpos + 3 * body);
  report.placement_error = std::hypot(p.x() - goal.target.x(), p.y() - goal.target.y());
  report.tilt = std::acos(std::clamp(d.xmat[9 * body + 8], -1.0, 1.0));
  const int address = model.joint_info(model.joint(scene.object + "/joint")).dof_address;
  report.final_speed = Eigen::Map<const Eigen::Vector3d>(d.qvel + address).norm();
  judge(report, criteria, sim);

  if (recorder)
    report.recording_error =
        finish_recording(*recorder, sim.time(), result_line(report), report.run);
  if (video) {
    report.video_error = finish_video(*video, sim.data());
    report.video_frames = video->frames();
    report.videos_written = video->written();
  }
  return report;
}

}  // namespace mjarm
