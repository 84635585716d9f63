#include "mjarm/trajectory/jerk_limited_brake.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

namespace {

constexpr double kBrakeSlack = 1e-12;

/// The velocity once the acceleration is ramped to zero at full jerk.
double settled_velocity(const KinematicState& s, double jerk) noexcept {
  return s.v + s.a * std::abs(s.a) / (2.0 * jerk);
}

}  // namespace

bool is_startable(const KinematicState& s, const JerkLimits& limits) noexcept {
  const double v = limits.velocity * (1.0 + kBrakeSlack);
  const double a = limits.acceleration * (1.0 + kBrakeSlack);
  return std::abs(s.a) <= a && std::abs(s.v) <= v &&
         std::abs(settled_velocity(s, limits.jerk)) <= v;
}

bool is_reachable(const KinematicState& s, const JerkLimits& limits) noexcept {
  const double v = limits.velocity * (1.0 + kBrakeSlack);
  const double a = limits.acceleration * (1.0 + kBrakeSlack);
  return std::abs(s.a) <= a && std::abs(s.v) <= v &&
         std::abs(s.v - s.a * std::abs(s.a) / (2.0 * limits.jerk)) <= v;
}

namespace {

/// One brake pass from @p start (see append_brake).
void brake_pass(const KinematicState& start, const JerkLimits& limits,
                JerkProfile& profile) noexcept {
  const double V = limits.velocity, A = limits.acceleration, J = limits.jerk;
  // the braking direction: a velocity violation decides it, else the acceleration's; the
  // problem is then seen in "up" coordinates (all values times sign) with the violation on the
  // positive side
  const double f = settled_velocity(start, J);
  double sign = 1.0;
  if (start.v > V || f > V) {
    sign = 1.0;
  } else if (start.v < -V || f < -V) {
    sign = -1.0;
  } else {
    sign = start.a > A ? 1.0 : -1.0;
  }
  const double v0 = sign * start.v, a0 = sign * start.a;
  if (v0 > V || sign * f > V) {
    if (a0 < -A) {
      // more deceleration than allowed: ramp it up to −A, then hold until the velocity is V
      profile.append(sign * J, (-A - a0) / J);
      const double v1 = sign * profile.end().v;
      if (v1 > V) profile.append(0.0, (v1 - V) / A);
    } else {
      // ramp the acceleration down at full jerk until v = V: v = f_peak − J·τ²/2 with τ the time
      // since the (possibly past) instant where a = 0 on this ramp, f_peak = v0 + a0²/(2J);
      // hold at −A when that needs more deceleration than the limit
      const double f_peak = v0 + a0 * a0 / (2.0 * J);
      const double tau = std::sqrt(2.0 * std::max(f_peak - V, 0.0) / J);
      if (J * tau <= A) {
        profile.append(-sign * J, std::max(a0 / J + tau, 0.0));
      } else {
        profile.append(-sign * J, (a0 + A) / J);
        const double v1 = sign * profile.end().v;
        profile.append(0.0, std::max((v1 - V) / A, 0.0));
      }
    }
  } else if (a0 > A) {
    profile.append(-sign * J, (a0 - A) / J);  // only the acceleration is too large
  }
}

}  // namespace

bool append_brake(const KinematicState& start, const JerkLimits& limits,
                  JerkProfile& profile) noexcept {
  // a second pass handles a first one that overshoots to the other side (a deceleration far
  // beyond its limit turns a too-high velocity into a too-low one while it is ramped back)
  if (profile.size() == 0) profile.reset(start);
  for (int pass = 0; pass < 2 && !is_startable(profile.end(), limits); ++pass)
    brake_pass(profile.end(), limits, profile);
  return is_startable(profile.end(), limits);
}

}  // namespace mjarm
