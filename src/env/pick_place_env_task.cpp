#include "mjarm/env/pick_place_env_task.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/pick_place/controllers.hpp"

namespace mjarm {
namespace {

constexpr double kRestHeightTolerance = 0.005;  // a placed cube's centre within this of its rest

std::shared_ptr<const PickPlaceScene> pick_place_env_scene(const PickPlaceEnvOptions& o) {
  check_fields(o);
  PickPlaceSceneOptions scene;
  scene.robot = o.robot;  // unknown: the scene says so, with the choices
  scene.mode = SimulationMode::torque;
  scene.object.size = {o.object_half_size, o.object_half_size, o.object_half_size};
  scene.object.mass = o.object_mass;
  scene.object.friction = o.object_friction;
  const PickPlaceRobot& robot = pick_place_robot(o.robot);
  // a placeholder inside the table region: every episode puts the cube and target elsewhere
  scene.object.position = {robot.mount[0] + robot.min_radius, robot.mount[1]};
  scene.target = {robot.mount[0] + robot.max_radius, robot.mount[1]};
  scene.noslip_iterations = o.noslip_iterations;
  return std::make_shared<const PickPlaceScene>(build_pick_place_scene(scene));
}

}  // namespace

PickPlaceEnvTask::PickPlaceEnvTask(const PickPlaceEnvOptions& options)
    : options_(options),
      scene_(pick_place_env_scene(options)),
      arm_(scene_->model, scene_->arm_joints, scene_->tool),
      fingers_(make_pick_place_fingers(*scene_, SimulationMode::torque, options.grasp_force)) {
  // the ranges the trial draw checks, once here (an error now rather than at the first reset)
  PickPlaceOptions draw;
  draw.robot = options.robot;
  draw.ranges = options.ranges;
  draw.object_half_size = options.object_half_size;
  trial_ = draw_pick_place_trial(draw);

  const Robot& model = scene_->model;
  object_body_ = model.body(scene_->object);
  const JointInfo free = model.joint_info(model.joint(scene_->object + "/joint"));
  object_qpos_ = free.qpos_address;
  object_dof_ = free.dof_address;
  home_ = model.keyframe_qpos("home");
  for (int k = 0; k < 2; ++k) {
    const JointInfo j = model.joint_info(model.joint(scene_->fingers[static_cast<std::size_t>(k)]));
    finger_qpos_[static_cast<std::size_t>(k)] = j.qpos_address;
    home_[static_cast<std::size_t>(j.qpos_address)] = j.upper;  // open, as the trials start
  }
  qpos_ = home_;
  qvel_.assign(static_cast<std::size_t>(model.nv()), 0.0);
  half_height_ = options.object_half_size;
}

PickPlaceEnvTask::PickPlaceEnvTask(const PickPlaceEnvTask& other)
    : EnvTask(other),
      options_(other.options_),
      scene_(other.scene_),
      arm_(other.arm_),
      fingers_(make_pick_place_fingers(*scene_, SimulationMode::torque, options_.grasp_force)),
      object_body_(other.object_body_),
      object_qpos_(other.object_qpos_),
      object_dof_(other.object_dof_),
      finger_qpos_(other.finger_qpos_),
      home_(other.home_),
      qpos_(other.qpos_),
      qvel_(other.qvel_),
      trial_(other.trial_),
      half_height_(other.half_height_),
      target_(other.target_),
      X_WO_(other.X_WO_),
      object_quaternion_(other.object_quaternion_) {}

PickPlaceEnvTask::~PickPlaceEnvTask() = default;

std::unique_ptr<EnvTask> PickPlaceEnvTask::clone() const {
  return std::make_unique<PickPlaceEnvTask>(*this);
}

std::string_view PickPlaceEnvTask::description() const noexcept {
  return "the tasks room's pick and place: grasp the cube (gripper command: the action's last "
         "entry) and put it down on the target; reward −(tool to cube + cube to target), "
         "terminates placed, or when the cube falls or the robot touches the table";
}

double PickPlaceEnvTask::controller_period() const noexcept {
  return scene_->model.model().opt.timestep;  // the fingers' force loop needs every step
}

std::vector<ArraySpec> PickPlaceEnvTask::observation_specs() const {
  ArraySpec pose = ArraySpec::vector("object_pose", 7);
  pose.minimum.tail<4>().setConstant(-1.0);
  pose.maximum.tail<4>().setConstant(1.0);
  return {pose, ArraySpec::vector("target", 3), ArraySpec::vector("target_offset", 3),
          ArraySpec::vector("grasp", 4)};
}

std::vector<std::string> PickPlaceEnvTask::default_observations() const {
  return {"joint_positions", "joint_velocities", "ee_pose", "object_pose", "target", "grasp"};
}

std::vector<int> PickPlaceEnvTask::object_geoms() const {
  return {scene_->model.geom(scene_->object + "/geom")};
}

void PickPlaceEnvTask::initialize_episode(Simulation& sim, EpisodeRandom& random) {
  if (monitored_ != &sim) {
    // the monitor and the table watch live on the environment's simulation
    const Robot& model = scene_->model;
    monitor_.emplace(sim, scene_->hand, scene_->object,
                     GeomSet::of_geoms(model, {scene_->fingers[0]}),
                     GeomSet::of_geoms(model, {scene_->fingers[1]}), options_.criteria.grasp);
    table_watch_ = sim.watch_contacts(GeomSet::of_bodies(model, {scene_->robot_root}, true),
                                      GeomSet::of_bodies(model, {scene_->table}, false));
    monitored_ = &sim;
  }
  // the tasks room's draw for this seed: cube position and yaw, target
  PickPlaceOptions draw;
  draw.robot = options_.robot;
  draw.seed = random.seed;
  draw.ranges = options_.ranges;
  draw.object_half_size = options_.object_half_size;
  trial_ = draw_pick_place_trial(draw);
  const double rest = scene_->table_height + half_height_;
  target_ = Eigen::Vector3d(trial_.target[0], trial_.target[1], rest);

  std::copy(home_.begin(), home_.end(), qpos_.begin());
  const double r = options_.start_perturbation;
  for (int i = 0; i < arm_.size(); ++i) {
    double& q = qpos_[static_cast<std::size_t>(arm_.qpos_address(i))];
    q = std::clamp(q + uniform(random.task, -r, r), arm_.lower()[i], arm_.upper()[i]);
  }
  double* o = qpos_.data() + object_qpos_;
  o[0] = trial_.object.position[0];
  o[1] = trial_.object.position[1];
  o[2] = rest;
  o[3] = std::cos(0.5 * trial_.object.yaw);
  o[4] = 0.0;
  o[5] = 0.0;
  o[6] = std::sin(0.5 * trial_.object.yaw);
  sim.reset();
  sim.set_state(qpos_, qvel_);
  monitor_->open();
  monitor_->update();
  outcome_ = PickPlaceEnvOutcome::running;
  read_object(sim.data());
}

void PickPlaceEnvTask::read_object(const mjData& d) noexcept {
  const double* q = d.qpos + object_qpos_;
  X_WO_.p = Eigen::Vector3d(q[0], q[1], q[2]);
  object_quaternion_ = Eigen::Vector4d(q[3], q[4], q[5], q[6]).normalized();
  X_WO_.R = Eigen::Quaterniond(object_quaternion_[0], object_quaternion_[1], object_quaternion_[2],
                               object_quaternion_[3])
                .toRotationMatrix();
  object_speed_ = Eigen::Map<const Eigen::Vector3d>(d.qvel + object_dof_).norm();
}

void PickPlaceEnvTask::after_step(const StepContext& context) noexcept {
  const Simulation& sim = context.simulation();
  read_object(context.data());
  monitor_->update();
  const GraspReading& g = monitor_->reading();
  const PickPlaceCriteria& c = options_.criteria;
  if (X_WO_.p.z() < scene_->table_height) {
    outcome_ = PickPlaceEnvOutcome::fell;
    return;
  }
  if (options_.table_contact_fails && sim.contacts(table_watch_).contacts > 0) {
    outcome_ = PickPlaceEnvOutcome::table_contact;
    return;
  }
  const double horizontal = std::hypot(X_WO_.p.x() - target_.x(), X_WO_.p.y() - target_.y());
  const double tilt = std::acos(std::clamp(X_WO_.R(2, 2), -1.0, 1.0));
  if (horizontal <= c.placement_tolerance &&
      std::abs(X_WO_.p.z() - target_.z()) <= kRestHeightTolerance &&
      object_speed_ <= c.rest_speed && tilt <= c.max_tilt && g.finger1_contacts == 0 &&
      g.finger2_contacts == 0)
    outcome_ = PickPlaceEnvOutcome::placed;
}

void PickPlaceEnvTask::observe(int index, const StepContext& context,
                               std::span<double> out) const noexcept {
  switch (index) {
    case 0:
      for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = X_WO_.p[k];
      for (int k = 0; k < 4; ++k) out[static_cast<std::size_t>(3 + k)] = object_quaternion_[k];
      break;
    case 1:
      for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = target_[k];
      break;
    case 2:
      for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = target_[k] - X_WO_.p[k];
      break;
    default: {
      const mjData& d = context.data();
      const GraspReading& g = monitor_->reading();
      out[0] = d.qpos[finger_qpos_[0]] + d.qpos[finger_qpos_[1]];
      out[1] = g.finger1_contacts > 0 ? 1.0 : 0.0;
      out[2] = g.finger2_contacts > 0 ? 1.0 : 0.0;
      out[3] = g.force;
      break;
    }
  }
}

double PickPlaceEnvTask::reward(const StepContext& context) const noexcept {
  const double r = -((context.X_WE.p - X_WO_.p).norm() + (X_WO_.p - target_).norm());
  const bool failed =
      outcome_ == PickPlaceEnvOutcome::fell || outcome_ == PickPlaceEnvOutcome::table_contact;
  return failed ? r - options_.failure_penalty : r;
}

bool PickPlaceEnvTask::terminated(const StepContext&) const noexcept {
  return outcome_ != PickPlaceEnvOutcome::running;
}

}  // namespace mjarm
