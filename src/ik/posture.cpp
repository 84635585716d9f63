#include "mjarm/ik/posture.hpp"

#include <algorithm>

#include "option_check.hpp"

namespace mjarm {

Eigen::VectorXd resolve_posture(const Chain& chain, const Posture& posture) {
  detail::check_fields(detail::OptionCheck("posture "), posture);
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

namespace detail {

void check_fields(const OptionCheck& require, const Posture& posture) {
  require.require(posture.gain >= 0.0 && posture.gain <= 1.0, "gain", posture.gain, "in [0, 1]");
}

}  // namespace detail

double secondary_scale(double task_norm, double secondary_norm, double ratio) noexcept {
  if (!(secondary_norm > 0.0)) return 1.0;
  return std::min(1.0, ratio * task_norm / secondary_norm);
}

}  // namespace mjarm
