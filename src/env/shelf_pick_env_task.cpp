#include "mjarm/env/shelf_pick_env_task.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/control/task_error.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

const ShelfPickRobot& pose_robot(const ShelfPickEnvOptions& o) {
  const ShelfPickRobot& robot = shelf_pick_robot(o.robot);
  if (robot.position_only)
    throw Error("shelf-pick environment: robot '" + robot.name +
                "' has a position-only shelf pick; the environment's end-effector actions "
                "command a pose (use panda)");
  check(o.criteria, "shelf-pick environment");
  check_fields(o);
  return robot;
}

}  // namespace

ShelfPickEnvTask::ShelfPickEnvTask(const ShelfPickEnvOptions& options)
    : options_(options),
      robot_(&pose_robot(options)),
      model_(Robot::bundled(robot_->model)),
      monitor_(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), options.criteria) {
  chain_.emplace(model_, robot_->frame);
  home_ = model_.keyframe_qpos("home");
  qpos_ = home_;
  qvel_.assign(static_cast<std::size_t>(model_.nv()), 0.0);
  // the tool keeps its orientation at home (as the tasks room's plan)
  ChainKinematics kinematics(*chain_);
  X_WT_.R = kinematics.update(chain_->gather(home_.data())).R;
  quaternion_ = quaternion_from_rotation(X_WT_.R);
}

std::unique_ptr<EnvTask> ShelfPickEnvTask::clone() const {
  return std::make_unique<ShelfPickEnvTask>(*this);
}

std::string_view ShelfPickEnvTask::description() const noexcept {
  return "the tasks room's shelf pick: tool tip onto the pick point at the home tool orientation "
         "and held within the tolerance; reward −(position error + w·orientation error)";
}

std::vector<ArraySpec> ShelfPickEnvTask::observation_specs() const {
  Eigen::VectorXd lo(7), hi(7);
  lo << robot_->pick_center - robot_->pick_half_width, -1.0, -1.0, -1.0, -1.0;
  hi << robot_->pick_center + robot_->pick_half_width, 1.0, 1.0, 1.0, 1.0;
  return {ArraySpec::bounded("target", lo, hi)};
}

void ShelfPickEnvTask::initialize_episode(Simulation& sim, EpisodeRandom& random) {
  std::copy(home_.begin(), home_.end(), qpos_.begin());
  X_WT_.p = draw_shelf_pick(*robot_, *chain_, random.task, qpos_);
  sim.reset();
  sim.set_state(qpos_, qvel_);
  // the monitor measures the approach from the tip's start (kinematics fresh after set_state)
  const FrameRef& frame = chain_->frame();
  const mjData& d = sim.data();
  const double* p =
      frame.kind == FrameKind::site ? d.site_xpos + 3 * frame.id : d.xpos + 3 * frame.id;
  monitor_ = PickMonitor(Eigen::Vector3d(p[0], p[1], p[2]), X_WT_.p, options_.criteria);
}

void ShelfPickEnvTask::after_step(const StepContext& context) noexcept {
  const Vector6d e = task_error(context.X_WE, X_WT_);
  monitor_.observe(context.time, context.X_WE.p, e.tail<3>().norm());
}

void ShelfPickEnvTask::observe(int, const StepContext&, std::span<double> out) const noexcept {
  for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = X_WT_.p[k];
  for (int k = 0; k < 4; ++k) out[static_cast<std::size_t>(3 + k)] = quaternion_[k];
}

double ShelfPickEnvTask::reward(const StepContext& context) const noexcept {
  const Vector6d e = task_error(context.X_WE, X_WT_);
  return -(e.head<3>().norm() + options_.orientation_weight * e.tail<3>().norm());
}

bool ShelfPickEnvTask::terminated(const StepContext&) const noexcept { return monitor_.held(); }

}  // namespace mjarm
