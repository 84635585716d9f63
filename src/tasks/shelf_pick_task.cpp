#include "mjarm/tasks/shelf_pick_task.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/sim/recorder.hpp"

namespace mjarm {

const char* to_string(PickPhase phase) noexcept {
  switch (phase) {
    case PickPhase::approach:
      return "approach";
    case PickPhase::settle:
      return "settle";
    case PickPhase::hold:
      return "hold";
    case PickPhase::release:
      return "release";
  }
  return "unknown";
}

namespace {

const ShelfPickGoal& checked(const Chain& chain, const ShelfPickGoal& goal) {
  const auto finite_pose = [](const Pose& X) { return X.R.allFinite() && X.p.allFinite(); };
  if (!finite_pose(goal.X_WS)) throw Error("ShelfPickTask: the start pose X_WS holds NaN/inf");
  if (!finite_pose(goal.X_WT)) throw Error("ShelfPickTask: the target pose X_WT holds NaN/inf");
  chain.check(goal.q_start, "ShelfPickGoal::q_start");
  chain.check(goal.q_target, "ShelfPickGoal::q_target");
  if (!(goal.velocity_lag >= 0.0) || !std::isfinite(goal.velocity_lag))
    throw Error("ShelfPickTask: velocity_lag must be ≥ 0 and finite [s], got " +
                std::to_string(goal.velocity_lag));
  return goal;
}

}  // namespace

ShelfPickTask::ShelfPickTask(const Chain& chain, const ShelfPickGoal& goal, Recorder* recorder)
    : chain_(chain),
      goal_(checked(chain, goal)),
      recorder_(recorder),
      profile_(goal.approach_time),
      monitor_(goal.X_WS.p, goal.X_WT.p, goal.criteria),
      t0_(std::numeric_limits<double>::quiet_NaN()) {
  if (!goal.position_only) rotation_ = so3::log(goal.X_WT.R * goal.X_WS.R.transpose());
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
  const MinJerkProfile::Sample s = profile_.at(t);
  const double ds = profile_.at(t - goal_.velocity_lag).ds;
  TaskReference& task = reference.task;
  const Eigen::Vector3d dp = goal_.X_WT.p - goal_.X_WS.p;
  task.X_WE.p = goal_.X_WS.p + s.s * dp;
  task.X_WE.R = goal_.position_only ? goal_.X_WT.R
                                    : Eigen::Matrix3d(so3::exp(s.s * rotation_) * goal_.X_WS.R);
  task.V_WE << ds * dp, ds * rotation_;
  task.A_WE << s.dds * dp, s.dds * rotation_;
  task.F_ext.setZero();
  JointReference& joint = reference.joint;
  if (joint.q.size() != n) joint.q.resize(n);
  if (joint.qd.size() != n) joint.qd.resize(n);
  if (joint.qdd.size() != n) joint.qdd.resize(n);
  joint.q = goal_.q_start + s.s * (goal_.q_target - goal_.q_start);
  joint.qd = ds * (goal_.q_target - goal_.q_start);
  joint.qdd = s.dds * (goal_.q_target - goal_.q_start);

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
      enter(t < profile_.duration() ? PickPhase::approach : PickPhase::settle, data.time);
      break;
    case PickEvent::held:
      enter(PickPhase::release, data.time);
      break;
    case PickEvent::none:
      if (phase_ == PickPhase::approach && t >= profile_.duration())
        enter(PickPhase::settle, data.time);
      break;
  }
  reference.gripper = phase_ == PickPhase::hold ? 1.0 : 0.0;
  return phase_ != PickPhase::release;
}

}  // namespace mjarm
