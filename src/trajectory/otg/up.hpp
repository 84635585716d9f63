#pragma once
// The "up" form of a one-DoF jerk-limited problem, shared by the profile solvers of the trajectory
// room (private). Every problem is solved in the direction `sign` = ±1 after multiplying all its
// states by it, so that the solvers know one profile shape only, UDDU: seven phases with jerk
// (+J, 0, −J, 0, −J, 0, +J); phase 2 holds the acceleration at its peak level u, phase 4 the
// velocity (a = 0), phase 6 the acceleration at its lowest level w. The mirrored direction gives
// the profiles that go down first.

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/otg/block.hpp"
#include "mjarm/trajectory/otg/profile.hpp"
#include "mjarm/trajectory/otg/reach.hpp"

namespace mjarm::jerk_detail {

/// Jerk of each UDDU phase divided by J.
inline constexpr double kUddu[7] = {1.0, 0.0, -1.0, 0.0, -1.0, 0.0, 1.0};

/// Durations within this of zero [s] count as zero (round-off of the solvers).
inline constexpr double kDurationSlack = 1e-12;

/// A one-DoF problem in its up form: start (0, v0, a0), target (d, vf, af), all times `sign`.
struct UpForm {
  double sign = 1.0;
  double v0 = 0.0, a0 = 0.0;  ///< start velocity and acceleration
  double vf = 0.0, af = 0.0;  ///< target velocity and acceleration
  double d = 0.0;             ///< distance to go
  double V = 1.0, A = 1.0, J = 1.0;
  double ij = 1.0;  ///< 1/J
  // shorthands of the velocity and position equations (units of acceleration powers):
  double f0 = 0.0;  ///< 2J·v0 − a0²
  double f = 0.0;   ///< 2J·vf − af²
  double k = 0.0;   ///< J·(vf − v0) + (a0² − af²)/2 = (f − f0)/2
  double m = 0.0;   ///< (f0 + f)/2
  double e = 0.0;   ///< 3J²·d + 3J·(a0·v0 − af·vf) − a0³ + af³

  /// Fills the shorthands from the fields above.
  void derive() noexcept {
    ij = 1.0 / J;
    f0 = 2.0 * J * v0 - a0 * a0;
    f = 2.0 * J * vf - af * af;
    k = 0.5 * (f - f0);
    m = 0.5 * (f0 + f);
    e = 3.0 * J * J * d + 3.0 * J * (a0 * v0 - af * vf) - a0 * a0 * a0 + af * af * af;
  }
};

/// The problem from @p start to (target distance @p d, @p vf, @p af) seen in direction @p sign.
inline UpForm make_up_form(const KinematicState& start, double d, double vf, double af,
                           const JerkLimits& limits, double sign) noexcept {
  UpForm up;
  up.sign = sign;
  up.v0 = sign * start.v;
  up.a0 = sign * start.a;
  up.vf = sign * vf;
  up.af = sign * af;
  up.d = sign * d;
  up.V = limits.velocity;
  up.A = limits.acceleration;
  up.J = limits.jerk;
  up.derive();
  return up;
}

/// The time-reversed problem: a UDDU profile t₁ … t₇ of it, read backwards (t₇ … t₁), is a UDDU
/// profile of @p up (r(t) = p₀ + p_f − p(T − t) starts at (v_f, −a_f) and ends at (v₀, −a₀)).
inline UpForm reversed(const UpForm& up) noexcept {
  UpForm r = up;
  r.v0 = up.vf;
  r.a0 = -up.af;
  r.vf = up.v0;
  r.af = -up.a0;
  r.derive();
  return r;
}

/// The state at the end of the UDDU profile @p t (durations ≥ 0) of @p up, from (0, v0, a0).
inline KinematicState uddu_end(const UpForm& up, const double* t) noexcept {
  KinematicState s{0.0, up.v0, up.a0};
  for (int i = 0; i < 7; ++i) {
    if (!(t[i] > 0.0)) continue;
    if (i == JerkPhases::kCruise) s.a = 0.0;  // the plateau (see JerkPhases)
    s = integrate_jerk(s, kUddu[i] * up.J, t[i]);
  }
  return s;
}

/// Clamps durations within kDurationSlack of zero to zero; false when one is more negative or
/// not finite.
inline bool clamp_durations(double* t) noexcept {
  for (int i = 0; i < 7; ++i) {
    if (!(t[i] >= -kDurationSlack) || !(t[i] < HUGE_VAL)) return false;
    if (t[i] < 0.0) t[i] = 0.0;
  }
  return true;
}

/// The phases of the UDDU profile @p t of @p up in the original direction.
inline JerkPhases to_phases(const UpForm& up, const double* t) noexcept {
  JerkPhases p;
  for (int i = 0; i < 7; ++i) {
    p.jerk[i] = up.sign * kUddu[i] * up.J;
    p.duration[i] = t[i];
  }
  return p;
}

/// Durations of @p up's reversed problem read backwards (see reversed()).
inline void reverse_durations(const double* in, double* out) noexcept {
  for (int i = 0; i < 7; ++i) out[i] = in[6 - i];
}

/// The rise from (v0, a0) to (V, 0) at full jerk: level u (≤ A, with a hold h2 at A when u would
/// pass it); false when the start cannot rise to V without overshooting.
inline bool rise_to_limit(double v0, double a0, double V, double A, double J, double& u,
                          double& h) noexcept {
  const double u2 = J * (V - v0) + 0.5 * a0 * a0;
  if (!(u2 >= 0.0)) return false;
  u = std::sqrt(u2);
  h = 0.0;
  if (u > A) {
    u = A;
    h = (V - v0 - (2.0 * A * A - a0 * a0) / (2.0 * J)) / A;
  }
  // a level below a₀ by round-off only is a₀ itself (t₁ = 0 exactly: the ramps then still end at
  // a = 0, which a long cruise after them needs)
  if (u < a0) {
    if (u < a0 - 1e-12 * A) return false;
    u = a0;
  }
  return true;
}

/// The UDDU profile with a cruise at +V of one direction, without its cruise: it does not depend
/// on the duration or the distance, so it is computed once and serves step 1 (the cruise that
/// closes the distance) and the reachable range at any duration (the cruise that fills it).
struct CruiseShape {
  bool valid = false;     ///< the start can rise to (V, 0) and the target be reached from it
  double t[7] = {};       ///< durations, t[3] (the cruise) = 0
  double duration = 0.0;  ///< their sum [s]
  double p = 0.0;         ///< the position they cover, from 0 [u]
  double v = 0.0;  ///< the velocity of the cruise: V, or a hair above it when the start is on the
                   ///< edge of the startable states (a long cruise must use the true one)
};

/// The cruise shape of @p up.
inline CruiseShape cruise_shape(const UpForm& up) noexcept {
  CruiseShape c;
  double u = 0.0, h2 = 0.0, w = 0.0, h6 = 0.0;
  if (!rise_to_limit(up.v0, up.a0, up.V, up.A, up.J, u, h2) ||
      !rise_to_limit(up.vf, -up.af, up.V, up.A, up.J, w, h6))
    return c;
  c.valid = true;
  c.t[0] = (u - up.a0) * up.ij;
  c.t[1] = h2;
  c.t[2] = u * up.ij;
  c.t[4] = w * up.ij;
  c.t[5] = h6;
  c.t[6] = (up.af + w) * up.ij;
  KinematicState s{0.0, up.v0, up.a0};
  for (int i = 0; i < 3; ++i) s = integrate_jerk(s, kUddu[i] * up.J, c.t[i]);
  c.v = s.v;
  s.a = 0.0;
  for (int i = 4; i < 7; ++i) s = integrate_jerk(s, kUddu[i] * up.J, c.t[i]);
  c.p = s.p;
  for (const double x : c.t) c.duration += x;
  return c;
}

/// A one-DoF problem in both directions with their cruise shapes: everything about it that does
/// not depend on the duration.
struct UpPair {
  UpForm form[2];         ///< up (sign +1) and down (−1)
  CruiseShape cruise[2];  ///< their cruise shapes

  /// The problem from @p start to (distance @p d, @p vf, @p af) under @p limits.
  void set(const KinematicState& start, double d, double vf, double af,
           const JerkLimits& limits) noexcept {
    for (int k = 0; k < 2; ++k) {
      form[k] = make_up_form(start, d, vf, af, limits, k == 0 ? 1.0 : -1.0);
      cruise[k] = cruise_shape(form[k]);
    }
  }
};

/// reach_range() for @p up (its distance is not used) from a start at position @p p0.
bool reach_range(const UpPair& up, double p0, double duration, JerkReach& reach) noexcept;

/// min_time_profile() for @p up, the problem from @p start to @p target.
bool min_time_profile(const UpPair& up, const KinematicState& start, const KinematicState& target,
                      JerkBlock& block) noexcept;

}  // namespace mjarm::jerk_detail
