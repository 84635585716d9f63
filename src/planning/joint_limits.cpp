#include "mjarm/planning/joint_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

/// The torque bound of the actuator driving chain joint @p i (+inf when none is known).
double actuator_torque_bound(const Chain& chain, int i) {
  const std::optional<int> actuator = chain.actuator(i);
  if (!actuator) return std::numeric_limits<double>::infinity();
  const mjModel& m = chain.robot().model();
  const int a = *actuator;
  const double gear = std::abs(m.actuator_gear[6 * a]);
  if (m.actuator_forcelimited[a])
    return gear * std::min(std::abs(m.actuator_forcerange[2 * a]),
                           std::abs(m.actuator_forcerange[2 * a + 1]));
  // a motor's ctrl is its force (gain 1, no bias)
  const bool motor = m.actuator_gaintype[a] == mjGAIN_FIXED && m.actuator_gainprm[10 * a] == 1.0 &&
                     m.actuator_biastype[a] == mjBIAS_NONE;
  if (m.actuator_ctrllimited[a] && motor)
    return gear * std::min(std::abs(m.actuator_ctrlrange[2 * a]),
                           std::abs(m.actuator_ctrlrange[2 * a + 1]));
  return std::numeric_limits<double>::infinity();
}

void check_vector(const Eigen::VectorXd& v, int n, const char* what, bool finite) {
  if (v.size() != n)
    throw Error(std::string("joint limits: ") + what + " has " + std::to_string(v.size()) +
                " entries, expected " + std::to_string(n) + " (one per chain joint)");
  for (int i = 0; i < n; ++i) {
    if (!(v[i] > 0.0) || (finite && !std::isfinite(v[i])))
      throw Error(std::string("joint limits: ") + what + " of joint " + std::to_string(i) +
                  " must be " + (finite ? "positive and finite" : "positive") + ", got " +
                  number_text(v[i]));
  }
}

}  // namespace

JointLimits joint_limits_from_model(const Chain& chain, const Eigen::VectorXd& q,
                                    const ModelLimitOptions& options) {
  chain.check(q, "limit configuration q");
  check_fields(options);
  const int n = chain.size();
  const Robot& robot = chain.robot();
  const mjModel& m = robot.model();
  // the mass matrix at q, on a scratch mjData
  DataPtr data = robot.make_data();
  chain.scatter(q, data->qpos);
  mj_forward(&m, data.get());
  ChainDynamics dynamics(chain);
  dynamics.update(*data);

  JointLimits limits;
  limits.max_velocity = Eigen::VectorXd::Constant(n, options.velocity);
  limits.max_acceleration.resize(n);
  limits.max_torque.resize(n);
  for (int i = 0; i < n; ++i) {
    const double tau = actuator_torque_bound(chain, i);
    limits.max_torque[i] = tau > 0.0 ? tau : std::numeric_limits<double>::infinity();
    const double inertia = dynamics.mass_matrix()(i, i);
    limits.max_acceleration[i] = std::isfinite(limits.max_torque[i]) && inertia > 0.0
                                     ? options.torque_fraction * limits.max_torque[i] / inertia
                                     : options.acceleration;
  }
  return limits;
}

void check(const JointLimits& limits, int n) {
  check_vector(limits.max_velocity, n, "max_velocity", true);
  check_vector(limits.max_acceleration, n, "max_acceleration", true);
  check_vector(limits.max_torque, n, "max_torque", false);
}

std::string describe(const JointLimits& limits) {
  std::ostringstream out;
  const auto list = [&out](const char* what, const Eigen::VectorXd& v) {
    out << what << ":";
    for (Eigen::Index i = 0; i < v.size(); ++i) out << (i ? ", " : " ") << v[i];
    out << '\n';
  };
  list("max velocity [rad/s]", limits.max_velocity);
  list("max acceleration [rad/s²]", limits.max_acceleration);
  list("max torque [N·m]", limits.max_torque);
  return out.str();
}

}  // namespace mjarm
