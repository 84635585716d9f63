#include "mjarm/trajectory/jerk_limited_fixed_time.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/jerk_limited_min_time.hpp"
#include "mjarm/trajectory/jerk_limited_reach.hpp"

namespace mjarm {

namespace {

/// The phases of nonzero duration of @p p: their end times (the last pinned to @p duration; the
/// sums differ from it by round-off only), jerks and whether each is the cruise slot.
struct Switches {
  double end[JerkPhases::kSize];
  double jerk[JerkPhases::kSize];
  bool cruise[JerkPhases::kSize];
  int size = 0;

  Switches(const JerkPhases& p, double duration) noexcept {
    double t = 0.0;
    for (int i = 0; i < JerkPhases::kSize; ++i) {
      if (!(p.duration[i] > 0.0)) continue;
      t += p.duration[i];
      end[size] = std::min(t, duration);
      jerk[size] = p.jerk[i];
      cruise[size] = i == JerkPhases::kCruise && p.jerk[i] == 0.0;
      ++size;
    }
    if (size == 0) {  // a profile of no duration: rest at the target's acceleration
      end[0] = duration;
      jerk[0] = 0.0;
      cruise[0] = false;
      size = 1;
    }
    end[size - 1] = duration;
  }
};

/// Appends λ·@p hi + (1 − λ)·@p lo, both of duration @p duration, phase by phase over the union
/// of their switching times.
bool append_blend(const JerkPhases& hi, const JerkPhases& lo, double lambda, double duration,
                  JerkProfile& profile) noexcept {
  const Switches h(hi, duration), l(lo, duration);
  int i = 0, k = 0;
  double now = 0.0;
  while (i < h.size && k < l.size) {
    const double next = std::min(h.end[i], l.end[k]);
    if (next > now) {
      // both cruising: the plateau at zero acceleration (see JerkPhases)
      const bool ok =
          h.cruise[i] && l.cruise[k]
              ? profile.append_cruise(next - now)
              : profile.append(lambda * h.jerk[i] + (1.0 - lambda) * l.jerk[k], next - now);
      if (!ok) return false;
      now = next;
    }
    if (h.end[i] <= now) ++i;
    if (l.end[k] <= now) ++k;
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
