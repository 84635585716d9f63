#include "mjarm/tasks/wiping/task.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/tasks/home_ik.hpp"

namespace mjarm {

namespace {

constexpr double kTableXMin = kWipingTableNear, kTableXMax = kWipingTableNear + kWipingTableDepth,
                 kTableYHalf = 0.5 * kWipingTableWidth;

/// The tool pointing straight down, its x against the world's (the iiwa's flange at home).
Eigen::Matrix3d tool_down() { return Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal(); }

/// @throws Error when @p p (a point of the stroke) is not on the table with @p margin to spare.
void check_on_table(const Eigen::Vector3d& p, double margin, const char* which) {
  if (p.x() < kTableXMin + margin || p.x() > kTableXMax - margin ||
      std::abs(p.y()) > kTableYHalf - margin)
    throw Error(std::string("wiping: the stroke's ") + which + " (" + number_text(p.x()) + ", " +
                number_text(p.y()) + ") m is off the table (x " + number_text(kTableXMin) + " … " +
                number_text(kTableXMax) + " m, |y| ≤ " + number_text(kTableYHalf) +
                " m, less the pad's radius)");
}

Eigen::VectorXd start_configuration(const WipingScene& scene, const Pose& X_WE) {
  const IkResult result = home_pose_ik(scene.robot, scene.chain, X_WE);
  if (result.status != IkStatus::converged)
    throw Error("wiping: the start (tip at (" + number_text(X_WE.p.x()) + ", " +
                number_text(X_WE.p.y()) + ", " + number_text(X_WE.p.z()) +
                ") m) is out of the iiwa14's reach (IK " + std::string(to_string(result.status)) +
                ")");
  return result.q;
}

}  // namespace

WipingPlan plan_wiping(const WipingScene& scene, const WipingPath& path, const WipingMotion& motion,
                       std::uint64_t seed) {
  check_fields(path);
  check_fields(motion);
  WipingPlan plan;
  Random rng(splitmix64(seed));
  const double u = path.height_uncertainty;
  plan.true_height = scene.surface.table_height;
  plan.believed_height = plan.true_height + (u > 0.0 ? uniform(rng, -u, u) : 0.0);
  plan.direction = Eigen::Vector3d(std::cos(path.heading), std::sin(path.heading), 0.0);
  plan.length = path.length;
  const Eigen::Vector3d center(path.center[0], path.center[1], plan.believed_height);
  plan.start = center - 0.5 * path.length * plan.direction;
  const double margin = scene.surface.pad_radius;
  check_on_table(plan.start, margin, "start");
  check_on_table(center + 0.5 * path.length * plan.direction, margin, "end");
  plan.X_start = Pose{tool_down(), plan.start + motion.start_height * Eigen::Vector3d::UnitZ()};
  plan.q_start = start_configuration(scene, plan.X_start);
  plan.approach_time = motion.approach_time;
  plan.press_time = motion.force_ramp + motion.settle_time;
  plan.stroke_time = TrapezoidProfile(path.length, motion.speed, motion.acceleration).duration();
  plan.hold_time = motion.hold_time;
  return plan;
}

namespace {

WrenchSourceOptions sensor_options() {
  WrenchSourceOptions o;
  o.kind = WrenchSourceKind::sensor;
  o.site = WipingNames::ft_site;
  return o;
}

}  // namespace

WipingTask::WipingTask(const WipingScene& scene, const WipingPlan& plan, const WipingMotion& motion,
                       const WipingForceLoop& loop, std::uint64_t seed, Recorder* recorder)
    : scene_(scene),
      plan_(plan),
      motion_(motion),
      loop_(loop),
      recorder_(recorder),
      sensor_(scene.chain, sensor_options()),
      noise_(splitmix64(seed ^ 0x5eed'0f'f0'5e'd0'15eULL)),
      approach_(plan.X_start, Vector6d::Zero(), Vector6d::Zero(), Pose{plan.X_start.R, plan.start},
                plan.approach_time),
      stroke_(plan.length, motion.speed, motion.acceleration),
      t0_(std::numeric_limits<double>::quiet_NaN()) {
  check_fields(motion);
  check_fields(loop);
}

void WipingTask::enter(WipingPhase phase, double time) noexcept {
  if (phase == phase_ && started_) return;
  phase_ = phase;
  if (recorder_ != nullptr) recorder_->event(time, "phase", to_string(phase));
}

bool WipingTask::update(const mjData& data, Reference& reference) noexcept {
  if (observer_ != nullptr) observer_->on_tick(data);
  if (!started_) {
    t0_ = data.time;
    last_time_ = data.time;
    enter(WipingPhase::approach, data.time);
    started_ = true;
  }
  const double t = data.time - t0_;
  if (t >= plan_.duration() - 1e-9) return false;
  const double t_press = plan_.approach_time;
  const double t_stroke = plan_.stroke_start();
  const double t_hold = t_stroke + plan_.stroke_time;
  enter(t < t_press    ? WipingPhase::approach
        : t < t_stroke ? WipingPhase::press
        : t < t_hold   ? WipingPhase::stroke
                       : WipingPhase::hold,
        data.time);

  TaskReference& task = reference.task;
  if (phase_ == WipingPhase::approach) {
    const Se3Interpolation::Sample s = approach_.at(t);
    task.X_WE = s.X_WE;
    task.V_WE = s.V_WE;
    task.A_WE = s.A_WE;
  } else {
    const TrapezoidProfile::Sample s = stroke_.at(std::max(0.0, t - t_stroke));
    task.X_WE = Pose{plan_.X_start.R, plan_.start + s.position * plan_.direction};
    task.V_WE.setZero();
    task.A_WE.setZero();
    task.V_WE.head<3>() = s.velocity * plan_.direction;
    task.A_WE.head<3>() = s.acceleration * plan_.direction;
  }
  p_WD_ = task.X_WE.p;

  // the force: feed-forward F_d, and the loop on the sensor's normal force from the press on
  const double dt = data.time - last_time_;
  last_time_ = data.time;
  desired_force_ =
      t < t_press ? 0.0 : motion_.force * std::min(1.0, (t - t_press) / motion_.force_ramp);
  double correction = 0.0;
  if (t >= t_press && loop_.gain > 0.0) {
    const int tip = scene_.chain.frame().id;
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(data.site_xmat +
                                                                           9 * tip);
    const Pose X_WE{R, Eigen::Map<const Eigen::Vector3d>(data.site_xpos + 3 * tip)};
    sensor_.measure(data, X_WE);
    const double measured = sensor_.wrench()(2) + normal(noise_, 0.0, loop_.sensor_noise);
    if (std::isfinite(measured)) integral_ += (desired_force_ - measured) * dt;
    const double bound = desired_force_ / loop_.gain;
    integral_ = std::clamp(integral_, -bound, bound);
    correction = loop_.gain * integral_;
  }
  commanded_force_ = desired_force_ + correction;
  task.F_ext.setZero();
  task.F_ext(2) = -commanded_force_;

  reference.joint.hold(plan_.q_start);  // the null-space posture
  return true;
}

}  // namespace mjarm
