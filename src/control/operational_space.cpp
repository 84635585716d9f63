#include "mjarm/control/operational_space.hpp"

#include <algorithm>
#include <cmath>

#include "control_checks.hpp"

namespace mjarm {

OperationalSpaceController::OperationalSpaceController(const Chain& chain,
                                                       const OperationalSpaceOptions& options)
    : options_(options),
      rows_(task_rows(options.mode)),
      dynamics_(chain),
      task_space_(chain.size(), task_rows(options.mode), options.task_space),
      limits_(chain, options.joint_limits) {
  using O = OperationalSpaceOptions;
  check_fields(detail::ignored_rows_cleared(options, rows_, &O::stiffness, &O::damping, &O::inertia,
                                            &O::integral_gain, &O::integral_limit),
               "osc");
  // automatic damping for a fixed desired inertia is a constant
  for (int i = 0; i < 6; ++i) {
    const double d = options.damping[i];
    damping_[i] = d >= 0.0 ? d
                           : 2.0 * options.damping_ratio *
                                 std::sqrt(options.inertia[i] * options.stiffness[i]);
  }
  const int n = chain.size();
  tau0_.setZero(n);
  null_.setZero(n);
  passive_.setZero(n);
}

void OperationalSpaceController::reset() noexcept {
  integral_.setZero();
  force_.setZero();
  wrench_.setZero();
  integral_held_ = false;
  has_last_time_ = false;
  last_time_ = 0.0;
}

void OperationalSpaceController::compute(const mjData& data, const Reference& reference,
                                         JointCommand& command) noexcept {
  command.kind = CommandKind::torque;
  const int n = dynamics_.size();
  const int m = rows_;
  if (command.value.size() != n) return;
  dynamics_.update(data);
  const TaskSpaceStatus status = task_space_.update(dynamics_);
  const Eigen::MatrixXd& Lambda = task_space_.lambda();

  // errors and their integral (clamped: anti-windup)
  const TaskReference& task = reference.task;
  const Vector6d e = task_error(dynamics_.pose(), task.X_WE);
  const Vector6d e_dot = task.V_WE - dynamics_.velocity();
  const double dt = has_last_time_ ? std::max(0.0, data.time - last_time_) : 0.0;
  last_time_ = data.time;
  has_last_time_ = true;
  Vector6d F_m = wrench_;
  if (!F_m.allFinite()) F_m.setZero();
  integral_held_ = F_m.head<3>().norm() >= options_.integral_hold_force;
  if (dt > 0.0 && !integral_held_ && e.allFinite()) {
    for (int i = 0; i < m; ++i) {
      if (options_.integral_gain[i] == 0.0) continue;
      const double limit = options_.integral_limit[i];
      integral_[i] = std::clamp(integral_[i] + e[i] * dt, -limit, limit);
    }
  }

  // impedance wrench, then the task force
  Vector6d damping = damping_;
  if (options_.task_inertia) {
    for (int i = 0; i < m; ++i) {
      if (options_.damping[i] < 0.0) {
        damping[i] = 2.0 * options_.damping_ratio * std::sqrt(Lambda(i, i) * options_.stiffness[i]);
      }
    }
  }
  const Vector6d f = options_.stiffness.cwiseProduct(e) + damping.cwiseProduct(e_dot) +
                     options_.integral_gain.cwiseProduct(integral_);
  Vector6d u = task.A_WE - dynamics_.bias_acceleration();
  const bool feedback = options_.wrench_feedback && !options_.task_inertia;
  if (feedback) {
    // exact M_d: cancel the measured wrench, then feed it (and F_ext) back through M_d⁻¹
    u += (f + F_m + task.F_ext).cwiseQuotient(options_.inertia);
  } else if (!options_.task_inertia) {
    u += f.cwiseQuotient(options_.inertia);
  }
  force_.head(m).noalias() = Lambda * u.head(m);
  if (options_.task_inertia) force_.head(m) += f.head(m);
  if (feedback) {
    force_.head(m) -= F_m.head(m);
  } else {
    force_.head(m) += task.F_ext.head(m);
  }

  // joint torques: task force, bias forces, null-space damping/posture
  auto tau = command.value.head(n);
  tau.noalias() = dynamics_.jacobian().topRows(m).transpose() * force_.head(m);
  tau += dynamics_.bias();
  if (options_.compensate_passive) {
    detail::read_passive(dynamics_.chain(), data, passive_);
    tau -= passive_;
  }
  tau0_ = -options_.nullspace_damping * dynamics_.qd();
  const auto& q_ref = reference.joint.q;
  if (options_.nullspace_stiffness > 0.0 && q_ref.size() == n) {
    tau0_ += options_.nullspace_stiffness * (q_ref - dynamics_.q());
  }
  task_space_.project_torque(tau0_, null_);
  tau += null_;
  if (limits_.enabled()) {
    limits_.update(dynamics_.q(), dynamics_.qd());
    limits_.add_to(&task_space_, tau);
  }

  values_[0] = e.head<3>().norm();
  values_[1] = m == 6 ? e.tail<3>().norm() : 0.0;
  values_[2] = 0.0;  // lambda_condition: see internal_values()
  values_[3] = status == TaskSpaceStatus::ok ? 0.0 : 1.0;
  for (int i = 0; i < 6; ++i) values_[4 + i] = integral_[i];
}

std::span<const double> OperationalSpaceController::internal_values() const noexcept {
  values_[2] = task_space_.condition();
  return values_;
}

}  // namespace mjarm
