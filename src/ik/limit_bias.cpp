#include "mjarm/ik/limit_bias.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

void check(const LimitBias& bias) { check_fields(bias); }

void add_limit_bias(const Chain& chain, const LimitBias& bias,
                    const Eigen::Ref<const Eigen::VectorXd>& q,
                    Eigen::Ref<Eigen::VectorXd> step) noexcept {
  const Eigen::VectorXd& lo = chain.lower();
  const Eigen::VectorXd& hi = chain.upper();
  for (int i = 0; i < chain.size(); ++i) {
    if (!std::isfinite(lo[i]) || !std::isfinite(hi[i])) continue;
    step[i] += bias.centre_gain * (0.5 * (lo[i] + hi[i]) - q[i]);
    const double zone = bias.repulsion_zone * (hi[i] - lo[i]);
    if (zone <= 0.0 || bias.repulsion_gain == 0.0) continue;
    // depth into the zone, 0 at its inner edge and 1 at the bound (clipped beyond)
    const double low_depth = std::min(1.0, (lo[i] + zone - q[i]) / zone);
    const double high_depth = std::min(1.0, (q[i] - (hi[i] - zone)) / zone);
    if (low_depth > 0.0) step[i] += bias.repulsion_gain * zone * low_depth * low_depth;
    if (high_depth > 0.0) step[i] -= bias.repulsion_gain * zone * high_depth * high_depth;
  }
}

int saturate_step(const Chain& chain, const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& dq, Eigen::Ref<Eigen::VectorXd> locked,
                  Eigen::Ref<Eigen::VectorXd> dq_locked) noexcept {
  int count = 0;
  for (int i = 0; i < chain.size(); ++i) {
    if (locked[i] != 0.0) continue;
    const double target = q[i] + dq[i];
    if (target > chain.upper()[i]) {
      dq_locked[i] = std::max(0.0, chain.upper()[i] - q[i]);
    } else if (target < chain.lower()[i]) {
      dq_locked[i] = std::min(0.0, chain.lower()[i] - q[i]);
    } else {
      continue;
    }
    locked[i] = 1.0;
    ++count;
  }
  return count;
}

void clamp_to_limits(const Chain& chain, Eigen::Ref<Eigen::VectorXd> q) noexcept {
  q = q.cwiseMax(chain.lower()).cwiseMin(chain.upper());
}

}  // namespace mjarm
