#include "mjarm/env/docking_env_task.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

void check_docking_env(const DockingEnvOptions& o) {
  check_fields(o);
  check(o.motion);  // the standoff against the start height
  if (!o.scene.ft_sensor)
    throw Error("docking environment: the scene needs its force/torque sensor (scene.ft_sensor)");
  const DockingOffset& r = o.offset_range;
  if (!(r.dx >= 0.0 && r.dx <= 0.05) || !(r.dy >= 0.0 && r.dy <= 0.05) ||
      !(r.dyaw >= 0.0 && r.dyaw <= 3.14159265358979323846))
    throw Error(
        "docking environment: offset_range needs dx, dy in [0, 0.05] m and dyaw in [0, π] rad");
}

std::shared_ptr<const DockingScene> checked_scene(const DockingEnvOptions& o) {
  check_docking_env(o);
  return std::make_shared<const DockingScene>(build_docking_scene(o.scene));
}

}  // namespace

DockingEnvTask::DockingEnvTask(const DockingEnvOptions& options)
    : options_(options), scene_(checked_scene(options)), probe_(*scene_, iiwa14_max_velocity()) {
  // the start and the true seat as the docking run plans them (the offset is drawn per episode)
  const DockingPlan plan = plan_docking(*scene_, DockingOffset{}, options.motion);
  X_seated_ = plan.X_seated;
  X_believed_ = plan.X_seated;
  believed_quaternion_ = quaternion_from_rotation(X_believed_.R);
  full_depth_ = plan.full_depth;
  q_start_ = plan.q_start;
  home_ = scene_->robot.keyframe_qpos("home");
  scene_->chain.scatter(q_start_, home_.data());
  qpos_ = home_;
  qvel_.assign(static_cast<std::size_t>(scene_->robot.nv()), 0.0);
}

std::unique_ptr<EnvTask> DockingEnvTask::clone() const {
  return std::make_unique<DockingEnvTask>(*this);
}

std::string_view DockingEnvTask::description() const noexcept {
  return "the tasks room's peg-in-hole docking: seat the peg in the chamfered bore (0.5 mm "
         "clearance) from above; reward −(tip distance to the seat + w·tilt), terminates seated "
         "or on an excess force or a foreign contact";
}

std::vector<ArraySpec> DockingEnvTask::observation_specs() const {
  ArraySpec target = ArraySpec::vector("target", 7);
  target.minimum.tail<4>().setConstant(-1.0);
  target.maximum.tail<4>().setConstant(1.0);
  return {target, ArraySpec::vector("wrench", 6), ArraySpec::vector("insertion", 3)};
}

std::vector<std::string> DockingEnvTask::default_observations() const {
  return {"joint_positions",
          "joint_velocities",
          "ee_pose",
          "ee_twist",
          "target",
          std::string("sensor:") + DockingNames::force,
          std::string("sensor:") + DockingNames::torque};
}

void DockingEnvTask::initialize_episode(Simulation& sim, EpisodeRandom& random) {
  const DockingOffset& r = options_.offset_range;
  offset_.dx = uniform(random.task, -r.dx, r.dx);
  offset_.dy = uniform(random.task, -r.dy, r.dy);
  offset_.dyaw = uniform(random.task, -r.dyaw, r.dyaw);
  // the believed socket X_WB = X_WS·(R_z(dyaw), (dx, dy, 0)), as plan_docking has it
  const Pose& X_WS = scene_->options.X_WS;
  const Pose X_SB = Pose::from_rotation_vector(Eigen::Vector3d(offset_.dx, offset_.dy, 0.0),
                                               Eigen::Vector3d(0.0, 0.0, offset_.dyaw));
  X_believed_ = scene_->seated(X_WS * X_SB);
  believed_quaternion_ = quaternion_from_rotation(X_believed_.R);

  std::copy(home_.begin(), home_.end(), qpos_.begin());
  const Chain& chain = scene_->chain;
  const double p = options_.start_perturbation;
  for (int i = 0; i < chain.size(); ++i) {
    double& q = qpos_[static_cast<std::size_t>(chain.qpos_address(i))];
    q = std::clamp(q + uniform(random.task, -p, p), chain.lower()[i], chain.upper()[i]);
  }
  sim.reset();
  sim.set_state(qpos_, qvel_);
  sample_ = DockingSample{};
  seated_since_ = -1.0;
  outcome_ = DockingEnvOutcome::running;
  // the tip at the start (kinematics fresh after set_state)
  const mjData& d = sim.data();
  const int tip = chain.frame().id;
  Pose X_WE;
  X_WE.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.site_xmat + 9 * tip);
  X_WE.p = Eigen::Map<const Eigen::Vector3d>(d.site_xpos + 3 * tip);
  measure(X_WE);
}

void DockingEnvTask::measure(const Pose& X_WE) noexcept {
  const DockingInsertion in = docking_insertion(X_WE, scene_->options.X_WS);
  insertion_ << in.depth, in.lateral, in.tilt;
}

void DockingEnvTask::after_step(const StepContext& context) noexcept {
  // the ground truth of the step's last physics step (contacts and their forces)
  probe_.sample(context.simulation().model(), context.data(), context.time, X_believed_, false,
                sample_);
  measure(context.X_WE);
  const DockingCriteria& c = options_.criteria;
  if (sample_.other_contact) {
    outcome_ = DockingEnvOutcome::other_contact;
    return;
  }
  if (sample_.F_peg.head<3>().norm() > c.max_force) {
    outcome_ = DockingEnvOutcome::excess_force;
    return;
  }
  const bool seated_now = insertion_[0] >= full_depth_ - c.depth_tolerance &&
                          insertion_[1] <= c.max_lateral && insertion_[2] <= c.max_tilt &&
                          context.V_WE.head<3>().norm() <= c.max_speed;
  if (!seated_now) {
    seated_since_ = -1.0;
  } else if (seated_since_ < 0.0) {
    seated_since_ = context.time;
  }
  if (seated_since_ >= 0.0 && context.time - seated_since_ >= options_.seated_time - 1e-9)
    outcome_ = DockingEnvOutcome::seated;
}

void DockingEnvTask::observe(int index, const StepContext&, std::span<double> out) const noexcept {
  switch (index) {
    case 0:
      for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = X_believed_.p[k];
      for (int k = 0; k < 4; ++k) out[static_cast<std::size_t>(3 + k)] = believed_quaternion_[k];
      break;
    case 1:
      for (int k = 0; k < 6; ++k) out[static_cast<std::size_t>(k)] = sample_.F_peg[k];
      break;
    default:
      for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = insertion_[k];
      break;
  }
}

double DockingEnvTask::reward(const StepContext& context) const noexcept {
  const double r = -((context.X_WE.p - X_seated_.p).norm() + options_.tilt_weight * insertion_[2]);
  const bool failed =
      outcome_ == DockingEnvOutcome::excess_force || outcome_ == DockingEnvOutcome::other_contact;
  return failed ? r - options_.failure_penalty : r;
}

bool DockingEnvTask::terminated(const StepContext&) const noexcept {
  return outcome_ != DockingEnvOutcome::running;
}

}  // namespace mjarm
