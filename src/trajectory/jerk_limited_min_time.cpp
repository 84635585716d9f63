#include "mjarm/trajectory/jerk_limited_min_time.hpp"

#include <algorithm>
#include <cmath>

#include "trajectory/jerk_limited_symbolic.hpp"

namespace mjarm {

using jerk_detail::Ext;
using jerk_detail::ext;
using jerk_detail::linear;
using jerk_detail::SymbolicPhases;
using jerk_detail::operator+;
using jerk_detail::operator-;
using jerk_detail::operator*;

bool reaches_within_limits(const JerkProfile& profile, const KinematicState& target,
                           const JerkLimits& limits) noexcept {
  const KinematicState e = profile.end();
  auto near = [](double x, double y) {
    return std::abs(x - y) <= JerkTolerance::kTarget * std::max(1.0, std::abs(y));
  };
  return near(e.p, target.p) && near(e.v, target.v) && near(e.a, target.a) &&
         profile.within(limits, JerkTolerance::kLimits);
}

namespace {

/// One DoF's problem seen in the direction `sign` (every state multiplied by it), so that every
/// structure is solved for its "up" form only: jerk pattern (+, 0, −, 0, −, 0, +).
struct UpProblem {
  KinematicState start;   ///< start in the original direction
  KinematicState target;  ///< target in the original direction
  JerkLimits limits;
  double sign = 1.0;
  double v0 = 0.0, a0 = 0.0, vf = 0.0, af = 0.0;  ///< velocities/accelerations times sign
  double distance = 0.0;                          ///< (pf − p0)·sign
};

/// Collects the valid profiles of step 1.
struct MinTimeCollector {
  JerkBlock* block = nullptr;
  JerkProfile candidate;
  bool found = false;

  /// Builds the profile of up-form jerks @p j and durations @p t (n phases), verifies it and
  /// records it.
  void offer(const UpProblem& up, const double* j, const double* t, int n) noexcept {
    candidate.reset(up.start);
    for (int i = 0; i < n; ++i) {
      double ti = t[i];
      if (!(ti >= -1e-12)) return;  // also NaN
      if (ti < 0.0) ti = 0.0;
      if (ti == 0.0) continue;
      candidate.append(up.sign * j[i], ti);
    }
    if (!reaches_within_limits(candidate, up.target, up.limits)) return;
    record(candidate);
    if (!found || candidate.duration() < block->t_min) {
      block->fastest = candidate;
      block->t_min = candidate.duration();
    }
    found = true;
  }

  void record(const JerkProfile& profile) noexcept {
    const double duration = profile.duration();
    JerkBlock& b = *block;
    for (int i = 0; i < b.duration_count; ++i)
      if (std::abs(b.durations[i] - duration) <= 1e-9 * std::max(1.0, duration)) return;
    if (b.duration_count == JerkBlock::kMaxDurations) return;
    int i = b.duration_count++;
    while (i > 0 && b.durations[i - 1] > duration) {
      b.durations[i] = b.durations[i - 1];
      b.profiles[i] = b.profiles[i - 1];
      --i;
    }
    b.durations[i] = duration;
    b.profiles[i] = profile;
  }
};

/// Phases 1–3 and 5–7 merged (no velocity plateau): levels u (phase 2) and w (phase 6).
void solve_without_plateau(const UpProblem& up, MinTimeCollector& out) noexcept {
  const double A = up.limits.acceleration, J = up.limits.jerk;
  const double a0 = up.a0, af = up.af, v0 = up.v0, D = up.distance;
  const double dv = up.vf - v0;
  std::array<double, kMaxRoots> roots{};

  // velocity: Δv = (2u² − 2w² − a0² + af²)/(2J) + u·h1 + w·h5
  {  // no acceleration plateau: x = w, r = u with u² = w² + J·Δv + (a0² − af²)/2
    Polynomial q = linear(J * dv + 0.5 * (a0 * a0 - af * af));
    q.c[2] = 1.0;
    q.degree = 2;
    SymbolicPhases s(q, v0, a0);
    s.phase(J, ext(linear(-a0 / J), linear(1.0 / J)));
    s.phase(-J, ext(linear(0.0, -1.0 / J), linear(1.0 / J)));
    s.phase(J, ext(linear(af / J, -1.0 / J)));
    const int n = real_roots(s.residual(D), -A, std::min(af, A), roots);
    for (int i = 0; i < n; ++i) {
      const double w = roots[i];
      const double qw = q(w);
      if (qw < -1e-12 * std::max(1.0, A * A)) continue;
      for (const double u : {std::sqrt(std::max(qw, 0.0)), -std::sqrt(std::max(qw, 0.0))}) {
        const double j[3] = {J, -J, J};
        const double t[3] = {(u - a0) / J, (u - w) / J, (af - w) / J};
        out.offer(up, j, t, 3);
      }
    }
  }
  {  // plateau at +a_max in phase 2: x = w, h1 polynomial in w
    const Polynomial h1 = (1.0 / A) * (linear(dv - (2.0 * A * A - a0 * a0 + af * af) / (2.0 * J)) +
                                       Polynomial{{0.0, 0.0, 1.0 / J}, 2});
    SymbolicPhases s(Polynomial{}, v0, a0);
    s.phase(J, ext(linear((A - a0) / J)));
    s.phase(0.0, ext(h1));
    s.phase(-J, ext(linear(A / J, -1.0 / J)));
    s.phase(J, ext(linear(af / J, -1.0 / J)));
    const int n = real_roots(s.residual(D), -A, std::min(af, A), roots);
    for (int i = 0; i < n; ++i) {
      const double w = roots[i];
      const double j[4] = {J, 0.0, -J, J};
      const double t[4] = {(A - a0) / J, h1(w), (A - w) / J, (af - w) / J};
      out.offer(up, j, t, 4);
    }
  }
  {  // plateau at −a_max in phase 6: x = u, h5 polynomial in u
    const Polynomial h5 =
        (-1.0 / A) * (linear(dv - (-2.0 * A * A - a0 * a0 + af * af) / (2.0 * J)) -
                      Polynomial{{0.0, 0.0, 1.0 / J}, 2});
    SymbolicPhases s(Polynomial{}, v0, a0);
    s.phase(J, ext(linear(-a0 / J, 1.0 / J)));
    s.phase(-J, ext(linear(A / J, 1.0 / J)));
    s.phase(0.0, ext(h5));
    s.phase(J, ext(linear((af + A) / J)));
    const int n = real_roots(s.residual(D), std::max(a0, -A), A, roots);
    for (int i = 0; i < n; ++i) {
      const double u = roots[i];
      const double j[4] = {J, -J, 0.0, J};
      const double t[4] = {(u - a0) / J, (u + A) / J, h5(u), (af + A) / J};
      out.offer(up, j, t, 4);
    }
  }
  {  // both plateaus: x = h5, h1 = (Δv − (af² − a0²)/(2J) + A·h5)/A
    const Polynomial h1 = linear((dv - (af * af - a0 * a0) / (2.0 * J)) / A, 1.0);
    SymbolicPhases s(Polynomial{}, v0, a0);
    s.phase(J, ext(linear((A - a0) / J)));
    s.phase(0.0, ext(h1));
    s.phase(-J, ext(linear(2.0 * A / J)));
    s.phase(0.0, ext(linear(0.0, 1.0)));
    s.phase(J, ext(linear((af + A) / J)));
    const int n = real_roots(s.residual(D), 0.0, HUGE_VAL, roots);
    for (int i = 0; i < n; ++i) {
      const double h5 = roots[i];
      const double j[5] = {J, 0.0, -J, 0.0, J};
      const double t[5] = {(A - a0) / J, h1(h5), 2.0 * A / J, h5, (af + A) / J};
      out.offer(up, j, t, 5);
    }
  }
}

/// With a velocity plateau at +v_max (phase 4): both halves in closed form.
void solve_with_plateau(const UpProblem& up, MinTimeCollector& out) noexcept {
  const double V = up.limits.velocity, A = up.limits.acceleration, J = up.limits.jerk;
  const double a0 = up.a0, af = up.af;
  // to (V, 0): V − v0 = (2u² − a0²)/(2J) + u·h1
  double u2 = J * (V - up.v0) + 0.5 * a0 * a0;
  if (u2 < 0.0) return;
  double u = std::sqrt(u2), h1 = 0.0;
  if (u > A) {
    u = A;
    h1 = (V - up.v0 - (2.0 * A * A - a0 * a0) / (2.0 * J)) / A;
  }
  // from (V, 0): vf − V = (af² − 2w²)/(2J) + w·h5
  double w2 = J * (V - up.vf) + 0.5 * af * af;
  if (w2 < 0.0) return;
  double w = -std::sqrt(w2), h5 = 0.0;
  if (w < -A) {
    w = -A;
    h5 = (up.vf - V - (af * af - 2.0 * A * A) / (2.0 * J)) / (-A);
  }
  const double j[7] = {J, 0.0, -J, 0.0, -J, 0.0, J};
  double t[7] = {(u - a0) / J, h1, u / J, 0.0, -w / J, h5, (af - w) / J};
  // the cruise closes the distance
  KinematicState s{0.0, up.v0, a0};
  for (int i = 0; i < 7; ++i) s = integrate_jerk(s, j[i], std::max(t[i], 0.0));
  t[3] = (up.distance - s.p) / V;
  out.offer(up, j, t, 7);
}

}  // namespace

bool min_time_profile(const KinematicState& start, const KinematicState& target,
                      const JerkLimits& limits, JerkBlock& block) noexcept {
  block.duration_count = 0;
  block.blocked_count = 0;
  block.t_min = 0.0;
  MinTimeCollector out;
  out.block = &block;
  {  // already there
    UpProblem still;
    still.start = start;
    still.target = target;
    still.limits = limits;
    out.offer(still, nullptr, nullptr, 0);
  }
  for (const double sign : {1.0, -1.0}) {
    UpProblem up;
    up.start = start;
    up.target = target;
    up.limits = limits;
    up.sign = sign;
    up.v0 = sign * start.v;
    up.a0 = sign * start.a;
    up.vf = sign * target.v;
    up.af = sign * target.a;
    up.distance = sign * (target.p - start.p);
    solve_with_plateau(up, out);
    solve_without_plateau(up, out);
  }
  if (!out.found) return false;
  block.set_blocked_from_durations();
  return true;
}

}  // namespace mjarm
