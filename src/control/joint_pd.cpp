#include "mjarm/control/joint_pd.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

void require_one_or_n(const Eigen::VectorXd& v, int n, std::string_view owner, const char* what) {
  if (v.size() != 1 && v.size() != n) {
    throw Error(std::string(owner) + ": " + what + " needs 1 or " + std::to_string(n) +
                " entries (one per chain joint), got " + std::to_string(v.size()));
  }
}

Eigen::VectorXd expand(const Eigen::VectorXd& v, int n) {
  return v.size() == n ? v : Eigen::VectorXd::Constant(n, v[0]);
}

}  // namespace

JointPdGains JointPdGains::uniform(double kp, double kd) {
  return JointPdGains{Eigen::VectorXd::Constant(1, kp), Eigen::VectorXd::Constant(1, kd)};
}

JointPdGains JointPdGains::critically_damped(double omega) { return uniform(omega * omega, 2.0 * omega); }

JointPdGains JointPdGains::expanded(int n, std::string_view owner) const {
  require_one_or_n(kp, n, owner, "kp");
  require_one_or_n(kd, n, owner, "kd");
  check_fields(*this, owner);
  return JointPdGains{expand(kp, n), expand(kd, n)};
}

JointPdController::JointPdController(const Chain& chain, const JointPdOptions& options)
    : gains_(options.gains.expanded(chain.size(), "joint-pd")),
      gravity_(options.gravity_compensation),
      dynamics_(chain) {}

void JointPdController::compute(const mjData& data, const Reference& reference,
                                JointCommand& command) noexcept {
  const Chain& chain = dynamics_.chain();
  const int n = chain.size();
  if (command.value.size() != n) return;
  command.kind = CommandKind::torque;
  const bool has_q = reference.joint.q.size() == n;
  const bool has_qd = reference.joint.qd.size() == n;
  if (gravity_) dynamics_.update(data);
  double e2 = 0.0, edot2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double e = has_q ? reference.joint.q[i] - data.qpos[chain.qpos_address(i)] : 0.0;
    const double edot = (has_qd ? reference.joint.qd[i] : 0.0) - data.qvel[chain.dof_address(i)];
    command.value[i] = gains_.kp[i] * e + gains_.kd[i] * edot + (gravity_ ? dynamics_.gravity()[i] : 0.0);
    e2 += e * e;
    edot2 += edot * edot;
  }
  values_ = {std::sqrt(e2), std::sqrt(edot2), has_q ? 1.0 : 0.0};
}

}  // namespace mjarm
