#include "mjarm/ik/posture.hpp"

#include <algorithm>

namespace mjarm {

Eigen::VectorXd resolve_posture(const Chain& chain, const Posture& posture) {
  check_fields(posture);
  if (posture.q_pref.size() == 0) return chain.center();
  chain.check(posture.q_pref, "posture q_pref");
  return posture.q_pref;
}

void add_posture_pull(const Eigen::Ref<const Eigen::VectorXd>& q_pref, double gain,
                      const Eigen::Ref<const Eigen::VectorXd>& q,
                      Eigen::Ref<Eigen::VectorXd> step) noexcept {
  if (gain == 0.0) return;
  step += gain * (q_pref - q);
}

double secondary_scale(double task_norm, double secondary_norm, double ratio) noexcept {
  if (!(secondary_norm > 0.0)) return 1.0;
  return std::min(1.0, ratio * task_norm / secondary_norm);
}

}  // namespace mjarm
