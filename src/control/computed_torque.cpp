#include "mjarm/control/computed_torque.hpp"

#include <cmath>

namespace mjarm {

ComputedTorqueController::ComputedTorqueController(const Chain& chain,
                                                   const ComputedTorqueOptions& options)
    : gains_(options.gains.expanded(chain.size(), "ct")),
      compensate_passive_(options.compensate_passive),
      dynamics_(chain),
      qdd_(Eigen::VectorXd::Zero(chain.size())) {}

void ComputedTorqueController::compute(const mjData& data, const Reference& reference,
                                       JointCommand& command) noexcept {
  const Chain& chain = dynamics_.chain();
  const int n = chain.size();
  if (command.value.size() != n) return;
  command.kind = CommandKind::torque;
  const JointReference& ref = reference.joint;
  const bool has_q = ref.q.size() == n;
  const bool has_qd = ref.qd.size() == n;
  const bool has_qdd = ref.qdd.size() == n;
  // commanded acceleration: feed-forward plus PD on the tracking error
  double e2 = 0.0, edot2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double e = has_q ? ref.q[i] - data.qpos[chain.qpos_address(i)] : 0.0;
    const double edot = (has_qd ? ref.qd[i] : 0.0) - data.qvel[chain.dof_address(i)];
    qdd_[i] = (has_qdd ? ref.qdd[i] : 0.0) + gains_.kp[i] * e + gains_.kd[i] * edot;
    e2 += e * e;
    edot2 += edot * edot;
  }
  // τ = M·q̈ + h, then cancel the passive forces MuJoCo adds on its own
  dynamics_.inverse_dynamics(data, qdd_, command.value);
  if (compensate_passive_) {
    for (int i = 0; i < n; ++i) command.value[i] -= data.qfrc_passive[chain.dof_address(i)];
  }
  values_ = {std::sqrt(e2), std::sqrt(edot2), has_q ? 1.0 : 0.0};
}

}  // namespace mjarm
