#include "mjarm/tasks/shelf_pick/task.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/recorder.hpp"

namespace mjarm {

namespace {

const ShelfPickGoal& checked(const Chain& chain, const ShelfPickGoal& goal) {
  const auto finite_pose = [](const Pose& X) { return X.R.allFinite() && X.p.allFinite(); };
  if (!finite_pose(goal.X_WS)) throw Error("ShelfPickTask: the start pose X_WS holds NaN/inf");
  if (!finite_pose(goal.X_WT)) throw Error("ShelfPickTask: the target pose X_WT holds NaN/inf");
  chain.check(goal.q_start, "ShelfPickGoal::q_start");
  chain.check(goal.q_target, "ShelfPickGoal::q_target");
  check_fields(goal);
  return goal;
}

/// The pose the task interpolates to: the target, or in a position-only task the target
/// position with the start rotation (the orientation is not a goal there).
Pose approach_goal(const ShelfPickGoal& goal) {
  Pose X = goal.X_WT;
  if (goal.position_only) X.R = goal.X_WS.R;
  return X;
}

QuinticTrajectory::State at_rest(const Eigen::VectorXd& q) {
  return {q, Eigen::VectorXd::Zero(q.size()), Eigen::VectorXd::Zero(q.size())};
}

}  // namespace

ShelfPickTask::ShelfPickTask(const Chain& chain, const ShelfPickGoal& goal, Recorder* recorder)
    : chain_(chain),
      goal_(checked(chain, goal)),
      recorder_(recorder),
      approach_(goal.X_WS, Vector6d::Zero(), Vector6d::Zero(), approach_goal(goal),
                goal.approach_time),
      joints_(QuinticTrajectory::to_rest(at_rest(goal.q_start), goal.q_target, goal.approach_time)),
      q_scratch_(goal.q_start.size()),
      qdd_scratch_(goal.q_start.size()),
      monitor_(goal.X_WS.p, goal.X_WT.p, goal.criteria),
      t0_(std::numeric_limits<double>::quiet_NaN()) {
  X_WE_ = goal.X_WS;
}

void ShelfPickTask::enter(PickPhase phase, double t) noexcept {
  if (phase == phase_) return;
  phase_ = phase;
  if (recorder_ != nullptr) recorder_->event(t, "phase", to_string(phase));
}

bool ShelfPickTask::update(const mjData& data, Reference& reference) noexcept {
  const int n = chain_.size();
  if (observer_ != nullptr) observer_->on_tick(data);
  if (!started_) {
    started_ = true;
    t0_ = data.time;
    if (recorder_ != nullptr) recorder_->event(t0_, "phase", to_string(PickPhase::approach));
  }
  const double t = data.time - t0_;

  // the tip, from the simulation's fresh kinematics (MuJoCo matrices are row-major)
  const FrameRef& frame = chain_.frame();
  const double* p =
      frame.kind == FrameKind::site ? data.site_xpos + 3 * frame.id : data.xpos + 3 * frame.id;
  const double* R =
      frame.kind == FrameKind::site ? data.site_xmat + 9 * frame.id : data.xmat + 9 * frame.id;
  X_WE_.p = Eigen::Vector3d(p[0], p[1], p[2]);
  X_WE_.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R);

  // the references (storage is sized on the first tick only)
  const Se3Interpolation::Sample x = approach_.at(t);
  TaskReference& task = reference.task;
  task.X_WE.p = x.X_WE.p;
  task.X_WE.R = goal_.position_only ? goal_.X_WT.R : x.X_WE.R;
  task.V_WE = approach_.at(t - goal_.velocity_lag).V_WE;
  task.A_WE = x.A_WE;
  if (goal_.position_only) {
    task.V_WE.tail<3>().setZero();
    task.A_WE.tail<3>().setZero();
  }
  task.F_ext.setZero();
  JointReference& joint = reference.joint;
  if (joint.q.size() != n) joint.q.resize(n);
  if (joint.qd.size() != n) joint.qd.resize(n);
  if (joint.qdd.size() != n) joint.qdd.resize(n);
  joints_.at(t - goal_.velocity_lag, q_scratch_, joint.qd, qdd_scratch_);
  joints_.at(t, joint.q, q_scratch_, joint.qdd);

  // the pick's figures and phases
  const double orientation_error =
      goal_.position_only ? 0.0 : so3::angle(goal_.X_WT.R * X_WE_.R.transpose());
  const PickEvent event = monitor_.observe(t, X_WE_.p, orientation_error);
  switch (event) {
    case PickEvent::entered:
      enter(PickPhase::hold, data.time);
      break;
    case PickEvent::left:
      if (recorder_ != nullptr) {
        std::snprintf(message_.data(), message_.size(),
                      "tip left the %.3g mm tolerance (error %.4g mm); the hold restarts",
                      goal_.criteria.tolerance * 1e3, monitor_.metrics().final_error * 1e3);
        recorder_->event(data.time, "warning", message_.data());
      }
      enter(t < approach_.duration() ? PickPhase::approach : PickPhase::settle, data.time);
      break;
    case PickEvent::held:
      enter(PickPhase::release, data.time);
      break;
    case PickEvent::none:
      if (phase_ == PickPhase::approach && t >= approach_.duration())
        enter(PickPhase::settle, data.time);
      break;
  }
  reference.gripper = phase_ == PickPhase::hold ? 1.0 : 0.0;
  return phase_ != PickPhase::release;
}

}  // namespace mjarm
