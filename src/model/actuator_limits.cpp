#include "mjarm/model/actuator_limits.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mjarm {

TorqueRange joint_torque_range(const Chain& chain, int i) {
  TorqueRange range;
  const std::optional<int> actuator = chain.actuator(i);
  if (!actuator) return range;
  const mjModel& m = chain.robot().model();
  const int a = *actuator;
  const double gear = m.actuator_gear[6 * a];
  // the interval gear·[lo, hi], ordered
  auto scaled = [gear](double lo, double hi) {
    const double x = gear * lo, y = gear * hi;
    return TorqueRange{std::min(x, y), std::max(x, y)};
  };
  auto intersect = [&range](const TorqueRange& r) {
    range.lower = std::max(range.lower, r.lower);
    range.upper = std::min(range.upper, r.upper);
  };
  // a motor's force is gain·ctrl
  const bool motor =
      m.actuator_gaintype[a] == mjGAIN_FIXED && m.actuator_biastype[a] == mjBIAS_NONE;
  if (motor && m.actuator_ctrllimited[a]) {
    const double gain = m.actuator_gainprm[mjNGAIN * a];
    const double lo = gain * m.actuator_ctrlrange[2 * a],
                 hi = gain * m.actuator_ctrlrange[2 * a + 1];
    intersect(scaled(std::min(lo, hi), std::max(lo, hi)));
  }
  if (m.actuator_forcelimited[a]) {
    intersect(scaled(m.actuator_forcerange[2 * a], m.actuator_forcerange[2 * a + 1]));
  }
  return range;
}

double joint_torque_limit(const Chain& chain, int i) {
  const mjModel& m = chain.robot().model();
  const std::optional<int> a = chain.actuator(i);
  double limit = std::numeric_limits<double>::infinity();
  if (!a) return limit;
  const double gear = std::abs(m.actuator_gear[6 * *a]);
  if (m.actuator_ctrllimited[*a]) {
    const double c = std::max(std::abs(m.actuator_ctrlrange[2 * *a]),
                              std::abs(m.actuator_ctrlrange[2 * *a + 1]));
    // a motor's force is gain·ctrl (gain = gainprm[0])
    limit = std::min(limit, c * std::abs(m.actuator_gainprm[mjNGAIN * *a]) * gear);
  }
  if (m.actuator_forcelimited[*a]) {
    const double f = std::max(std::abs(m.actuator_forcerange[2 * *a]),
                              std::abs(m.actuator_forcerange[2 * *a + 1]));
    limit = std::min(limit, f * gear);
  }
  return limit;
}

}  // namespace mjarm
