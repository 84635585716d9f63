#include "mjarm/teleop/bimanual_lift.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

// qpos address of the free joint of body @p name
int free_joint_qpos(const Robot& robot, const std::string& name) {
  const mjModel& m = robot.model();
  const int body = robot.body(name);
  for (int j = 0; j < m.njnt; ++j) {
    if (m.jnt_bodyid[j] == body && m.jnt_type[j] == mjJNT_FREE) return m.jnt_qposadr[j];
  }
  throw Error("bimanual lift: body '" + name + "' has no free joint");
}

}  // namespace

BimanualLiftResult run_bimanual_lift(SessionRecorder& recorder, const BimanualLiftOptions& o,
                                     const std::function<void(const TeleopSession&)>& on_tick) {
  check_fields(o);
  TeleopSession& session = recorder.session();
  if (session.hands().size() != 2)
    throw Error("bimanual lift: the session needs two hands, it has " +
                std::to_string(session.hands().size()));
  const int adr = free_joint_qpos(session.robot(), o.object);
  auto bar = [&]() {
    const double* q = session.simulation().data().qpos + adr;
    return Pose{Eigen::Quaterniond(q[3], q[4], q[5], q[6]).toRotationMatrix(),
                Eigen::Vector3d(q[0], q[1], q[2])};
  };
  const Pose X_WB = bar();
  BimanualLiftResult result;
  result.start_z = X_WB.p.z();
  // grasp frames: tool z down, fingers closing across the bar (along its x axis), the left hand
  // at the bar's +y end
  const Eigen::Vector3d axis = X_WB.R.col(1);
  const double yaw = std::atan2(X_WB.R(1, 0), X_WB.R(0, 0)) + std::numbers::pi / 2;
  const Eigen::Matrix3d R_grasp = rotation_from_rpy(std::numbers::pi, 0.0, yaw);
  const double sides[2] = {1.0, -1.0};
  auto targets_at = [&](double up, double gripper, double lift_by) {
    TeleopTargets t = session.targets();
    for (int i = 0; i < 2; ++i) {
      t.hands[i].X_WT.R = R_grasp;
      t.hands[i].X_WT.p = X_WB.p + sides[i] * o.grasp_offset * axis +
                          Eigen::Vector3d(0.0, 0.0, o.grasp_height + up + lift_by);
      t.hands[i].gripper = gripper;
    }
    return t;
  };
  auto run = [&](double seconds) {
    const int ticks = static_cast<int>(std::lround(seconds / session.control_period()));
    for (int k = 0; k < ticks; ++k) {
      if (recorder.step(1) != 1) return false;
      ++result.ticks;
      if (on_tick) on_tick(session);
    }
    return true;
  };
  bool ok = true;
  recorder.set_targets(targets_at(o.approach_height, 0.0, 0.0));
  ok = ok && run(o.approach_time);
  recorder.set_targets(targets_at(0.0, 0.0, 0.0));
  ok = ok && run(o.descend_time);
  recorder.set_targets(targets_at(0.0, 1.0, 0.0));
  ok = ok && run(o.close_time);
  recorder.set_targets(targets_at(0.0, 1.0, o.lift_height));
  ok = ok && run(o.lift_time);
  const double hold_start = bar().p.z();
  const int hold_ticks = static_cast<int>(std::lround(o.hold_time / session.control_period()));
  for (int k = 0; ok && k < hold_ticks; ++k) {
    ok = recorder.step(1) == 1;
    ++result.ticks;
    if (on_tick) on_tick(session);
    result.sag = std::max(result.sag, hold_start - bar().p.z());
  }
  result.end_z = bar().p.z();
  result.lifted = result.end_z - result.start_z;
  for (int i = 0; i < 2; ++i) result.grasp_force[i] = session.stats().hands[i].grasp_force;
  if (!ok) {
    result.failure = "the simulation stopped: " + session.stats().fault;
  } else if (result.lifted < o.lift_height - o.tolerance) {
    result.failure = "the bar rose " + number_text(result.lifted) + " m, not " +
                     number_text(o.lift_height) + " m";
  } else if (result.sag > o.tolerance) {
    result.failure = "the bar sank " + number_text(result.sag) + " m while held";
  }
  result.success = result.failure.empty();
  return result;
}

}  // namespace mjarm
