#include "mjarm/tasks/docking/controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {

namespace {

constexpr std::array<DockingLaw, 3> kLaws{DockingLaw::cic, DockingLaw::hqp_ac, DockingLaw::se3};

}  // namespace

DockingLaw docking_law(std::string_view name) {
  return parse_enum<DockingLaw>(name, "docking controller");
}

std::span<const DockingLaw> docking_laws() noexcept { return kLaws; }

void check(const DockingControllerOptions& o) {
  check_fields(o);
  if (o.law == DockingLaw::hqp_ac && (o.release_axes[3] || o.release_axes[4] || o.release_axes[5]))
    throw Error(
        "docking controller: hqp-ac releases translational axes only (release_axes rx, ry, rz "
        "must be off)");
}

namespace {

WrenchSourceOptions source_options(const DockingControllerOptions& o) {
  WrenchSourceOptions w;
  if (o.source == ForceSource::sensor) {
    w.kind = WrenchSourceKind::sensor;
    w.site = DockingNames::ft_site;
  } else {
    w.kind = WrenchSourceKind::observer;
    w.control_period = o.control_period;
  }
  return w;
}

}  // namespace

DockingController::DockingController(const DockingScene& scene,
                                     const DockingControllerOptions& options)
    : options_(options), dynamics_(scene.chain) {
  check(options);
  const Chain& chain = scene.chain;
  const mjModel& m = scene.robot.model();
  switch (options.law) {
    case DockingLaw::se3: {
      Se3ImpedanceOptions o;
      o.inertia = options.se3_inertia.asDiagonal();
      o.stiffness = options.se3_stiffness.asDiagonal();
      o.damping = (2.0 * options.se3_damping_ratio *
                   options.se3_inertia.cwiseProduct(options.se3_stiffness).cwiseSqrt())
                      .asDiagonal();
      o.release.axes = options.release_axes;
      o.release.contact_force = options.release_force;
      o.release.duration = options.release_duration;
      o.nullspace_stiffness = options.nullspace_stiffness;
      o.nullspace_damping = options.nullspace_damping;
      o.wrench_feed_forward = true;  // the preload F_ext, made by the spring
      o.friction_feed_forward = options.friction_feed_forward;
      o.friction = friction_options_for(true, options.friction_mode);
      se3_ = std::make_unique<Se3ImpedanceController>(chain, o);
      law_ = se3_.get();
      source_.emplace(chain, source_options(options));  // names the site when it is missing
      if (options.source == ForceSource::sensor && std::isfinite(options.sensor_cutoff))
        alpha_ = 1.0 -
                 std::exp(-2.0 * std::numbers::pi * options.sensor_cutoff * options.control_period);
      break;
    }
    case DockingLaw::cic: {
      CartesianImpedanceOptions o;
      o.stiffness = options.cic_stiffness;
      o.damping = Vector6d::Constant(-1.0);
      o.damping_ratio = options.cic_damping_ratio;
      o.nullspace_stiffness = options.nullspace_stiffness;
      o.nullspace_damping = options.nullspace_damping;
      o.friction_feed_forward = options.friction_feed_forward;
      o.friction.mode = options.friction_mode;
      o.force = source_options(options);
      cic_ = std::make_unique<CartesianImpedanceController>(chain, o);
      law_ = cic_.get();
      stiffness_ = options.cic_stiffness;
      break;
    }
    case DockingLaw::hqp_ac: {
      HqpAcOptions o;
      o.compliance.stiffness = options.hqp_stiffness.asDiagonal();
      o.preload.force = 0.0;  // the task's F_ext instead (compute_hqp)
      o.max_velocity = iiwa14_max_velocity();
      o.friction_feed_forward = options.friction_feed_forward;
      o.friction.mode = options.friction_mode;
      o.force = source_options(options);
      hqp_ = std::make_unique<HqpAcController>(chain, o);
      law_ = hqp_.get();
      task_space_.emplace(chain.size(), 6, o.task_space);  // as the law's own
      break;
    }
  }
  // motor ranges, for the torque the observer is told about (se3)
  const int n = chain.size();
  lower_ = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
  upper_ = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i) {
    const std::optional<int> a = chain.actuator(i);
    if (!a || !m.actuator_ctrllimited[*a]) continue;
    const double gear = m.actuator_gear[6 * *a];
    const double lo = gear * m.actuator_ctrlrange[2 * *a];
    const double hi = gear * m.actuator_ctrlrange[2 * *a + 1];
    lower_[i] = std::min(lo, hi);
    upper_[i] = std::max(lo, hi);
  }
  tau_ = Eigen::VectorXd::Zero(n);
  reference_.joint.q = Eigen::VectorXd::Zero(n);
  reference_.joint.qd = Eigen::VectorXd::Zero(n);
  reference_.joint.qdd = Eigen::VectorXd::Zero(n);
  for (const char* axis : {"x", "y", "z", "rx", "ry", "rz"})
    names_.push_back(std::string("wrench_") + axis);
  for (const char* axis : {"x", "y", "z", "rx", "ry", "rz"})
    names_.push_back(std::string("stiffness_") + axis);
  names_.push_back("bad_wrench_ticks");
  for (const std::string& name : law_->internal_names()) names_.push_back(name);
  values_.assign(names_.size(), 0.0);
}

DockingController::~DockingController() = default;

void DockingController::reset() noexcept {
  law_->reset();
  if (source_) source_->reset();
  release_started_ = false;
  release_armed_ = true;
  release_ = 0.0;
  wrench_.setZero();
  bad_wrench_ticks_ = 0;
}

void DockingController::set_release_armed(bool armed) noexcept {
  release_armed_ = armed;
  if (se3_) se3_->set_release_armed(armed);
  if (armed) return;
  release_started_ = false;
  release_ = 0.0;
}

void DockingController::compute(const mjData& data, const Reference& reference,
                                JointCommand& command) noexcept {
  if (command.value.size() != dynamics_.size()) return;
  if (se3_) return compute_se3(data, reference, command);
  if (hqp_) return compute_hqp(data, reference, command);
  cic_->compute(data, reference, command);
  wrench_ = cic_->measured_wrench();
  if (cic_->wrench_source().status() != WrenchStatus::ok) ++bad_wrench_ticks_;
}

void DockingController::copy_reference(const Reference& reference) noexcept {
  const Eigen::Index n = dynamics_.size();
  reference_.task = reference.task;
  reference_.gripper = reference.gripper;
  if (reference.joint.q.size() == n) {
    reference_.joint.q = reference.joint.q;
    reference_.joint.qd = reference.joint.qd;
    reference_.joint.qdd = reference.joint.qdd;
  }
}

void DockingController::compute_hqp(const mjData& data, const Reference& reference,
                                    JointCommand& command) noexcept {
  dynamics_.update(data);
  copy_reference(reference);
  // the preload: A_d + Λ⁻¹·F_ext is the law's own b with F_p = F_ext (same Λ⁻¹, unfloored)
  const Vector6d& F_ext = reference.task.F_ext;
  if (F_ext.allFinite() && !F_ext.isZero(0.0) && dynamics_.q().allFinite() &&
      task_space_->update(dynamics_) != TaskSpaceStatus::not_positive_definite)
    reference_.task.A_WE.noalias() += task_space_->lambda_inverse() * F_ext;
  // the release: the target follows E along the released axes, K_r acts on (I − s·P)·e
  if (release_armed_ && !release_started_ &&
      hqp_->measured_wrench().head<3>().norm() >= options_.release_force) {  // previous tick
    release_started_ = true;
    release_start_ = data.time;
  }
  release_ = release_started_
                 ? smoothstep((data.time - release_start_) / options_.release_duration).s
                 : 0.0;
  const Pose& X_WE = dynamics_.pose();
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i)
    if (options_.release_axes[static_cast<std::size_t>(i)])
      P.noalias() += X_WE.R.col(i) * X_WE.R.col(i).transpose();
  if (release_ > 0.0 && X_WE.p.allFinite())
    reference_.task.X_WE.p += release_ * (P * (X_WE.p - reference.task.X_WE.p));
  hqp_->compute(data, reference_, command);
  wrench_ = hqp_->measured_wrench();
  const Matrix6d& K = hqp_->compliance().stiffness();
  stiffness_ = K.diagonal();
  stiffness_.head<3>() =
      (K.topLeftCorner<3, 3>() * (Eigen::Matrix3d::Identity() - release_ * P)).diagonal();
  if (!hqp_->last_tick().wrench_valid) ++bad_wrench_ticks_;
}

void DockingController::compute_se3(const mjData& data, const Reference& reference,
                                    JointCommand& command) noexcept {
  dynamics_.update(data);
  const Pose& X_WE = dynamics_.pose();
  if (source_->measure(data, X_WE) == WrenchStatus::ok) {
    wrench_ += alpha_ * (source_->wrench() - wrench_);  // α = 1: no filter (the observer)
  } else {
    ++bad_wrench_ticks_;  // keep the last good value: a lost sample, not a zero force
  }
  Vector6d F_E;
  F_E.head<3>() = X_WE.R.transpose() * wrench_.head<3>();
  F_E.tail<3>() = X_WE.R.transpose() * wrench_.tail<3>();
  se3_->set_measured_wrench(F_E);
  // the law adds the preload (F_ext through its spring) and the friction feed-forward itself;
  // the copy keeps the posture of a reference without joint.q at the last one given (or zero)
  copy_reference(reference);
  se3_->compute(data, reference_, command);
  stiffness_ = se3_->stiffness().diagonal();
  tau_ = command.value.cwiseMax(lower_).cwiseMin(upper_);
  source_->record_command(data, dynamics_, tau_);  // the observer only
}

std::span<const double> DockingController::internal_values() const noexcept {
  for (int i = 0; i < 6; ++i) {
    values_[static_cast<std::size_t>(i)] = wrench_[i];
    values_[static_cast<std::size_t>(6 + i)] = stiffness_[i];
  }
  values_[12] = static_cast<double>(bad_wrench_ticks_);
  const std::span<const double> inner = law_->internal_values();
  std::copy(inner.begin(), inner.end(), values_.begin() + 13);
  return values_;
}

}  // namespace mjarm
