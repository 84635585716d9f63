#include "mjarm/tasks/docking_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "docking_checks.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/se3.hpp"

namespace mjarm {

namespace {

constexpr std::array<DockingLaw, 3> kLaws{DockingLaw::cic, DockingLaw::hqp_ac, DockingLaw::se3};

void require_gains(const Vector6d& v, const std::string& what) {
  static const char* const kAxes[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int i = 0; i < 6; ++i)
    docking_detail::require_positive(v[i], "docking controller", what + " " + kAxes[i]);
}

}  // namespace

const char* to_string(DockingLaw law) noexcept {
  switch (law) {
    case DockingLaw::cic:
      return "cic";
    case DockingLaw::hqp_ac:
      return "hqp-ac";
    case DockingLaw::se3:
      return "se3";
  }
  return "unknown";
}

DockingLaw docking_law(std::string_view name) {
  for (DockingLaw law : kLaws)
    if (name == to_string(law)) return law;
  throw Error("unknown docking controller '" + std::string(name) +
              "'; controllers: cic, hqp-ac, se3");
}

std::span<const DockingLaw> docking_laws() noexcept { return kLaws; }

const char* to_string(ForceSource source) noexcept {
  return source == ForceSource::sensor ? "sensor" : "observer";
}

void check(const DockingControllerOptions& o) {
  if (!(o.sensor_cutoff > 0.0) || std::isnan(o.sensor_cutoff))
    throw Error("docking controller: sensor_cutoff must be positive [Hz] (+inf: no filter), got " +
                std::to_string(o.sensor_cutoff));
  require_gains(o.se3_inertia, "se3_inertia");
  require_gains(o.se3_stiffness, "se3_stiffness");
  docking_detail::require_positive(o.se3_damping_ratio, "docking controller", "se3_damping_ratio");
  docking_detail::require_positive(o.release_force, "docking controller", "release_force [N]");
  docking_detail::require_positive(o.release_duration, "docking controller",
                                   "release_duration [s]");
  require_gains(o.cic_stiffness, "cic_stiffness");
  docking_detail::require_positive(o.cic_damping_ratio, "docking controller", "cic_damping_ratio");
  docking_detail::require_non_negative(o.nullspace_stiffness, "docking controller",
                                       "nullspace_stiffness");
  docking_detail::require_non_negative(o.nullspace_damping, "docking controller",
                                       "nullspace_damping");
  docking_detail::require_positive(o.control_period, "docking controller", "control_period [s]");
}

DockingController::DockingController(const DockingScene& scene,
                                     const DockingControllerOptions& options)
    : options_(options),
      dynamics_(scene.chain),
      friction_(scene.chain, friction_options_for(true, options.friction_mode)),
      peg_mass_(scene.peg_mass),
      peg_com_E_(scene.peg_com_E) {
  check(options);
  const Chain& chain = scene.chain;
  const mjModel& m = scene.robot.model();
  if (!(m.opt.disableflags & mjDSBL_GRAVITY))
    gravity_ = Eigen::Map<const Eigen::Vector3d>(m.opt.gravity);
  switch (options.law) {
    case DockingLaw::se3: {
      Se3ImpedanceOptions o;
      o.inertia = options.se3_inertia.asDiagonal();
      o.stiffness = options.se3_stiffness.asDiagonal();
      o.damping = (2.0 * options.se3_damping_ratio *
                   options.se3_inertia.cwiseProduct(options.se3_stiffness).cwiseSqrt())
                      .asDiagonal();
      o.release.axes = options.se3_release;
      o.release.contact_force = options.release_force;
      o.release.duration = options.release_duration;
      o.nullspace_stiffness = options.nullspace_stiffness;
      o.nullspace_damping = options.nullspace_damping;
      se3_ = std::make_unique<Se3ImpedanceController>(chain, o);
      law_ = se3_.get();
      break;
    }
    case DockingLaw::cic: {
      OperationalSpaceOptions o;
      o.mode = TaskMode::pose;
      o.task_inertia = true;  // the arm's own Λ: passive against contact, no measurement needed
      o.stiffness = options.cic_stiffness;
      o.damping = Vector6d::Constant(-1.0);
      o.damping_ratio = options.cic_damping_ratio;
      o.nullspace_stiffness = options.nullspace_stiffness;
      o.nullspace_damping = options.nullspace_damping;
      cic_ = std::make_unique<OperationalSpaceController>(chain, o);
      law_ = cic_.get();
      stiffness_ = options.cic_stiffness;
      break;
    }
    case DockingLaw::hqp_ac:
      throw Error(
          "docking controller: hqp-ac is not available in this build yet (it comes with "
          "the HQP-AC controller of control/); use cic or se3");
  }
  if (options.source == ForceSource::sensor) {
    sensor_.emplace(scene.robot, DockingNames::ft_site);  // names the site when it is missing
    if (std::isfinite(options.sensor_cutoff)) {
      filtered_ = true;
      alpha_ =
          1.0 - std::exp(-2.0 * std::numbers::pi * options.sensor_cutoff * options.control_period);
    }
  } else {
    observer_.emplace(chain, friction_);
  }
  // motor ranges, for the torque the observer is told about
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
  move_ = Eigen::VectorXd::Zero(n);
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
  if (observer_) observer_->reset();
  wrench_.setZero();
  bad_wrench_ticks_ = 0;
}

void DockingController::measure(const mjData& data) noexcept {
  const Pose& X_WE = dynamics_.pose();
  if (observer_) {
    wrench_ = observer_->contact_wrench();  // from the previous tick's update
    return;
  }
  const WrenchReading reading = sensor_->read_world(data, X_WE.p);
  if (!reading.ok()) {
    ++bad_wrench_ticks_;
    return;  // keep the last filtered value: a lost sample, not a zero force
  }
  // the environment's wrench on the peg: the sensor holds the peg against its weight and the
  // contact, −S = m·g + F_env (quasi-static)
  Vector6d F;
  const Eigen::Vector3d weight = peg_mass_ * gravity_;
  F.head<3>() = -reading.wrench.head<3>() - weight;
  F.tail<3>() = -reading.wrench.tail<3>() - (X_WE.R * peg_com_E_).cross(weight);
  if (filtered_) {
    wrench_ += alpha_ * (F - wrench_);
  } else {
    wrench_ = F;
  }
}

void DockingController::compute(const mjData& data, const Reference& reference,
                                JointCommand& command) noexcept {
  const int n = dynamics_.size();
  if (command.value.size() != n) return;
  dynamics_.update(data);
  measure(data);
  if (se3_) {
    const Pose& X_WE = dynamics_.pose();
    Vector6d F_E;
    F_E.head<3>() = X_WE.R.transpose() * wrench_.head<3>();
    F_E.tail<3>() = X_WE.R.transpose() * wrench_.tail<3>();
    se3_->set_measured_wrench(F_E);
    // the preload: shift the target so that the spring pushes with F_ext (D's axes)
    reference_.task = reference.task;
    reference_.gripper = reference.gripper;
    if (reference.joint.q.size() == n) {
      reference_.joint.q = reference.joint.q;
      reference_.joint.qd = reference.joint.qd;
      reference_.joint.qdd = reference.joint.qdd;
    }
    const Vector6d& F_ext = reference.task.F_ext;
    if (F_ext.allFinite() && !F_ext.isZero(0.0)) {
      const Eigen::Matrix3d& R_WD = reference.task.X_WE.R;
      Vector6d F_D;
      F_D.head<3>() = R_WD.transpose() * F_ext.head<3>();
      F_D.tail<3>() = R_WD.transpose() * F_ext.tail<3>();
      Vector6d shift = Vector6d::Zero();
      const Matrix6d& K = se3_->stiffness();
      for (int i = 0; i < 6; ++i)
        if (!options_.se3_release[static_cast<std::size_t>(i)] && K(i, i) > 0.0)
          shift[i] = F_D[i] / K(i, i);
      reference_.task.X_WE = reference.task.X_WE * se3::exp(shift);
    }
    se3_->compute(data, reference_, command);
    stiffness_ = se3_->stiffness().diagonal();
  } else {
    cic_->compute(data, reference, command);
  }
  if (options_.friction_feed_forward && friction_.active()) {
    // the part of τ that moves the joints sets the feed-forward's sign
    const Eigen::VectorXd& h = dynamics_.bias();
    for (int i = 0; i < n; ++i)
      move_[i] = command.value[i] - h[i] + data.qfrc_passive[dynamics_.chain().dof_address(i)];
    tau_ = move_;
    friction_.apply(dynamics_.qd(), tau_);
    command.value += tau_ - move_;
  }
  if (observer_) {
    tau_ = command.value.cwiseMax(lower_).cwiseMin(upper_);
    observer_->update(data, dynamics_, tau_, options_.control_period);
  }
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
