#include "mjarm/trajectory/jerk_limited_velocity.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

namespace {

constexpr double kVelocityTolerance = 1e-9;

bool velocity_reached(const JerkProfile& p, double v, double a, const JerkLimits& limits) noexcept {
  const KinematicState e = p.end();
  const JerkExtrema x = p.extrema();
  const double amax = limits.acceleration * (1.0 + 1e-12);
  return std::abs(e.v - v) <= kVelocityTolerance * std::max(1.0, std::abs(v)) &&
         std::abs(e.a - a) <= kVelocityTolerance * std::max(1.0, std::abs(a)) && x.a_min >= -amax &&
         x.a_max <= amax;
}

/// Writes the rising form (sign +1) or the falling one (−1) with level u and plateau h.
bool offer_level(const KinematicState& start, double sign, double u, double h, double a0, double af,
                 double J, JerkProfile& profile) noexcept {
  const double t1 = (u - a0) / J, t3 = (u - af) / J;
  if (!(t1 >= -1e-12 && t3 >= -1e-12 && h >= -1e-12)) return false;
  profile.reset(start);
  if (t1 > 0.0) profile.append(sign * J, t1);
  if (h > 0.0) profile.append(0.0, h);
  if (t3 > 0.0) profile.append(-sign * J, t3);
  return true;
}

/// Adds @p p to the distinct extremal durations of @p block, ascending.
void record_extremal(const JerkProfile& p, JerkBlock& block) noexcept {
  const double d = p.duration();
  for (int i = 0; i < block.duration_count; ++i)
    if (std::abs(block.durations[i] - d) <= 1e-9 * std::max(1.0, d)) return;
  if (block.duration_count == JerkBlock::kMaxDurations) return;
  int i = block.duration_count++;
  while (i > 0 && block.durations[i - 1] > d) {
    block.durations[i] = block.durations[i - 1];
    block.profiles[i] = block.profiles[i - 1];
    --i;
  }
  block.durations[i] = d;
  block.profiles[i] = p;
}

}  // namespace

bool min_time_velocity_profile(const KinematicState& start, double v_target, double a_target,
                               const JerkLimits& limits, JerkBlock& block) noexcept {
  const double A = limits.acceleration, J = limits.jerk;
  block.duration_count = 0;
  block.blocked_count = 0;
  JerkProfile candidate;
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
      if (!offer_level(start, sign, u, h, a0, af, J, candidate)) continue;
      if (!velocity_reached(candidate, v_target, a_target, limits)) continue;
      record_extremal(candidate, block);
    }
  }
  if (block.duration_count == 0) return false;
  block.t_min = block.durations[0];
  block.fastest = block.profiles[0];
  block.set_blocked_from_durations();
  return true;
}

bool fixed_time_velocity_profile(const KinematicState& start, double v_target, double a_target,
                                 const JerkLimits& limits, double duration,
                                 JerkProfile& profile) noexcept {
  const double J = limits.jerk, T = duration;
  if (!(T >= 0.0) || !std::isfinite(T)) return false;
  for (const double sign : {1.0, -1.0}) {
    const double a0 = sign * start.a, af = sign * a_target, dv = sign * (v_target - start.v);
    // level form: u² − u·(J·T + a0 + af) + (a0² + af² + 2J·Δv)/2 = 0, h = T − (2u − a0 − af)/J
    const double b = J * T + a0 + af;
    const double disc = b * b - 2.0 * (a0 * a0 + af * af + 2.0 * J * dv);
    if (disc >= -1e-12 * b * b) {
      const double r = std::sqrt(std::max(disc, 0.0));
      for (const double u : {0.5 * (b - r), 0.5 * (b + r)}) {
        if (!offer_level(start, sign, u, T - (2.0 * u - a0 - af) / J, a0, af, J, profile)) continue;
        if (std::abs(profile.duration() - T) <= 1e-9 * std::max(1.0, T) &&
            velocity_reached(profile, v_target, a_target, limits))
          return true;
      }
    }
    // monotone ramp a0 → af (falling when a0 > af) with a hold at a level m between them:
    // Δv = (a0² − af²)/(2J)·s + m·h with s = sign of the ramp
    if (a0 >= af) {
      const double h = T - (a0 - af) / J;
      if (h > 0.0) {
        const double m = (dv - (a0 * a0 - af * af) / (2.0 * J)) / h;
        if (m <= a0 && m >= af) {
          profile.reset(start);
          if (a0 > m) profile.append(-sign * J, (a0 - m) / J);
          profile.append(0.0, h);
          if (m > af) profile.append(-sign * J, (m - af) / J);
          if (velocity_reached(profile, v_target, a_target, limits)) return true;
        }
      }
    }
  }
  return false;
}

}  // namespace mjarm
