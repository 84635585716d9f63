#include "mjarm/trajectory/otg/reach.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/otg/min_time.hpp"
#include "trajectory/otg/up.hpp"

namespace mjarm {

namespace {

using jerk_detail::UpForm;

/// Relative slack of the limit checks.
constexpr double kSlack = 1.0 + JerkTolerance::kLimits;

/// Clamps @p t to ≥ 0 into @p out; false when a duration is negative beyond round-off.
bool accept(const double* t, double* out) noexcept {
  for (int i = 0; i < 7; ++i) out[i] = t[i];
  return jerk_detail::clamp_durations(out);
}

/// The hold at +A with a free lowest level w (see the file comment) for @p q, which is @p up or
/// its time-reversed problem (then the durations are read backwards: the hold at −A).
bool hold_at_top(const UpForm& q, bool reverse, double T, double* out) noexcept {
  const double A = q.A, J = q.J;
  const double iJ = q.ij;
  const double c = q.k + A * A - A * J * T + A * (q.af - q.a0);
  const double disc = A * A - c;
  if (disc < 0.0) return false;
  const double w = A - std::sqrt(disc);
  // w ≥ −A, and the velocity peak (F + 2w²)/(2J) ≤ V when w < 0
  if (w < -A * kSlack || (w < 0.0 && q.f + 2.0 * w * w > 2.0 * J * q.V * kSlack)) return false;
  const double t[7] = {
      (A - q.a0) * iJ, T - (2.0 * A - q.a0 + q.af - 2.0 * w) * iJ, (A - w) * iJ, 0.0, 0.0, 0.0,
      (q.af - w) * iJ};
  if (!reverse) return accept(t, out);
  double r[7];
  jerk_detail::reverse_durations(t, r);
  return accept(r, out);
}

/// The durations of the highest up profile of duration @p T in @p t and its end position in
/// @p p; false when there is none. At most one structure is valid for a given T (they meet only
/// where their profiles coincide), so the first valid one is it. Validity as in
/// min_time.cpp: durations ≥ 0, levels within ±A, and the velocity peak (where the
/// acceleration turns from u > 0 to w < 0) ≤ V.
bool highest_profile(const UpForm& up, const jerk_detail::CruiseShape& cruise, double T, double* t,
                     double& p) noexcept {
  const double A = up.A, J = up.J, V = up.V;
  const double iJ = up.ij;
  if (cruise.valid && T - cruise.duration >= -jerk_detail::kDurationSlack) {
    // a cruise at +V fills the time: the most common case once synchronized to a slower DoF
    const double rest = std::max(T - cruise.duration, 0.0);
    for (int i = 0; i < 7; ++i) t[i] = cruise.t[i];
    t[3] = rest;
    if (jerk_detail::clamp_durations(t)) {
      p = cruise.p + cruise.v * rest;
      return true;
    }
  }
  bool found = false;
  {  // no hold: u − w = S, u + w = K/S
    const double S = 0.5 * (J * T + up.a0 - up.af);
    if (S > 0.0) {
      const double ks = up.k / S;
      const double u = 0.5 * (S + ks), w = 0.5 * (ks - S);
      if (u <= A * kSlack && w >= -A * kSlack &&
          !(u > 0.0 && w < 0.0 && up.f0 + 2.0 * u * u > 2.0 * J * V * kSlack)) {
        const double c[7] = {(u - up.a0) * iJ, 0.0, S * iJ, 0.0, 0.0, 0.0, (up.af - w) * iJ};
        found = accept(c, t);
      }
    }
  }
  if (!found) {  // holds at +A and −A: h2 + h6 = H, h2 − h6 = K/(A·J)
    const double H = T - (4.0 * A - up.a0 + up.af) * iJ;
    const double g = up.k * iJ / A;
    const double h2 = 0.5 * (H + g);
    if (up.f0 + 2.0 * A * A + 2.0 * J * A * h2 <= 2.0 * J * V * kSlack) {
      const double c[7] = {(A - up.a0) * iJ, h2, 2.0 * A * iJ, 0.0, 0.0, 0.5 * (H - g),
                           (up.af + A) * iJ};
      found = accept(c, t);
    }
  }
  found =
      found || hold_at_top(up, false, T, t) || hold_at_top(jerk_detail::reversed(up), true, T, t);
  if (found) p = jerk_detail::uddu_end(up, t).p;
  return found;
}

}  // namespace

namespace jerk_detail {

bool reach_range(const UpPair& up, double p0, double duration, JerkReach& reach) noexcept {
  if (!(duration >= 0.0) || !std::isfinite(duration)) return false;
  const UpForm& f = up.form[0];
  if (duration <= kDurationSlack) {
    // no time: only the start itself, when it has the target's velocity and acceleration
    if (std::abs(f.v0 - f.vf) > 1e-9 * std::max(1.0, std::abs(f.vf)) ||
        std::abs(f.a0 - f.af) > 1e-9 * std::max(1.0, std::abs(f.af)))
      return false;
    reach.p_min = reach.p_max = p0;
    reach.lowest = reach.highest = JerkPhases{};
    return true;
  }
  for (int k = 0; k < 2; ++k) {
    double t[7], p = 0.0;
    if (!highest_profile(up.form[k], up.cruise[k], duration, t, p)) return false;
    if (k == 0) {
      reach.p_max = p0 + p;
      reach.highest = to_phases(up.form[k], t);
    } else {
      reach.p_min = p0 - p;
      reach.lowest = to_phases(up.form[k], t);
    }
  }
  return true;
}

}  // namespace jerk_detail

bool reach_range(const KinematicState& start, double v_target, double a_target,
                 const JerkLimits& limits, double duration, JerkReach& reach) noexcept {
  jerk_detail::UpPair up;
  up.set(start, 0.0, v_target, a_target, limits);
  return jerk_detail::reach_range(up, start.p, duration, reach);
}

bool reach_contains(const JerkReach& reach, double position) noexcept {
  const double tol =
      JerkTolerance::kTarget *
      std::max({1.0, std::abs(position), std::abs(reach.p_min), std::abs(reach.p_max)});
  return position <= reach.p_max + tol && position >= reach.p_min - tol;
}

bool duration_feasible(const KinematicState& start, const KinematicState& target,
                       const JerkLimits& limits, double duration) noexcept {
  JerkReach r;
  return reach_range(start, target.v, target.a, limits, duration, r) && reach_contains(r, target.p);
}

}  // namespace mjarm
