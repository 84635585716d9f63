#include "mjarm/trajectory/otg/brake.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

namespace {

constexpr double kBrakeSlack = 1e-12;
/// The brake aims this far (relative) inside the velocity limit: it can pass through velocities
/// far above the limit (hundreds of times, for a large acceleration and a small jerk), whose
/// round-off would otherwise leave its end a hair outside.
constexpr double kBrakeMargin = 1e-10;

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

bool append_brake(const KinematicState& start, const JerkLimits& limits,
                  JerkProfile& profile) noexcept {
  if (is_startable(start, limits)) return true;
  const double V = limits.velocity * (1.0 - kBrakeMargin), A = limits.acceleration;
  const double J = limits.jerk;
  const double f = settled_velocity(start, J);
  if (std::abs(f) <= V) {
    // ramp the acceleration towards zero: f stays, v moves towards it, |a| falls
    const double s = start.a > 0.0 ? 1.0 : -1.0;  // a ≠ 0 here, else v = f would be within
    const double a = s * start.a, v = s * start.v;
    double tau = std::max((a - A) / J, 0.0);
    if (v < -V) tau = std::max(tau, (a - std::sqrt(std::max(a * a + 2.0 * J * (V + v), 0.0))) / J);
    return profile.append(-s * J, std::min(tau, a / J));
  }
  // seen with the violation on the positive side (f > V): bring v down to V, ending on a +J ramp
  // whose settled velocity is f_e (the velocity the acceleration would settle at): f_e = 0 when
  // a_max²/(2j) ≥ V, else V − a_max²/(2j) (then the ramp is empty and the brake holds at −a_max)
  const double s = f > V ? 1.0 : -1.0;
  double a = s * start.a, v = s * start.v;
  if (a < -A) {
    // a deceleration beyond its limit: up to −A first (f stays > V on the way)
    if (!profile.append(s * J, (-A - a) / J)) return false;
    v = s * profile.end().v;
    a = -A;
  }
  const double f_e = std::max(V - 0.5 * A * A / J, 0.0);
  const double c = v + 0.5 * a * a / J;  // v + a²/(2J) stays c on a −J ramp
  if (c <= 2.0 * V - f_e) {
    // the −J ramp alone meets v = V (the later crossing: v + a·τ − J·τ²/2 = V) at a level in
    // [−√(2J(V − f_e)), 0], where v − a²/(2J) = 2V − c ≥ f_e
    const double tau = (a + std::sqrt(std::max(a * a + 2.0 * J * (v - V), 0.0))) / J;
    return !(tau > 0.0) || profile.append(-s * J, tau);
  }
  // −J down to m (a hold there when m = −A), then +J up to a_e: v − a²/(2J) = f_e on that ramp
  const double m = -std::min(std::sqrt(J * (c - f_e)), A);
  if ((a - m) / J > 0.0 && !profile.append(-s * J, (a - m) / J)) return false;
  // the later phases are timed from the integrated state, so that the brake ends on v = V to
  // round-off even after passing through velocities far above it
  KinematicState e = profile.end();
  if (m == -A) {
    const double hold = (s * e.v - (f_e + 0.5 * A * A / J)) / A;
    if (hold > 0.0 && !profile.append(0.0, hold)) return false;
    e = profile.end();
  }
  // +J until v = V: v + a·τ + J·τ²/2 = V, the first crossing
  const double ve = s * e.v, ae = s * e.a;
  const double tau = (-ae - std::sqrt(std::max(ae * ae - 2.0 * J * (ve - V), 0.0))) / J;
  return !(tau > 0.0) || profile.append(s * J, tau);
}

BrakeFamily brake_family(const KinematicState& start, const JerkLimits& limits) noexcept {
  BrakeFamily family;
  if (is_startable(start, limits)) return family;
  const double V = limits.velocity * (1.0 - kBrakeMargin), A = limits.acceleration;
  const double J = limits.jerk;
  const double f = settled_velocity(start, J);
  double s = 0.0;
  if (std::abs(f) > V)
    s = f > 0.0 ? 1.0 : -1.0;
  else if (std::abs(start.v) > V)
    s = start.v > 0.0 ? 1.0 : -1.0;
  else
    return family;  // only the acceleration is beyond: its ramp is the only brake
  double a = s * start.a, v = s * start.v;
  if (a < -A) {
    // the forced ramp up to −A (v − a²/(2J) stays on it)
    v -= 0.5 * (a * a - A * A) / J;
    a = -A;
  }
  if (is_startable({0.0, s * v, s * a}, limits)) return family;  // that ramp was the brake
  const double c = v + 0.5 * a * a / J;  // v + a²/(2J) stays c on a −J ramp
  const double release_from = std::min(a, 0.0);
  family.side = s;
  family.highest = std::min(V, c - release_from * release_from / J);
  family.lowest = std::min(family.highest, std::max({-V, V - 0.5 * A * A / J, 2.0 * V - c}));
  return family;
}

bool append_brake_member(const KinematicState& start, const JerkLimits& limits, double settled,
                         JerkProfile& profile) noexcept {
  const BrakeFamily family = brake_family(start, limits);
  if (family.side == 0.0) return append_brake(start, limits, profile);
  const double V = limits.velocity * (1.0 - kBrakeMargin), A = limits.acceleration;
  const double J = limits.jerk, s = family.side;
  const double f_e = std::clamp(settled, family.lowest, family.highest);
  double a = s * start.a, v = s * start.v;
  if (a < -A) {
    if (!profile.append(s * J, (-A - a) / J)) return false;
    v = s * profile.end().v;
    a = -A;
  }
  const double c = v + 0.5 * a * a / J;
  if (f_e <= 2.0 * V - c) {
    // no release: the −J ramp alone meets v = V (the later crossing)
    const double tau = (a + std::sqrt(std::max(a * a + 2.0 * J * (v - V), 0.0))) / J;
    return !(tau > 0.0) || profile.append(-s * J, tau);
  }
  // −J down to m (a hold there when m = −A), then the release: +J with v − a²/(2J) = f_e
  const double m = -std::min(std::sqrt(J * std::max(c - f_e, 0.0)), A);
  if ((a - m) / J > 0.0 && !profile.append(-s * J, (a - m) / J)) return false;
  KinematicState e = profile.end();
  if (m == -A) {
    const double hold = (s * e.v - (f_e + 0.5 * A * A / J)) / A;
    if (hold > 0.0 && !profile.append(0.0, hold)) return false;
    e = profile.end();
  }
  // timed from the integrated state, as append_brake's: +J until v = V, the first crossing
  const double ve = s * e.v, ae = s * e.a;
  const double tau = (-ae - std::sqrt(std::max(ae * ae - 2.0 * J * (ve - V), 0.0))) / J;
  return !(tau > 0.0) || profile.append(s * J, tau);
}

}  // namespace mjarm
