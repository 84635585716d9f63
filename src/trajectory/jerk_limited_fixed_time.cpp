#include "mjarm/trajectory/jerk_limited_fixed_time.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/jerk_limited_block.hpp"
#include "mjarm/trajectory/jerk_limited_min_time.hpp"
#include "trajectory/jerk_limited_symbolic.hpp"

namespace mjarm {

using jerk_detail::evaluate;
using jerk_detail::Ext;
using jerk_detail::ext;
using jerk_detail::linear;
using jerk_detail::SymbolicPhases;
using jerk_detail::operator+;
using jerk_detail::operator-;
using jerk_detail::operator*;

namespace {

/// A structure of up to 7 phases whose durations depend on one unknown x (and r = ±√Q(x)).
struct FixedStructure {
  int size = 0;
  double jerk[7] = {};
  Ext duration[7];
  Polynomial q;  ///< r² = q(x); zero when r does not appear
  void add(double j, const Ext& t) noexcept {
    jerk[size] = j;
    duration[size] = t;
    ++size;
  }
};

/// The fixed-duration problem in one direction (states times `sign`).
struct FixedProblem {
  KinematicState start, target;
  JerkLimits limits;
  double duration = 0.0;
  double sign = 1.0;
  double v0 = 0.0, a0 = 0.0, vf = 0.0, af = 0.0, distance = 0.0;
};

/// Solves @p st for x in [lo, hi]; on the first valid profile writes it and returns true.
bool solve_structure(const FixedProblem& fp, const FixedStructure& st, double lo, double hi,
                     JerkProfile& profile) noexcept {
  SymbolicPhases s(st.q, fp.v0, fp.a0);
  for (int i = 0; i < st.size; ++i) s.phase(st.jerk[i], st.duration[i]);
  std::array<double, kMaxRoots> roots{};
  const int n = real_roots(s.residual(fp.distance), lo, hi, roots);
  for (int k = 0; k < n; ++k) {
    const double x = roots[k];
    const double qx = st.q(x);
    if (qx < -1e-10) continue;
    const double r = std::sqrt(std::max(qx, 0.0));
    for (const double rr : {r, -r}) {
      profile.reset(fp.start);
      bool ok = true;
      for (int i = 0; i < st.size && ok; ++i) {
        double t = evaluate(st.duration[i], x, rr);
        if (!(t >= -1e-12)) ok = false;  // also NaN
        if (ok && t > 0.0) profile.append(fp.sign * st.jerk[i], t);
      }
      if (ok && std::abs(profile.duration() - fp.duration) <= 1e-9 * std::max(1.0, fp.duration) &&
          reaches_within_limits(profile, fp.target, fp.limits))
        return true;
      if (r == 0.0) break;
    }
  }
  return false;
}

/// Cruise at a free velocity: rise (+j, plateau?, −j) to (v_c, 0), cruise, then leave with
/// (−j, plateau?, +j) when `leave_down`, else (+j, plateau?, −j).
bool solve_cruise(const FixedProblem& fp, bool rise_plateau, bool leave_plateau, bool leave_down,
                  JerkProfile& profile) noexcept {
  const double A = fp.limits.acceleration, J = fp.limits.jerk;
  const double a0 = fp.a0, af = fp.af;
  FixedStructure st;
  // the rise: x = u (level) or x = h1 (plateau length at A)
  Polynomial vc;  // cruise velocity as a polynomial in x
  Ext rise_time;
  double lo = 0.0, hi = 0.0;
  if (!rise_plateau) {
    vc = linear(fp.v0 - a0 * a0 / (2.0 * J));
    vc.c[2] = 1.0 / J;
    vc.degree = 2;
    st.add(J, ext(linear(-a0 / J, 1.0 / J)));
    st.add(-J, ext(linear(0.0, 1.0 / J)));
    rise_time = ext(linear(-a0 / J, 2.0 / J));
    lo = std::max(a0, 0.0);
    hi = A;
  } else {
    vc = linear(fp.v0 + (2.0 * A * A - a0 * a0) / (2.0 * J), A);
    st.add(J, ext(linear((A - a0) / J)));
    st.add(0.0, ext(linear(0.0, 1.0)));
    st.add(-J, ext(linear(A / J)));
    rise_time = ext(linear((2.0 * A - a0) / J, 1.0));
    lo = 0.0;
    hi = HUGE_VAL;
  }
  // the leave: level w = ∓r (no plateau) or ∓A with a plateau h5(x)
  const double s = leave_down ? -1.0 : 1.0;  // sign of the leave's level
  Ext leave[3];
  int leave_size = 0;
  Ext leave_time;
  if (!leave_plateau) {
    // vf − v_c = s·(w² − af²/2)/J·... : w² = J·s·(vf − v_c) + af²/2
    st.q = (J * s) * (linear(fp.vf) - vc) + linear(0.5 * af * af);
    leave[leave_size++] = ext(Polynomial{}, linear(1.0 / J));         // |w|/J
    leave[leave_size++] = ext(linear(-s * af / J), linear(1.0 / J));  // (|w| − s·af)/J
    leave_time = ext(linear(-s * af / J), linear(2.0 / J));
  } else {
    // vf − v_c = s·(2A² − af²)/(2J) + s·A·h5
    const Polynomial h5 =
        (s / A) * (linear(fp.vf) - vc) - linear((2.0 * A * A - af * af) / (2.0 * J * A));
    leave[leave_size++] = ext(linear(A / J));
    leave[leave_size++] = ext(h5);
    leave[leave_size++] = ext(linear((A - s * af) / J));
    leave_time = ext(linear((2.0 * A - s * af) / J) + h5);
  }
  // cruise = T − rise − leave
  st.add(0.0, ext(linear(fp.duration)) - rise_time - leave_time);
  const double jl[3] = {s * J, 0.0, -s * J};
  if (!leave_plateau) {
    st.add(s * J, leave[0]);
    st.add(-s * J, leave[1]);
  } else {
    for (int i = 0; i < 3; ++i) st.add(jl[i], leave[i]);
  }
  return solve_structure(fp, st, lo, hi, profile);
}

/// No cruise: (+j, −j, +j) with a hold at a free level after the first ramp (`hold_first`) or
/// after the second.
bool solve_hold(const FixedProblem& fp, bool hold_first, JerkProfile& profile) noexcept {
  const double A = fp.limits.acceleration, J = fp.limits.jerk, T = fp.duration;
  const double a0 = fp.a0, af = fp.af, dv = fp.vf - fp.v0;
  FixedStructure st;
  if (!hold_first) {
    // x = w (held), u = w + r with r² = w² − c(w)
    // c(w) = w² + J·w·T + w·(a0 − af) + (af² − a0²)/2 − J·Δv
    const Polynomial c = Polynomial{{(af * af - a0 * a0) / 2.0 - J * dv, J * T + a0 - af, 1.0}, 2};
    st.q = Polynomial{{0.0, 0.0, 1.0}, 2} - c;
    const Ext u = ext(linear(0.0, 1.0), linear(1.0));
    st.add(J, (1.0 / J) * (u - ext(linear(a0))));
    st.add(-J, (1.0 / J) * (u - ext(linear(0.0, 1.0))));
    // hold = T − (2u − a0 − 2w + af)/J
    st.add(0.0,
           ext(linear(T)) - (1.0 / J) * (2.0 * u - ext(linear(a0 + 0.0, 2.0)) + ext(linear(af))));
    st.add(J, ext(linear(af / J, -1.0 / J)));
    return solve_structure(fp, st, -A, std::min(af, A), profile);
  }
  // x = u (held), w = u − r with r² = u² + c2(u)
  // c2(u) = −u² + u·(a0 − af + J·T) + (af² − a0²)/2 − J·Δv
  st.q = Polynomial{{(af * af - a0 * a0) / 2.0 - J * dv, a0 - af + J * T, 0.0}, 1};
  const Ext w = ext(linear(0.0, 1.0), linear(-1.0));
  const Ext u = ext(linear(0.0, 1.0));
  st.add(J, ext(linear(-a0 / J, 1.0 / J)));
  st.add(0.0, ext(linear(T)) - (1.0 / J) * (2.0 * u - ext(linear(a0)) - 2.0 * w + ext(linear(af))));
  st.add(-J, (1.0 / J) * (u - w));
  st.add(J, (1.0 / J) * (ext(linear(af)) - w));
  return solve_structure(fp, st, std::max(a0, -A), A, profile);
}

/// No cruise: a plateau at a limit and a hold at a free level: (+j, A, −j, hold at w, +j) when
/// `plateau_first`, else (+j, hold at u, −j, −A, +j). x = the free hold's length; the free level
/// solves a quadratic (r² = discriminant).
bool solve_plateau_and_hold(const FixedProblem& fp, bool plateau_first,
                            JerkProfile& profile) noexcept {
  const double A = fp.limits.acceleration, J = fp.limits.jerk, T = fp.duration;
  const double a0 = fp.a0, af = fp.af, dv = fp.vf - fp.v0;
  FixedStructure st;
  const Polynomial b = linear(2.0 * A, J);  // J·x + 2A
  const Ext x = ext(linear(0.0, 1.0));
  if (plateau_first) {
    // w² − (Jx + 2A)·w − E/2 = 0
    const Polynomial e = linear(-2.0 * A * A - a0 * a0 + af * af + 2.0 * J * A * T + 2.0 * A * a0 -
                                    2.0 * A * af - 2.0 * J * dv,
                                -2.0 * J * A);
    st.q = b * b + 2.0 * e;
    const Ext w = ext(linear(A, 0.5 * J), linear(0.5));
    st.add(J, ext(linear((A - a0) / J)));
    st.add(0.0, ext(linear(T)) - x - (1.0 / J) * (ext(linear(2.0 * A - a0 + af)) - 2.0 * w));
    st.add(-J, (1.0 / J) * (ext(linear(A)) - w));
    st.add(0.0, x);
    st.add(J, (1.0 / J) * (ext(linear(af)) - w));
    return solve_structure(fp, st, 0.0, T, profile);
  }
  // u² + (Jx + 2A)·u + G/2 = 0
  const Polynomial g = linear(2.0 * A * A - a0 * a0 + af * af - 2.0 * J * A * T - 2.0 * A * a0 +
                                  2.0 * A * af - 2.0 * J * dv,
                              2.0 * J * A);
  st.q = b * b - 2.0 * g;
  const Ext u = ext(linear(-A, -0.5 * J), linear(0.5));
  st.add(J, (1.0 / J) * (u - ext(linear(a0))));
  st.add(0.0, x);
  st.add(-J, (1.0 / J) * (u + ext(linear(A))));
  st.add(0.0, ext(linear(T)) - x - (1.0 / J) * (2.0 * u + ext(linear(2.0 * A - a0 + af))));
  st.add(J, ext(linear((af + A) / J)));
  return solve_structure(fp, st, 0.0, T, profile);
}

/// No cruise: (+j, −j, +j) with a hold at the start acceleration before it (`at_start`) or at
/// the target acceleration after it. x = the middle level on the far side of the hold; the
/// level next to the hold solves a quadratic (r² = discriminant).
bool solve_end_hold(const FixedProblem& fp, bool at_start, JerkProfile& profile) noexcept {
  const double A = fp.limits.acceleration, J = fp.limits.jerk, T = fp.duration;
  const double a0 = fp.a0, af = fp.af, dv = fp.vf - fp.v0;
  FixedStructure st;
  const Ext x = ext(linear(0.0, 1.0));
  if (at_start) {
    // x = w; u² − 2a0·u + C(w)/2 = 0,
    // C(w) = 2J·a0·T + a0² + 4a0·w − 2a0·af − 2w² + af² − 2J·Δv
    const Polynomial c = Polynomial{
        {2.0 * J * a0 * T + a0 * a0 - 2.0 * a0 * af + af * af - 2.0 * J * dv, 4.0 * a0, -2.0}, 2};
    st.q = linear(a0 * a0) - 0.5 * c;
    const Ext u = ext(linear(a0), linear(1.0));
    st.add(0.0, ext(linear(T)) - (1.0 / J) * (2.0 * u - ext(linear(a0 + af)) - 2.0 * x));
    st.add(J, (1.0 / J) * (u - ext(linear(a0))));
    st.add(-J, (1.0 / J) * (u - x));
    st.add(J, (1.0 / J) * (ext(linear(af)) - x));
    return solve_structure(fp, st, -A, std::min(af, A), profile);
  }
  // x = u; w² − 2af·w − C′(u)/2 = 0,
  // C′(u) = 2u² − 4af·u − a0² − af² + 2J·af·T + 2af·a0 − 2J·Δv
  const Polynomial c = Polynomial{
      {-a0 * a0 - af * af + 2.0 * J * af * T + 2.0 * af * a0 - 2.0 * J * dv, -4.0 * af, 2.0}, 2};
  st.q = linear(af * af) + 0.5 * c;
  const Ext w = ext(linear(af), linear(1.0));
  st.add(J, (1.0 / J) * (x - ext(linear(a0))));
  st.add(-J, (1.0 / J) * (x - w));
  st.add(J, (1.0 / J) * (ext(linear(af)) - w));
  st.add(0.0, ext(linear(T)) - (1.0 / J) * (2.0 * x - ext(linear(a0 - af)) - 2.0 * w));
  return solve_structure(fp, st, std::max(a0, -A), A, profile);
}

/// A cruise at +v_max, reached by (+j, −j) and left by (−j, +j), with a hold at a free level in
/// the rise (`hold_in_rise`) or in the leave. x = the hold's length; its level solves a
/// quadratic (r² = discriminant).
bool solve_limit_cruise(const FixedProblem& fp, bool hold_in_rise, JerkProfile& profile) noexcept {
  const double V = fp.limits.velocity, A = fp.limits.acceleration, J = fp.limits.jerk;
  const double T = fp.duration, a0 = fp.a0, af = fp.af;
  FixedStructure st;
  const Ext x = ext(linear(0.0, 1.0));
  if (hold_in_rise) {
    // V − v0 = (2u² − a0²)/(2J) + u·x;  leave: w² = J·(V − vf) + af²/2 (no hold)
    const double w2 = J * (V - fp.vf) + 0.5 * af * af;
    if (w2 < 0.0) return false;
    const double w = -std::sqrt(w2);
    st.q = Polynomial{{2.0 * a0 * a0 + 4.0 * J * (V - fp.v0), 0.0, J * J}, 2};
    const Ext u = ext(linear(0.0, -0.5 * J), linear(0.5));
    const Ext rise = (1.0 / J) * (2.0 * u - ext(linear(a0))) + x;
    const double leave = (af - 2.0 * w) / J;
    st.add(J, (1.0 / J) * (u - ext(linear(a0))));
    st.add(0.0, x);
    st.add(-J, (1.0 / J) * u);
    st.add(0.0, ext(linear(T - leave)) - rise);
    st.add(-J, ext(linear(-w / J)));
    st.add(J, ext(linear((af - w) / J)));
    return solve_structure(fp, st, 0.0, T, profile);
  }
  // rise without a hold: V − v0 = (2u² − a0²)/(2J) (+ a plateau at A when u would exceed it)
  double u = std::sqrt(std::max(J * (V - fp.v0) + 0.5 * a0 * a0, 0.0)), h1 = 0.0;
  if (u > A) {
    u = A;
    h1 = (V - fp.v0 - (2.0 * A * A - a0 * a0) / (2.0 * J)) / A;
  }
  // vf − V = (af² − 2w²)/(2J) + w·x
  st.q = Polynomial{{2.0 * af * af - 4.0 * J * (fp.vf - V), 0.0, J * J}, 2};
  const Ext w = ext(linear(0.0, 0.5 * J), linear(0.5));
  const double rise = (2.0 * u - a0) / J + h1;
  const Ext leave = (1.0 / J) * (ext(linear(af)) - 2.0 * w) + x;
  st.add(J, ext(linear((u - a0) / J)));
  st.add(0.0, ext(linear(h1)));
  st.add(-J, ext(linear(u / J)));
  st.add(0.0, ext(linear(T - rise)) - leave);
  st.add(-J, (-1.0 / J) * w);
  st.add(0.0, x);
  st.add(J, (1.0 / J) * (ext(linear(af)) - w));
  return solve_structure(fp, st, 0.0, T, profile);
}

/// No cruise, no hold: (+j_r, −j_r, +j_r) with a reduced jerk j_r ≤ j_max. With y = 1/j_r and
/// δ = a_f − a₀: t₂ = (T − δy)/2, t₁ + t₃ = S = (T + δy)/2, and the velocity equation gives
/// t₁ = N(y)/(2t₂) with N = (Δv − a₀T)·y − (S²/2 − t₂²/2 − t₂S). The jerk part of the position
/// is a homogeneous cubic P in the durations, so (2t₂)³·(position residual)·y is the polynomial
/// y·(2t₂)³·(v₀T + a₀T²/2 − D) + P(N, 2t₂², 2t₂S − N) of degree ≤ 7 in y.
bool solve_reduced_jerk(const FixedProblem& fp, JerkProfile& profile) noexcept {
  const double J = fp.limits.jerk, T = fp.duration, a0 = fp.a0, v0 = fp.v0;
  const double d = fp.af - a0;
  const Polynomial t2 = linear(0.5 * T, -0.5 * d);
  const Polynomial S = linear(0.5 * T, 0.5 * d);
  const Polynomial N =
      linear(0.0, fp.vf - v0 - a0 * T) - (0.5 * (S * S) - 0.5 * (t2 * t2) - t2 * S);
  const Polynomial two_t2 = 2.0 * t2;
  SymbolicPhases jerk_part(Polynomial{}, 0.0, 0.0);
  jerk_part.phase(1.0, ext(N));
  jerk_part.phase(-1.0, ext(two_t2 * t2));
  jerk_part.phase(1.0, ext(two_t2 * S - N));
  const Polynomial cube = two_t2 * two_t2 * two_t2;
  const Polynomial residual =
      linear(0.0, v0 * T + 0.5 * a0 * T * T - fp.distance) * cube + jerk_part.position().a;
  std::array<double, kMaxRoots> roots{};
  const int n = real_roots(residual, 1.0 / J, HUGE_VAL, roots);
  for (int k = 0; k < n; ++k) {
    const double y = roots[k];
    const double h2 = t2(y);
    if (!(h2 > 0.0)) continue;
    const double h1 = N(y) / (2.0 * h2), h3 = S(y) - h1;
    if (!(h1 >= -1e-12 && h3 >= -1e-12)) continue;
    const double jr = 1.0 / y;
    profile.reset(fp.start);
    if (h1 > 0.0) profile.append(fp.sign * jr, h1);
    profile.append(-fp.sign * jr, h2);
    if (h3 > 0.0) profile.append(fp.sign * jr, h3);
    if (std::abs(profile.duration() - T) <= 1e-9 * std::max(1.0, T) &&
        reaches_within_limits(profile, fp.target, fp.limits))
      return true;
  }
  return false;
}

}  // namespace

bool fixed_time_profile(const KinematicState& start, const KinematicState& target,
                        const JerkLimits& limits, double duration, JerkProfile& profile) noexcept {
  if (!(duration >= 0.0) || !std::isfinite(duration)) return false;
  profile.reset(start);
  if (duration == 0.0 || duration <= 1e-12) return reaches_within_limits(profile, target, limits);
  // the direction of the displacement first: its structures usually hold the answer
  const double first = target.p >= start.p ? 1.0 : -1.0;
  for (const double sign : {first, -first}) {
    FixedProblem fp;
    fp.start = start;
    fp.target = target;
    fp.limits = limits;
    fp.duration = duration;
    fp.sign = sign;
    fp.v0 = sign * start.v;
    fp.a0 = sign * start.a;
    fp.vf = sign * target.v;
    fp.af = sign * target.a;
    fp.distance = sign * (target.p - start.p);
    for (const bool leave_down : {true, false})
      for (const bool rise_plateau : {false, true})
        for (const bool leave_plateau : {false, true})
          if (solve_cruise(fp, rise_plateau, leave_plateau, leave_down, profile)) return true;
    for (const bool hold_first : {false, true})
      if (solve_hold(fp, hold_first, profile)) return true;
    for (const bool plateau_first : {true, false})
      if (solve_plateau_and_hold(fp, plateau_first, profile)) return true;
    for (const bool at_start : {true, false})
      if (solve_end_hold(fp, at_start, profile)) return true;
    for (const bool hold_in_rise : {false, true})
      if (solve_limit_cruise(fp, hold_in_rise, profile)) return true;
    if (solve_reduced_jerk(fp, profile)) return true;
  }
  // last resort when an end is at rest: the time-optimal profile and a rest before or after it
  const bool target_at_rest = target.v == 0.0 && target.a == 0.0;
  const bool start_at_rest = start.v == 0.0 && start.a == 0.0;
  if (!target_at_rest && !start_at_rest) return false;
  JerkBlock block;
  if (!min_time_profile(start, target, limits, block) || block.t_min > duration) return false;
  const JerkProfile& fastest = block.fastest;
  profile.reset(start);
  if (!target_at_rest) profile.append(0.0, duration - block.t_min);
  for (int i = 0; i < fastest.size(); ++i)
    profile.append(fastest.jerk(i), fastest.phase_duration(i));
  if (target_at_rest) profile.append(0.0, duration - block.t_min);
  return reaches_within_limits(profile, target, limits);
}

}  // namespace mjarm
