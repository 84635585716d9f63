#include "mjarm/control/cartesian_impedance.hpp"

#include <cmath>

#include "control_checks.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/kinematics/frame_state.hpp"

namespace mjarm {
namespace {

/// True when a chain dof has joint friction (dof_frictionloss > 0).
bool cic_has_friction(const Chain& chain) {
  const mjModel& m = chain.robot().model();
  for (const int dof : chain.dof_addresses()) {
    if (m.dof_frictionloss[dof] > 0.0) return true;
  }
  return false;
}

bool cic_integral_on(const Chain& chain, CicIntegral integral) {
  switch (integral) {
    case CicIntegral::on:
      return true;
    case CicIntegral::off:
      return false;
    case CicIntegral::automatic:
      break;
  }
  return cic_has_friction(chain);
}

/// The law's options for the operational-space controller, after checking ours.
OperationalSpaceOptions cic_law_options(const CartesianImpedanceOptions& o, bool integral_on) {
  check_fields(o, "cic");
  OperationalSpaceOptions law;
  law.mode = TaskMode::pose;
  law.stiffness = o.stiffness;
  law.damping = o.damping;
  law.damping_ratio = o.damping_ratio;
  law.inertia = o.desired_inertia;
  law.task_inertia = o.inertia == CicInertia::natural;
  law.wrench_feedback = o.inertia == CicInertia::exact;
  law.integral_gain.setZero();
  law.integral_limit.setZero();
  if (integral_on) {
    law.integral_gain.head<3>().setConstant(o.integral_gain);
    law.integral_limit.head<3>().setConstant(o.integral_bound / o.integral_gain);
  }
  law.integral_hold_force = o.integral_hold_force;
  law.nullspace_damping = o.nullspace_damping;
  law.nullspace_stiffness = o.nullspace_stiffness;
  law.compensate_passive = true;
  law.task_space = o.task_space;
  law.joint_limits = o.joint_limits;
  return law;
}

FrictionFeedForwardOptions cic_friction_options(const CartesianImpedanceOptions& o) {
  FrictionFeedForwardOptions f = o.friction;
  f.damping = DampingCompensation::by_controller;  // the law cancels qfrc_passive
  return f;
}

}  // namespace

CartesianImpedanceController::CartesianImpedanceController(const Chain& chain,
                                                           const CartesianImpedanceOptions& options)
    : options_(options),
      integral_on_(cic_integral_on(chain, options.integral)),
      impedance_(chain, cic_law_options(options, integral_on_)),
      source_(chain, options.force),
      friction_(chain, cic_friction_options(options)),
      friction_on_(options.friction_feed_forward && friction_.active()) {
  moving_.setZero(chain.size());
  friction_torque_.setZero(chain.size());
}

void CartesianImpedanceController::reset() noexcept {
  impedance_.reset();
  source_.reset();
  friction_torque_.setZero();
  status_ = CicStatus::ok;
  values_.fill(0.0);
}

void CartesianImpedanceController::hold(const mjData& data, Eigen::Ref<Eigen::VectorXd> tau,
                                        CicStatus status) noexcept {
  // τ = h − τ_passive − D_n·q̇, read straight from data (the law's dynamics may be stale)
  const Chain& c = chain();
  for (int i = 0; i < c.size(); ++i) {
    const int dof = c.dof_address(i);
    tau[i] =
        data.qfrc_bias[dof] - data.qfrc_passive[dof] - options_.nullspace_damping * data.qvel[dof];
  }
  if (!tau.allFinite()) tau.setZero();
  friction_torque_.setZero();
  status_ = status;
  values_.fill(0.0);
  values_[11] = static_cast<double>(static_cast<int>(status));
}

void CartesianImpedanceController::compute(const mjData& data, const Reference& reference,
                                           JointCommand& command) noexcept {
  command.kind = CommandKind::torque;
  const Chain& c = chain();
  const int n = c.size();
  if (command.value.size() != n) return;
  auto tau = command.value.head(n);

  // the state and the target first: the law's integral must never see a NaN
  const Pose X_WE = frame_pose(c.robot().model(), data, c.frame());
  bool state_ok = X_WE.p.allFinite() && detail::is_rotation(X_WE.R) && std::isfinite(data.time);
  for (int i = 0; i < n && state_ok; ++i) {
    const int dof = c.dof_address(i);
    state_ok = std::isfinite(data.qpos[c.qpos_address(i)]) && std::isfinite(data.qvel[dof]) &&
               std::isfinite(data.qfrc_bias[dof]) && std::isfinite(data.qfrc_passive[dof]);
  }
  if (!state_ok) return hold(data, tau, CicStatus::invalid_state);
  const TaskReference& target = reference.task;
  if (!target.X_WE.p.allFinite() || !detail::is_rotation(target.X_WE.R) ||
      !target.V_WE.allFinite() || !target.A_WE.allFinite() || !target.F_ext.allFinite()) {
    return hold(data, tau, CicStatus::invalid_target);
  }

  // the measured wrench, then the law
  const bool wrench_ok = source_.measure(data, X_WE) == WrenchStatus::ok;
  impedance_.set_measured_wrench(source_.wrench());
  impedance_.compute(data, reference, command);
  const ChainDynamics& dyn = impedance_.dynamics();
  if (!tau.allFinite()) return hold(data, tau, CicStatus::invalid_state);

  // friction feed-forward on the part of τ that moves the joints
  if (friction_on_) {
    moving_ = tau - dyn.bias();
    for (int i = 0; i < n; ++i) moving_[i] += data.qfrc_passive[c.dof_address(i)];
    friction_torque_ = moving_;
    friction_.apply(dyn.qd(), friction_torque_);
    friction_torque_ -= moving_;
    tau += friction_torque_;
  }
  source_.record_command(data, dyn, tau);

  status_ = !wrench_ok                                                ? CicStatus::invalid_wrench
            : impedance_.task_space().status() == TaskSpaceStatus::ok ? CicStatus::ok
                                                                      : CicStatus::damped;
  write_values(task_error(dyn.pose(), target.X_WE));
}

void CartesianImpedanceController::write_values(const Vector6d& e) noexcept {
  const Vector6d& F = impedance_.measured_wrench();
  values_[0] = e.head<3>().norm();
  values_[1] = e.tail<3>().norm();
  values_[2] = F.head<3>().norm();
  values_[3] = F.tail<3>().norm();
  for (int i = 0; i < 3; ++i) values_[static_cast<std::size_t>(4 + i)] = impedance_.integral()[i];
  values_[7] = impedance_.integral_held() ? 1.0 : 0.0;
  values_[8] = friction_torque_.norm();
  values_[9] = impedance_.task_space().status() == TaskSpaceStatus::ok ? 0.0 : 1.0;
  values_[10] = source_.status() == WrenchStatus::ok ? 1.0 : 0.0;
  values_[11] = static_cast<double>(static_cast<int>(status_));
}

}  // namespace mjarm
