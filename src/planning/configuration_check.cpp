#include "mjarm/planning/configuration_check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mjarm/error.hpp"

namespace mjarm {

void check(const CheckOptions& options) { check_fields(options); }

ConfigurationChecker::ConfigurationChecker(const Chain& chain, const JointLimits& limits,
                                           const CheckOptions& options)
    : chain_(chain),
      limits_(limits),
      options_(options),
      manipulability_(chain),
      dynamics_(chain),
      contacts_(chain) {
  mjarm::check(limits, chain.size());
  mjarm::check(options);
  install_mujoco_handlers();
  data_ = chain.robot().make_data();
  const mjModel& m = chain.robot().model();
  fixed_qpos_ = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
  zero_ = Eigen::VectorXd::Zero(chain.size());
  tau_ = Eigen::VectorXd::Zero(chain.size());
  q_ = Eigen::VectorXd::Zero(chain.size());
}

void ConfigurationChecker::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  chain_.check_qpos(qpos, "fixed qpos");
  fixed_qpos_ = qpos;
}

const ConfigurationCheck& ConfigurationChecker::check(
    const Eigen::Ref<const Eigen::VectorXd>& q) noexcept {
  return check(q, zero_, zero_);
}

const ConfigurationCheck& ConfigurationChecker::check(
    const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
    const Eigen::Ref<const Eigen::VectorXd>& qdd) noexcept {
  ConfigurationCheck& r = result_;
  r = ConfigurationCheck{};
  if (!q.allFinite() || !qd.allFinite() || !qdd.allFinite()) {
    r.failure = CheckFailure::invalid;
    return r;
  }
  const int n = chain_.size();
  // joint limits
  for (int i = 0; i < n && r.limit_joint < 0; ++i) {
    if (q[i] < chain_.lower()[i] - options_.limit_tolerance ||
        q[i] > chain_.upper()[i] + options_.limit_tolerance)
      r.limit_joint = i;
  }
  // singular values of the 6×n Jacobian (q is finite: evaluate does not throw)
  q_ = q;
  manipulability_.evaluate(q_);
  r.sigma_min = manipulability_.result().sigma_min;

  // the state on the scratch data: positions (kinematics, inertia, contacts), then velocities
  const mjModel& m = chain_.robot().model();
  mjData& d = *data_;
  std::copy(fixed_qpos_.data(), fixed_qpos_.data() + m.nq, d.qpos);
  chain_.scatter(q, d.qpos);
  std::fill(d.qvel, d.qvel + m.nv, 0.0);
  for (int i = 0; i < n; ++i) d.qvel[chain_.dof_address(i)] = qd[i];
  mj_fwdPosition(&m, &d);
  const RobotContact contact = contacts_.deepest(d, options_.collision_margin);
  r.geom1 = contact.geom1;
  r.geom2 = contact.geom2;
  r.distance = contact.distance;
  mj_fwdVelocity(&m, &d);
  dynamics_.inverse_dynamics(d, qdd, tau_);
  for (int i = 0; i < n; ++i) {
    const double ratio = std::abs(tau_[i]) / limits_.max_torque[i];  // 0 for an infinite limit
    if (ratio > r.torque_ratio || r.torque_joint < 0) {
      r.torque_ratio = std::isnan(ratio) ? 0.0 : ratio;
      r.torque_joint = i;
    }
  }

  if (!tau_.allFinite())
    r.failure = CheckFailure::invalid;
  else if (r.limit_joint >= 0)
    r.failure = CheckFailure::joint_limits;
  else if (r.geom1 >= 0)
    r.failure = CheckFailure::collision;
  else if (!(r.sigma_min >= options_.min_singular_value))
    r.failure = CheckFailure::singular;
  else if (r.torque_ratio > 1.0)
    r.failure = CheckFailure::torque;
  return r;
}

std::string ConfigurationChecker::describe(const ConfigurationCheck& r) const {
  std::ostringstream out;
  switch (r.failure) {
    case CheckFailure::none:
      return "ok";
    case CheckFailure::invalid:
      return "the state holds NaN or infinity";
    case CheckFailure::joint_limits: {
      const int i = r.limit_joint;
      out << "joint '" << chain_.joint_names()[i] << "' outside its range [" << chain_.lower()[i]
          << ", " << chain_.upper()[i] << "]";
      return out.str();
    }
    case CheckFailure::collision:
      out << contacts_.geom_name(r.geom1) << " of the robot touches "
          << contacts_.geom_name(r.geom2) << " (distance " << r.distance << " m)";
      return out.str();
    case CheckFailure::singular:
      out << "near a singularity: smallest singular value of the 6x" << chain_.size()
          << " Jacobian " << r.sigma_min << " < " << options_.min_singular_value;
      return out.str();
    case CheckFailure::torque: {
      const int i = r.torque_joint;
      out << "joint '" << chain_.joint_names()[i] << "' needs " << r.torque_ratio * 100.0
          << " % of its torque limit " << limits_.max_torque[i] << " N·m";
      return out.str();
    }
  }
  return "unknown";
}

}  // namespace mjarm
