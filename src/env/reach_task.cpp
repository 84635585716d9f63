#include "mjarm/env/reach_task.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/scene/scene.hpp"

namespace mjarm {
namespace {

// the robot as robot "arm" on a floor, with a force/torque pair on its frame when it is a site
Robot reach_scene(const ReachOptions& options) {
  Scene scene("reach");
  scene.add_arena();
  RobotSpec arm;
  arm.name = "arm";
  arm.model = options.model;
  scene.add_robot(arm);
  const std::string frame = "arm/" + options.frame;
  if (scene.has("site", frame)) {
    scene.add_sensor({"arm/ft_force", SensorType::force, frame});
    scene.add_sensor({"arm/ft_torque", SensorType::torque, frame});
  }
  return scene.compile();
}

void check_reach_options(const ReachOptions& o) { check_fields(o); }

}  // namespace

ReachTask::ReachTask(const ReachOptions& options)
    : options_((check_reach_options(options), options)), robot_(reach_scene(options)) {
  chain_.emplace(robot_, "arm/" + options.frame);
  const mjModel& m = robot_.model();
  if (options.keyframe.empty()) {
    qpos_start_.assign(m.qpos0, m.qpos0 + m.nq);
  } else {
    qpos_start_ = robot_.keyframe_qpos(options.keyframe);
  }
  qpos_.resize(qpos_start_.size());
  qvel_.assign(static_cast<std::size_t>(m.nv), 0.0);
}

std::unique_ptr<EnvTask> ReachTask::clone() const { return std::make_unique<ReachTask>(*this); }

std::string_view ReachTask::description() const noexcept {
  return "bring the end effector to a random point; reward −distance [m] per step, terminates "
         "within the success distance";
}

std::vector<ArraySpec> ReachTask::observation_specs() const {
  return {ArraySpec::bounded("target", options_.target_center - options_.target_half_width,
                             options_.target_center + options_.target_half_width),
          ArraySpec::vector("target_offset", 3)};
}

std::vector<std::string> ReachTask::default_observations() const {
  return {"joint_positions", "joint_velocities", "ee_pose", "target", "target_offset"};
}

void ReachTask::initialize_episode(Simulation& sim, EpisodeRandom& random) {
  const Chain& chain = *chain_;
  // the start: the keyframe with each joint perturbed, at rest
  std::copy(qpos_start_.begin(), qpos_start_.end(), qpos_.begin());
  const double r = options_.start_perturbation;
  for (int i = 0; i < chain.size(); ++i) {
    double& q = qpos_[static_cast<std::size_t>(chain.qpos_address(i))];
    q = std::clamp(q + uniform(random.task, -r, r), chain.lower()[i], chain.upper()[i]);
  }
  for (int k = 0; k < 3; ++k)
    target_[k] =
        options_.target_center[k] + uniform(random.task, -1.0, 1.0) * options_.target_half_width[k];
  sim.reset();
  sim.set_state(qpos_, qvel_);
}

void ReachTask::observe(int index, const StepContext& context,
                        std::span<double> out) const noexcept {
  const Eigen::Vector3d v = index == 0 ? target_ : Eigen::Vector3d(target_ - context.X_WE.p);
  for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = v[k];
}

double ReachTask::reward(const StepContext& context) const noexcept {
  return -(context.X_WE.p - target_).norm();
}

bool ReachTask::terminated(const StepContext& context) const noexcept {
  return options_.success_distance > 0.0 &&
         (context.X_WE.p - target_).norm() <= options_.success_distance;
}

}  // namespace mjarm
