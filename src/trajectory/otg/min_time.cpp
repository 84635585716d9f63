#include "mjarm/trajectory/otg/min_time.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/otg/reach.hpp"
#include "mjarm/trajectory/otg/roots.hpp"
#include "trajectory/otg/up.hpp"

namespace mjarm {

using jerk_detail::UpForm;

bool reaches_within_limits(const JerkProfile& profile, const KinematicState& target,
                           const JerkLimits& limits, int first_phase) noexcept {
  const KinematicState e = profile.end();
  auto near = [](double x, double y) {
    return std::abs(x - y) <= JerkTolerance::kTarget * std::max(1.0, std::abs(y));
  };
  if (!near(e.p, target.p) || !near(e.v, target.v) || !near(e.a, target.a)) return false;
  const JerkExtrema x = profile.extrema(first_phase);
  const double v = limits.velocity * (1.0 + JerkTolerance::kLimits);
  const double a = limits.acceleration * (1.0 + JerkTolerance::kLimits);
  const double j = limits.jerk * (1.0 + JerkTolerance::kLimits);
  for (int i = std::max(first_phase, 0); i < profile.size(); ++i)
    if (std::abs(profile.jerk(i)) > j) return false;
  return x.v_min >= -v && x.v_max <= v && x.a_min >= -a && x.a_max <= a;
}

namespace {

/// Verifies the profiles of step 1 and records the valid ones in the block.
///
/// Limits: the structures keep u ≤ A and w ≥ −A; the lowest velocity of a UDDU profile is at its
/// start, its end, or where the acceleration crosses zero in its first or last ramp — there
/// v₀ − a₀²/(2J) and v_f − a_f²/(2J), within the limits for a startable start and a reachable
/// target — so the highest velocity, where the acceleration crosses zero between the levels u > 0
/// and w < 0, is the one the structures check.
struct MinTimeCollector {
  JerkBlock* block = nullptr;
  double tol_p = 0.0, tol_v = 0.0, tol_a = 0.0;  ///< target tolerances (absolute)
  bool found = false;

  /// Offers the up-form durations @p t (clamped in place): recorded when ≥ 0 and on target.
  void offer(const UpForm& up, double* t) noexcept {
    if (!jerk_detail::clamp_durations(t)) return;
    const KinematicState e = jerk_detail::uddu_end(up, t);
    if (std::abs(e.p - up.d) > tol_p || std::abs(e.v - up.vf) > tol_v ||
        std::abs(e.a - up.af) > tol_a)
      return;
    double total = 0.0;
    for (int i = 0; i < 7; ++i) total += t[i];
    block->record(total, jerk_detail::to_phases(up, t));
    found = true;
  }
  /// Offers durations @p t of the reversed problem of @p up, read backwards.
  void offer_reversed(const UpForm& up, const double* t) noexcept {
    double r[7];
    jerk_detail::reverse_durations(t, r);
    offer(up, r);
  }
};

/// Relative slack of the velocity checks.
constexpr double kVelocitySlack = 1.0 + JerkTolerance::kLimits;

/// Roots of @p p (degree 2 or 4) in [lo, hi] widened by @p slack (so that a root on a
/// structure's boundary is found by both structures that meet there); none when lo > hi.
template <typename F>
void for_roots(const Polynomial& p, double lo, double hi, double slack, F&& f) noexcept {
  if (!(lo <= hi)) return;
  std::array<double, kMaxRoots> roots{};
  const int k = real_roots(p, lo - slack, hi + slack, roots);
  for (int i = 0; i < k; ++i) f(roots[i]);
}

/// A cruise at +V: the rise to (V, 0) and the fall from it in closed form (the cruise shape), the
/// cruise closes the distance.
void with_cruise(const UpForm& up, const jerk_detail::CruiseShape& cruise,
                 MinTimeCollector& out) noexcept {
  if (!cruise.valid) return;
  double t[7];
  for (int i = 0; i < 7; ++i) t[i] = cruise.t[i];
  t[3] = (up.d - cruise.p) / cruise.v;
  out.offer(up, t);
}

/// Holds at +A and −A without a cruise: with x = J·h₆ the position is the quadratic
/// A·x² + (3A² + F)·x + (48A⁴ + 6A²F₀ + 42A²F − 8A·E − 3F₀² + 3F²)/(24A) = 0; h₂ = h₆ + K/(A·J).
void with_both_holds(const UpForm& up, MinTimeCollector& out) noexcept {
  const double A = up.A, J = up.J, F0 = up.f0, F = up.f;
  const double iJ = up.ij;
  // the peak (F₀ + 2A²)/(2J) + A·h₂ ≤ V bounds h₂, and so x
  const double h2_max = (up.V * kVelocitySlack - (F0 + 2.0 * A * A) / (2.0 * J)) / A;
  const double x_lo = std::max(0.0, -up.k / A), x_hi = J * h2_max - up.k / A;
  if (!(x_lo <= x_hi + 1e-9 * A)) return;
  Polynomial p;
  p.degree = 2;
  p.c[2] = A;
  p.c[1] = 3.0 * A * A + F;
  p.c[0] = (48.0 * A * A * A * A + 6.0 * A * A * F0 + 42.0 * A * A * F - 8.0 * A * up.e -
            3.0 * F0 * F0 + 3.0 * F * F) /
           (24.0 * A);
  for_roots(p, x_lo, x_hi, 1e-9 * A, [&](double x) {
    const double h6 = x * iJ, h2 = h6 + up.k * iJ / A;
    if (F0 + 2.0 * A * A + 2.0 * J * A * h2 > 2.0 * J * up.V * kVelocitySlack) return;
    double t[7] = {(A - up.a0) * iJ, h2, 2.0 * A * iJ, 0.0, 0.0, h6, (up.af + A) * iJ};
    out.offer(up, t);
  });
}

/// A hold at +A, none at −A, no cruise: the quartic in the lowest level w
/// w⁴ − 2A·w³ + (A² + F)·w² − 2A·F·w − (8A·E − 6A²(F₀ + F) + 3F₀² − 3F²)/12 = 0,
/// h₂ = (w² − A² + K)/(A·J). For the time-reversed problem @p q of @p up (the hold at −A), the
/// durations are read backwards.
void with_top_hold(const UpForm& up, const UpForm& q, bool reverse,
                   MinTimeCollector& out) noexcept {
  const double A = q.A, J = q.J, V = q.V, F0 = q.f0, F = q.f;
  const double iJ = q.ij;
  // w in [−A, a_f], h₂ ≥ 0 (w² ≥ A² − K), and a velocity peak (F + 2w²)/(2J) ≤ V when w < 0
  const double lo = std::max(-A, -std::sqrt(std::max(0.0, J * V * kVelocitySlack - 0.5 * F)));
  const double hi = std::min(q.af, A);
  const double g = A * A - q.k;
  const double s = std::sqrt(std::max(g, 0.0));
  const double lo_neg = lo, hi_neg = std::min(hi, -s), lo_pos = std::max(lo, s);
  if (!(lo_neg <= hi_neg) && !(lo_pos <= hi)) return;
  Polynomial p;
  p.degree = 4;
  p.c[4] = 1.0;
  p.c[3] = -2.0 * A;
  p.c[2] = A * A + F;
  p.c[1] = -2.0 * A * F;
  p.c[0] = -(8.0 * A * q.e - 6.0 * A * A * (F0 + F) + 3.0 * F0 * F0 - 3.0 * F * F) / 12.0;
  const auto solution = [&](double w) {
    // the spans are widened by round-off: the limits are checked on the root itself
    if (w < -A * kVelocitySlack || (w < 0.0 && F + 2.0 * w * w > 2.0 * J * V * kVelocitySlack))
      return;
    double t[7] = {(A - q.a0) * iJ, (w * w - g) * iJ / A, (A - w) * iJ, 0.0, 0.0, 0.0,
                   (q.af - w) * iJ};
    if (reverse)
      out.offer_reversed(up, t);
    else
      out.offer(up, t);
  };
  if (s > 0.0) {
    for_roots(p, lo_neg, hi_neg, 1e-9 * A, solution);
    for_roots(p, lo_pos, hi, 1e-9 * A, solution);
  } else {
    for_roots(p, lo, hi, 1e-9 * A, solution);
  }
}

/// No hold, no cruise: (+J, −J, +J) through the levels u and w, u² = w² + K. The position
/// residual is (w³ + F·w + E/3) − u·(w² + M) = 0 (times −1/J²); squared, the sextic terms cancel:
/// K·w⁴ + (2E/3)·w³ + K²·w² + (2F·E/3)·w + E²/9 − K·M² = 0, and u = (w³ + F·w + E/3)/(w² + M)
/// (so every root is a solution, with the sign of u it gives).
void without_holds(const UpForm& up, MinTimeCollector& out) noexcept {
  const double A = up.A, J = up.J, K = up.k, E = up.e, F = up.f, M = up.m;
  const double iJ = up.ij;
  const double g = A * A - K;  // |u| ≤ A
  if (g < -1e-9 * A * A) return;
  // w in [−A, a_f] with −K ≤ w² ≤ A² − K; when u ≥ a₀ > 0, also w² ≥ a₀² − K, and a w < 0 makes
  // the velocity peak where the acceleration crosses zero: (F + 2w²)/(2J) ≤ V
  const double hi = std::min(up.af, A);
  double lo = -A, w2_min = std::max(-K, 0.0);
  if (up.a0 >= 0.0) {
    lo = std::max(lo, -std::sqrt(std::max(0.0, J * up.V * kVelocitySlack - 0.5 * F)));
    w2_min = std::max(w2_min, up.a0 * up.a0 - K);
  }
  const double s_hi = std::sqrt(std::max(g, 0.0)), s_lo = std::sqrt(w2_min);
  Polynomial p;
  p.degree = 4;
  p.c[4] = K;
  p.c[3] = 2.0 * E / 3.0;
  p.c[2] = K * K;
  p.c[1] = 2.0 * F * E / 3.0;
  p.c[0] = E * E / 9.0 - K * M * M;
  const double v_peak = 2.0 * J * up.V * kVelocitySlack - up.f0;  // 2u² ≤ this when u > 0 > w
  const auto solution = [&](double w) {
    if (w < -A * kVelocitySlack) return;
    const double r = std::sqrt(std::max(w * w + K, 0.0));
    const double n = w * (w * w + F) + E / 3.0, q = w * w + M;
    const auto offer_level = [&](double u) {
      if (u > A * kVelocitySlack || (u > 0.0 && w < 0.0 && 2.0 * u * u > v_peak)) return;
      double t[7] = {(u - up.a0) * iJ, 0.0, (u - w) * iJ, 0.0, 0.0, 0.0, (up.af - w) * iJ};
      out.offer(up, t);
    };
    if (std::abs(q) > 1e-9 * (w * w + std::abs(M)) && std::abs(n / q) > 1e-6 * r) {
      offer_level(std::copysign(r, n / q));
    } else {
      offer_level(r);
      if (r > 0.0) offer_level(-r);
    }
  };
  if (s_lo > 0.0) {
    for_roots(p, std::max(lo, -s_hi), std::min(hi, -s_lo), 1e-9 * A, solution);
    for_roots(p, std::max(lo, s_lo), std::min(hi, s_hi), 1e-9 * A, solution);
  } else {
    for_roots(p, std::max(lo, -s_hi), std::min(hi, s_hi), 1e-9 * A, solution);
  }
}

}  // namespace

namespace jerk_detail {

bool min_time_profile(const UpPair& up, const KinematicState& start, const KinematicState& target,
                      JerkBlock& block) noexcept {
  block.start = start;
  block.duration_count = 0;
  block.blocked_count = 0;
  block.t_min = 0.0;
  MinTimeCollector out;
  out.block = &block;
  out.tol_p = JerkTolerance::kTarget * std::max({1.0, std::abs(target.p), std::abs(start.p)});
  out.tol_v = JerkTolerance::kTarget * std::max(1.0, std::abs(target.v));
  out.tol_a = JerkTolerance::kTarget * std::max(1.0, std::abs(target.a));
  const double d = target.p - start.p;
  if (std::abs(d) <= out.tol_p && std::abs(target.v - start.v) <= out.tol_v &&
      std::abs(target.a - start.a) <= out.tol_a) {
    block.record(0.0, JerkPhases{});  // already there
    out.found = true;
  }
  for (int k = 0; k < 2; ++k) {
    const UpForm& f = up.form[k];
    with_cruise(f, up.cruise[k], out);
    with_both_holds(f, out);
    with_top_hold(f, f, false, out);
    with_top_hold(f, reversed(f), true, out);
    without_holds(f, out);
  }
  if (!out.found) return false;
  block.t_min = block.durations[0];
  // the target is out of reach inside a blocked interval: test one duration between each pair
  JerkReach reach;
  for (int k = 0; k + 1 < block.duration_count && block.blocked_count < JerkBlock::kMaxBlocked;
       ++k) {
    const double lower = block.durations[k], upper = block.durations[k + 1];
    if (!reach_range(up, start.p, 0.5 * (lower + upper), reach) || !reach_contains(reach, target.p))
      block.blocked[block.blocked_count++] = {lower, upper};
  }
  return true;
}

}  // namespace jerk_detail

bool min_time_profile(const KinematicState& start, const KinematicState& target,
                      const JerkLimits& limits, JerkBlock& block) noexcept {
  jerk_detail::UpPair up;
  up.set(start, target.p - start.p, target.v, target.a, limits);
  return jerk_detail::min_time_profile(up, start, target, block);
}

}  // namespace mjarm
