#include "mjarm/tasks/docking/task.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/tasks/home_ik.hpp"

namespace mjarm {

namespace {

Pose rotation_z(double angle, const Eigen::Vector3d& p) {
  Pose X;
  X.R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.p = p;
  return X;
}

/// E above the seated pose of a socket at @p X_WS by @p height over its top face.
Pose above(const DockingScene& scene, const Pose& X_WS, double height) {
  Pose X = scene.seated(X_WS);
  const DockingGeometry& g = scene.options.geometry;
  X.p += (g.chamfer + g.bore_depth + height) * X_WS.R.col(2);
  return X;
}

/// The first segment; checks the plan first (it is the task's first member to be built).
Se3Interpolation approach_of(const DockingPlan& plan, const DockingMotion& motion) {
  if (plan.q_start.size() == 0 || !plan.q_start.allFinite())
    throw Error("docking task: the plan has no start configuration (use plan_docking)");
  const Pose& goal =
      motion.reference == DockingReference::two_phase ? plan.X_standoff : plan.X_seated;
  return Se3Interpolation(plan.X_start, Vector6d::Zero(), Vector6d::Zero(), goal,
                          plan.approach_time);
}

}  // namespace

void check(const DockingOffset& o) {
  if (!std::isfinite(o.dx) || !std::isfinite(o.dy) || std::abs(o.dx) > 0.05 ||
      std::abs(o.dy) > 0.05)
    throw Error("docking offset: dx and dy must be finite and within ±0.05 m (±50 mm), got (" +
                number_text(o.dx) + ", " + number_text(o.dy) + ") m");
  if (!std::isfinite(o.dyaw) || std::abs(o.dyaw) > std::numbers::pi)
    throw Error("docking offset: dyaw must be finite and within ±π rad (±180°), got " +
                number_text(o.dyaw) + " rad");
}

DockingReference docking_reference(std::string_view name) {
  return parse_enum<DockingReference>(name, "docking reference");
}

void check(const DockingMotion& m) {
  check_fields(m);
  if (!(m.standoff < m.start_height))
    throw Error("docking motion: standoff must be ≥ 0 and below start_height (" +
                number_text(m.start_height) + " m), got " + number_text(m.standoff) + " m");
}

DockingPlan plan_docking(const DockingScene& scene, const DockingOffset& offset,
                         const DockingMotion& motion) {
  check(offset);
  check(motion);
  const DockingGeometry& g = scene.options.geometry;
  DockingPlan plan;
  plan.offset = offset;
  plan.X_WS = scene.options.X_WS;
  plan.X_WB = plan.X_WS * rotation_z(offset.dyaw, Eigen::Vector3d(offset.dx, offset.dy, 0.0));
  plan.full_depth = g.chamfer + g.bore_depth;
  plan.X_start = above(scene, plan.X_WS, motion.start_height);
  plan.X_standoff = above(scene, plan.X_WB, motion.standoff);
  plan.X_seated = scene.seated(plan.X_WB);
  const std::array<double, 3> times = docking_phase_times(motion, g);
  plan.approach_time = times[0];
  plan.insert_time = times[1];
  plan.hold_time = times[2];

  plan.q_start = docking_start_configuration(scene, plan.X_start);
  return plan;
}

std::array<double, 3> docking_phase_times(const DockingMotion& motion,
                                          const DockingGeometry& geometry) {
  check(motion);
  if (motion.reference == DockingReference::single_segment)
    return {motion.single_time, 0.0, motion.hold_time};
  const double insert = TrapezoidProfile(motion.standoff + geometry.chamfer + geometry.bore_depth,
                                         motion.insertion_speed, motion.insertion_acceleration)
                            .duration();
  return {motion.approach_time, insert, motion.hold_time};
}

Eigen::VectorXd docking_start_configuration(const DockingScene& scene, const Pose& X_WE) {
  const IkResult result = home_pose_ik(scene.robot, scene.chain, X_WE);
  if (result.status != IkStatus::converged)
    throw Error("docking: the start pose (tip at (" + number_text(X_WE.p.x()) + ", " +
                number_text(X_WE.p.y()) + ", " + number_text(X_WE.p.z()) +
                ") m) is out of reach of the iiwa14 (IK " + std::string(to_string(result.status)) +
                "); move the socket closer");
  return result.q;
}

DockingTask::DockingTask(const DockingPlan& plan, const DockingMotion& motion, double velocity_lag,
                         Recorder* recorder)
    : plan_(plan),
      motion_(motion),
      velocity_lag_(velocity_lag),
      recorder_(recorder),
      approach_(approach_of(plan, motion)),
      direction_(-plan.X_WB.R.col(2)),
      t0_(std::numeric_limits<double>::quiet_NaN()) {
  check(motion);
  if (!(velocity_lag >= 0.0) || !std::isfinite(velocity_lag))
    throw Error("docking task: velocity_lag must be ≥ 0 and finite [s]");
  if (motion.reference == DockingReference::two_phase)
    insertion_.emplace(motion.standoff + plan.full_depth, motion.insertion_speed,
                       motion.insertion_acceleration);
  X_WD_ = plan.X_start;
}

Se3Interpolation::Sample DockingTask::at(double t) const noexcept {
  if (t < plan_.approach_time) return approach_.at(t);
  Se3Interpolation::Sample s;
  s.X_WE = plan_.X_seated;
  if (insertion_ && t < plan_.approach_time + plan_.insert_time) {
    const TrapezoidProfile::Sample i = insertion_->at(t - plan_.approach_time);
    s.X_WE = plan_.X_standoff;
    s.X_WE.p += i.position * direction_;
    s.V_WE.head<3>() = i.velocity * direction_;
    s.A_WE.head<3>() = i.acceleration * direction_;
  }
  return s;
}

void DockingTask::enter(DockingPhase phase, double t) noexcept {
  if (phase == phase_ && started_) return;
  phase_ = phase;
  if (recorder_ != nullptr) recorder_->event(t, "phase", to_string(phase));
}

bool DockingTask::update(const mjData& data, Reference& reference) noexcept {
  if (observer_ != nullptr) observer_->on_tick(data);
  if (!started_) {
    t0_ = data.time;
    enter(DockingPhase::approach, data.time);
    started_ = true;
  }
  const double t = data.time - t0_;
  if (t >= plan_.duration() - 1e-9) return false;
  const double t_hold = plan_.approach_time + plan_.insert_time;
  enter(t < plan_.approach_time ? DockingPhase::approach
        : t < t_hold            ? DockingPhase::insert
                                : DockingPhase::hold,
        data.time);

  const Se3Interpolation::Sample now = at(t);
  const Se3Interpolation::Sample lagged = at(std::max(0.0, t - velocity_lag_));
  reference.task.X_WE = now.X_WE;
  reference.task.V_WE = lagged.V_WE;
  reference.task.A_WE = now.A_WE;
  reference.task.F_ext.setZero();
  if (t >= t_hold && motion_.preload > 0.0)
    reference.task.F_ext.head<3>() =
        motion_.preload * std::min(1.0, (t - t_hold) / motion_.preload_ramp) * direction_;
  reference.joint.hold(plan_.q_start);  // the null-space posture
  X_WD_ = now.X_WE;
  return true;
}

}  // namespace mjarm
