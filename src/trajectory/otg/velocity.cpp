#include "mjarm/trajectory/otg/velocity.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

namespace {

constexpr double kVelocityTolerance = 1e-9;

bool velocity_reached(const JerkProfile& p, double v, double a, const JerkLimits& limits,
                      int first_phase) noexcept {
  const KinematicState e = p.end();
  const JerkExtrema x = p.extrema(first_phase);
  const double amax = limits.acceleration * (1.0 + 1e-12);
  return std::abs(e.v - v) <= kVelocityTolerance * std::max(1.0, std::abs(v)) &&
         std::abs(e.a - a) <= kVelocityTolerance * std::max(1.0, std::abs(a)) && x.a_min >= -amax &&
         x.a_max <= amax;
}

/// The rising form (sign +1) or the falling one (−1) with level u and hold h, in @p phases;
/// false when a duration is negative.
bool level_phases(double sign, double u, double h, double a0, double af, double J,
                  JerkPhases& phases) noexcept {
  const double t1 = (u - a0) / J, t3 = (u - af) / J;
  if (!(t1 >= -1e-12 && t3 >= -1e-12 && h >= -1e-12)) return false;
  phases = JerkPhases{};
  phases.jerk[0] = sign * J;
  phases.duration[0] = std::max(t1, 0.0);
  phases.duration[1] = std::max(h, 0.0);
  phases.jerk[2] = -sign * J;
  phases.duration[2] = std::max(t3, 0.0);
  return true;
}

}  // namespace

bool min_time_velocity_profile(const KinematicState& start, double v_target, double a_target,
                               const JerkLimits& limits, JerkBlock& block) noexcept {
  const double A = limits.acceleration, J = limits.jerk;
  block.start = start;
  block.duration_count = 0;
  block.blocked_count = 0;
  const double amax = A * (1.0 + 1e-12);
  for (const double sign : {1.0, -1.0}) {
    const double a0 = sign * start.a, af = sign * a_target, dv = sign * (v_target - start.v);
    const double u2 = J * dv + 0.5 * (a0 * a0 + af * af);
    if (u2 < 0.0) continue;
    for (const double root : {std::sqrt(u2), -std::sqrt(u2)}) {
      double u = root, h = 0.0;
      if (u > A) {
        u = A;
        h = (dv - (2.0 * A * A - a0 * a0 - af * af) / (2.0 * J)) / A;
      }
      if (u < -amax) continue;
      JerkPhases phases;
      if (!level_phases(sign, u, h, a0, af, J, phases)) continue;
      const KinematicState e = phases.end(start);
      if (std::abs(e.v - v_target) > kVelocityTolerance * std::max(1.0, std::abs(v_target)) ||
          std::abs(e.a - a_target) > kVelocityTolerance * std::max(1.0, std::abs(a_target)))
        continue;
      block.record(phases.total(), phases);
    }
  }
  if (block.duration_count == 0) return false;
  block.t_min = block.durations[0];
  block.set_blocked_from_durations();
  return true;
}

bool fixed_time_velocity_profile(const KinematicState& start, double v_target, double a_target,
                                 const JerkLimits& limits, double duration,
                                 JerkProfile& profile) noexcept {
  profile.reset(start);
  return append_fixed_time_velocity_profile(start, v_target, a_target, limits, duration, profile);
}

bool append_fixed_time_velocity_profile(const KinematicState& start, double v_target,
                                        double a_target, const JerkLimits& limits, double duration,
                                        JerkProfile& profile) noexcept {
  const double J = limits.jerk, T = duration;
  if (!(T >= 0.0) || !std::isfinite(T)) return false;
  const int first = profile.size();
  JerkPhases phases;
  // tries one candidate: appended, kept when it reaches the target within the limits
  const auto keep = [&](const JerkPhases& p) {
    profile.truncate(first);
    p.append_to(profile);
    return std::abs(profile.duration() - profile.duration_until(first) - T) <=
               1e-9 * std::max(1.0, T) &&
           velocity_reached(profile, v_target, a_target, limits, first);
  };
  for (const double sign : {1.0, -1.0}) {
    const double a0 = sign * start.a, af = sign * a_target, dv = sign * (v_target - start.v);
    // level form: u² − u·(J·T + a0 + af) + (a0² + af² + 2J·Δv)/2 = 0, h = T − (2u − a0 − af)/J
    const double b = J * T + a0 + af;
    const double disc = b * b - 2.0 * (a0 * a0 + af * af + 2.0 * J * dv);
    if (disc >= -1e-12 * b * b) {
      // the root of larger magnitude from the sum, the other from the product c: b ± r would
      // cancel (J·T far above the levels: a long duration), and that root's round-off, times the
      // hold, would miss the target velocity
      const double r = std::sqrt(std::max(disc, 0.0));
      const double c = 0.5 * (a0 * a0 + af * af + 2.0 * J * dv);
      const double q = 0.5 * (b + std::copysign(r, b));
      const double other = q != 0.0 ? c / q : 0.0;
      for (const double u : {std::min(q, other), std::max(q, other)})
        if (level_phases(sign, u, T - (2.0 * u - a0 - af) / J, a0, af, J, phases) && keep(phases))
          return true;
    }
    // monotone ramp a0 → af (falling when a0 > af) with a hold at a level m between them:
    // Δv = (a0² − af²)/(2J)·s + m·h with s = sign of the ramp
    if (a0 >= af) {
      const double h = T - (a0 - af) / J;
      if (h > 0.0) {
        const double m = (dv - (a0 * a0 - af * af) / (2.0 * J)) / h;
        if (m <= a0 && m >= af) {
          phases = JerkPhases{};
          phases.jerk[0] = phases.jerk[2] = -sign * J;
          phases.duration[0] = (a0 - m) / J;
          phases.duration[1] = h;
          phases.duration[2] = (m - af) / J;
          if (keep(phases)) return true;
        }
      }
    }
  }
  profile.truncate(first);
  return false;
}

}  // namespace mjarm
