#include "mjarm/tasks/docking/task.hpp"

#include <algorithm>
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
  check(motion.search, g);
  DockingPlan plan;
  plan.offset = offset;
  plan.X_WS = scene.options.X_WS;
  plan.X_WB = plan.X_WS * rotation_z(offset.dyaw, Eigen::Vector3d(offset.dx, offset.dy, 0.0));
  plan.full_depth = g.chamfer + g.bore_depth;
  plan.clearance = g.bore_radius - g.peg_radius;
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
      t0_(std::numeric_limits<double>::quiet_NaN()),
      insert_from_(plan.X_standoff),
      insert_start_(plan.approach_time),
      hold_start_(plan.approach_time + plan.insert_time),
      X_hold_(plan.X_seated),
      centring_(motion.centring, plan.clearance),
      miss_since_(std::numeric_limits<double>::quiet_NaN()),
      miss_time_(std::numeric_limits<double>::quiet_NaN()),
      drop_time_(std::numeric_limits<double>::quiet_NaN()) {
  check(motion);
  if (!(velocity_lag >= 0.0) || !std::isfinite(velocity_lag))
    throw Error("docking task: velocity_lag must be ≥ 0 and finite [s]");
  if (motion.reference == DockingReference::two_phase)
    insertion_.emplace(motion.standoff + plan.full_depth, motion.insertion_speed,
                       motion.insertion_acceleration);
  X_WD_ = plan.X_start;
}

void DockingTask::attach(ContactChannel& channel, int tip_site) noexcept {
  if (motion_.reference != DockingReference::two_phase || tip_site < 0) return;
  search_on_ = motion_.search.pattern != SearchPattern::none;
  centring_on_ = motion_.centring.enabled && channel.releases();
  if (!search_on_ && !centring_on_) return;
  channel_ = &channel;
  tip_site_ = tip_site;
  if (search_on_) path_.emplace(motion_.search);
}

double DockingTask::max_duration() const noexcept {
  if (!search_on_) return plan_.duration();
  const double reinsert = TrapezoidProfile(motion_.standoff + plan_.full_depth,
                                           motion_.insertion_speed, motion_.insertion_acceleration)
                              .duration();
  return plan_.duration() + motion_.search.timeout + reinsert;
}

Eigen::Vector3d DockingTask::tip(const mjData& data) const noexcept {
  return Eigen::Map<const Eigen::Vector3d>(data.site_xpos + 3 * tip_site_);
}

bool DockingTask::missed(const mjData& data, double t) noexcept {
  const DockingSearchOptions& o = motion_.search;
  const Vector6d& F = channel_->measured_wrench();    // the environment on E
  const double axial = -F.head<3>().dot(direction_);  // the peg pushing in
  const double lateral = (F.head<3>() + axial * direction_).norm();
  // the tip's depth below the believed top face (the seated pose is full_depth below it)
  const double depth = (tip(data) - plan_.X_seated.p).dot(direction_) + plan_.full_depth;
  const bool flat = F.allFinite() && axial >= o.miss_force &&
                    lateral <= o.miss_lateral_ratio * axial && depth <= o.miss_max_depth;
  if (!flat) {
    miss_since_ = std::numeric_limits<double>::quiet_NaN();
    return false;
  }
  if (std::isnan(miss_since_)) miss_since_ = t;
  return t - miss_since_ >= o.miss_dwell - 1e-9;
}

void DockingTask::restart_insertion(const mjData& data, double t) noexcept {
  insert_from_.R = plan_.X_seated.R;
  insert_from_.p = tip(data);
  const double length = std::max(0.0, (plan_.X_seated.p - insert_from_.p).dot(direction_));
  insertion_.emplace(length, motion_.insertion_speed, motion_.insertion_acceleration);
  insert_start_ = t;
  hold_start_ = t + insertion_->duration();
  X_hold_ = insert_from_;
  X_hold_.p += length * direction_;
  channel_->set_release_armed(true);
  centring_.reset();
  rearm_at_hold_ = false;
}

DockingTask::SearchStep DockingTask::search(const mjData& data, double t,
                                            Reference& reference) noexcept {
  const DockingSearchOptions& o = motion_.search;
  const Eigen::Vector3d p = tip(data);
  if ((p - center_).dot(direction_) >= o.drop_depth) {  // the drop into the hole
    search_total_ += t - search_start_;
    drop_time_ = t;
    if (recorder_ != nullptr) recorder_->event(data.time, "search", "drop");
    restart_insertion(data, t);
    return SearchStep::dropped;
  }
  const SearchPath::Sample s = path_->at(t - search_start_);
  if (s.radius > o.max_radius * (1.0 + 1e-9) || search_total_ + (t - search_start_) > o.timeout) {
    search_total_ += t - search_start_;
    exhausted_ = true;
    if (recorder_ != nullptr) recorder_->event(data.time, "search", "exhausted");
    return SearchStep::exhausted;
  }
  // the axial force held at contact_force: F_ext fed to the law, trimmed by the measured error
  const Vector6d& F = channel_->measured_wrench();
  const double axial = -F.head<3>().dot(direction_);
  if (std::isfinite(axial))
    trim_ = std::clamp(trim_ + o.force_gain * (o.contact_force - axial) * (t - last_t_),
                       -o.force_trim, o.force_trim);
  const Eigen::Matrix3d& R = plan_.X_WB.R;
  reference.task.X_WE.R = plan_.X_seated.R;
  reference.task.X_WE.p =
      center_ + R.col(0) * s.offset.x() + R.col(1) * s.offset.y() + trim_ * direction_;
  reference.task.V_WE.setZero();
  reference.task.V_WE.head<3>() = R.col(0) * s.velocity.x() + R.col(1) * s.velocity.y();
  reference.task.A_WE.setZero();
  reference.task.F_ext.setZero();
  reference.task.F_ext.head<3>() = o.contact_force * direction_;
  return SearchStep::searching;
}

void DockingTask::centre(const mjData& data, double t, double t_hold, Se3Interpolation::Sample& now,
                         Se3Interpolation::Sample& lagged) noexcept {
  const Eigen::Vector3d p = tip(data);
  if (phase_ == DockingPhase::insert && t < t_hold) {
    const double depth = (p - plan_.X_seated.p).dot(direction_) + plan_.full_depth;
    if (centring_.decide(depth, p, now.X_WE.p, direction_, t)) {
      // the reference starts on the tip laterally when the stiffness comes back: nothing jumps
      channel_->set_release_armed(false);
      rearm_at_hold_ = true;
    }
  } else if (rearm_at_hold_ && t >= t_hold) {  // at the bottom the preload releases it again
    channel_->set_release_armed(true);
    rearm_at_hold_ = false;
  }
  if (!centring_.active()) return;
  centring_.update(p, now.X_WE.p, t);
  now.X_WE.p += centring_.shift(t);
  lagged.V_WE.head<3>() += centring_.shift_rate(std::max(0.0, t - velocity_lag_));
}

Se3Interpolation::Sample DockingTask::at(double t) const noexcept {
  if (t < plan_.approach_time) return approach_.at(t);
  Se3Interpolation::Sample s;
  s.X_WE = X_hold_;
  if (insertion_ && t < hold_start_) {
    const TrapezoidProfile::Sample i = insertion_->at(std::max(0.0, t - insert_start_));
    s.X_WE = insert_from_;
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
  if (phase_ == DockingPhase::search) {
    const SearchStep step = search(data, t, reference);
    last_t_ = t;
    if (step == SearchStep::exhausted) return false;
    if (step == SearchStep::searching) {
      reference.joint.hold(plan_.q_start);
      X_WD_ = reference.task.X_WE;
      return true;
    }  // dropped: the new insertion below
  } else if (t >= hold_start_ + plan_.hold_time - 1e-9) {
    return false;
  }
  const double t_hold = hold_start_;
  if (search_on_ && phase_ == DockingPhase::insert && t < t_hold && missed(data, t)) {
    ++searches_;
    if (std::isnan(miss_time_)) miss_time_ = t;
    center_ = tip(data);
    search_start_ = t;
    last_t_ = t;
    trim_ = 0.0;
    path_.emplace(motion_.search);
    channel_->set_release_armed(false);
    enter(DockingPhase::search, data.time);
    search(data, t, reference);
    reference.joint.hold(plan_.q_start);
    X_WD_ = reference.task.X_WE;
    return true;
  }
  enter(t < plan_.approach_time ? DockingPhase::approach
        : t < t_hold            ? DockingPhase::insert
                                : DockingPhase::hold,
        data.time);

  Se3Interpolation::Sample now = at(t);
  Se3Interpolation::Sample lagged = at(std::max(0.0, t - velocity_lag_));
  if (centring_on_) centre(data, t, t_hold, now, lagged);
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
