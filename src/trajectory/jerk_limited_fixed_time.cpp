#include "mjarm/trajectory/jerk_limited_fixed_time.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/jerk_limited_min_time.hpp"
#include "mjarm/trajectory/jerk_limited_reach.hpp"

namespace mjarm {

namespace {

/// Appends λ·@p hi + (1 − λ)·@p lo, both of duration @p duration, phase by phase over the union
/// of their switching times.
bool append_blend(const JerkPhases& hi, const JerkPhases& lo, double lambda, double duration,
                  JerkProfile& profile) noexcept {
  // switching times of each, the last one pinned to the duration (their sums differ by
  // round-off only)
  double end_hi[JerkPhases::kSize], end_lo[JerkPhases::kSize];
  double t_hi = 0.0, t_lo = 0.0;
  for (int i = 0; i < JerkPhases::kSize; ++i) {
    t_hi += hi.duration[i];
    t_lo += lo.duration[i];
    end_hi[i] = std::min(t_hi, duration);
    end_lo[i] = std::min(t_lo, duration);
  }
  end_hi[JerkPhases::kSize - 1] = end_lo[JerkPhases::kSize - 1] = duration;
  int i = 0, k = 0;
  double now = 0.0;
  while (now < duration) {
    while (i < JerkPhases::kSize - 1 && end_hi[i] <= now) ++i;
    while (k < JerkPhases::kSize - 1 && end_lo[k] <= now) ++k;
    const double next = std::min(end_hi[i], end_lo[k]);
    if (!(next > now)) break;
    // both cruising: the plateau at zero acceleration (see JerkPhases)
    const bool ok =
        i == JerkPhases::kCruise && k == JerkPhases::kCruise && hi.jerk[i] == 0.0 &&
                lo.jerk[k] == 0.0
            ? profile.append_cruise(next - now)
            : profile.append(lambda * hi.jerk[i] + (1.0 - lambda) * lo.jerk[k], next - now);
    if (!ok) return false;
    now = next;
  }
  return true;
}

}  // namespace

bool append_blended_profile(const JerkReach& reach, const KinematicState& target, double duration,
                            JerkProfile& profile) noexcept {
  if (!reach_contains(reach, target.p)) return false;
  const double span = reach.p_max - reach.p_min;
  const double lambda = span > 0.0 ? std::clamp((target.p - reach.p_min) / span, 0.0, 1.0) : 1.0;
  if (duration > 0.0 && !append_blend(reach.highest, reach.lowest, lambda, duration, profile))
    return false;
  // the limits hold by construction (a blend of two motions within them); the end is checked
  const KinematicState e = profile.end();
  const auto near = [](double x, double y) {
    return std::abs(x - y) <= JerkTolerance::kTarget * std::max(1.0, std::abs(y));
  };
  return near(e.p, target.p) && near(e.v, target.v) && near(e.a, target.a);
}

bool append_fixed_time_profile(const KinematicState& start, const KinematicState& target,
                               const JerkLimits& limits, double duration,
                               JerkProfile& profile) noexcept {
  JerkReach reach;
  return reach_range(start, target.v, target.a, limits, duration, reach) &&
         append_blended_profile(reach, target, duration, profile);
}

bool fixed_time_profile(const KinematicState& start, const KinematicState& target,
                        const JerkLimits& limits, double duration, JerkProfile& profile) noexcept {
  profile.reset(start);
  return append_fixed_time_profile(start, target, limits, duration, profile);
}

}  // namespace mjarm
