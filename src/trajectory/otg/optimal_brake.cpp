#include "mjarm/trajectory/otg/optimal_brake.hpp"

#include <cmath>
#include <limits>

#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"

namespace mjarm {

namespace {

constexpr int kGrid = 8;                    // members tried before the refinement
constexpr double kRefineTolerance = 1e-11;  // of the end-acceleration range
constexpr double kEndProbe = 1e-7;          // a step inwards from an end, of that range

/// The minimum of @p f on [@p a, @p b] near @p x (f(x) = @p fx, the lowest known) by Brent's
/// method: golden-section steps, parabolic ones where the last three points allow, until the
/// bracket is within 2·@p tol. @return its abscissa, the value in @p f_min.
template <class F>
double brent_minimum(F&& f, double a, double b, double x, double fx, double tol, double& f_min) {
  constexpr double kGoldenStep = 0.3819660112501051;  // (3 − √5)/2
  double w = x, v = x, fw = fx, fv = fx, d = 0.0, e = 0.0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double m = 0.5 * (a + b), tol2 = 2.0 * tol;
    if (std::abs(x - m) <= tol2 - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(e) > tol) {
      // the parabola through (x, fx), (w, fw), (v, fv): its vertex x + p/q
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      const double previous = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * previous) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = m > x ? tol : -tol;
        golden = false;
      }
    }
    if (golden) {
      e = x >= m ? a - x : b - x;
      d = kGoldenStep * e;
    }
    const double u = std::abs(d) >= tol ? x + d : x + (d > 0.0 ? tol : -tol);
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  f_min = fx;
  return x;
}

/// The brake in scratch.profile (from the start) and step 1 from its end: their total duration,
/// or +∞ when step 1 has no profile.
double total_after(const KinematicState& target, const JerkLimits& solve_limits,
                   OptimalBrakeScratch& scratch) noexcept {
  if (!min_time_profile(scratch.profile.end(), target, solve_limits, scratch.block))
    return std::numeric_limits<double>::infinity();
  return scratch.profile.duration() + scratch.block.t_min;
}

}  // namespace

bool append_optimal_brake(const KinematicState& start, const KinematicState& target,
                          const JerkLimits& limits, const JerkLimits& solve_limits,
                          JerkProfile& profile, OptimalBrakeScratch& scratch) noexcept {
  const BrakeFamily family = brake_family(start, limits);
  if (family.side == 0.0 || !(family.highest > family.lowest))
    return append_brake(start, limits, profile);  // no choice
  const double V = limits.velocity, J = limits.jerk;
  // a member by its end acceleration (≤ 0 on the side of the violation): f_e = V − a_e²/(2J)
  const auto settled_of = [&](double a_end) { return V - 0.5 * a_end * a_end / J; };
  const auto member_total = [&](double settled) {
    scratch.profile.reset(start);
    if (!append_brake_member(start, limits, settled, scratch.profile))
      return std::numeric_limits<double>::infinity();
    return total_after(target, solve_limits, scratch);
  };
  const double lo = -std::sqrt(2.0 * J * std::max(V - family.lowest, 0.0));
  const double hi = -std::sqrt(2.0 * J * std::max(V - family.highest, 0.0));
  const auto total_at = [&](double a_end) { return member_total(settled_of(a_end)); };
  double best_a = lo, best = total_at(lo);
  int best_k = 0;
  for (int k = 1; k < kGrid; ++k) {
    const double a_end = lo + (hi - lo) * k / (kGrid - 1);
    const double total = total_at(a_end);
    if (total < best) best = total, best_a = a_end, best_k = k;
  }
  // an end of the family that the total rises from (often the best: the latest or the earliest
  // release) is kept; else Brent's minimization (golden section with parabolic steps) between
  // the best member's neighbours
  const double step = (hi - lo) / (kGrid - 1);
  const bool at_end = best_k == 0 || best_k == kGrid - 1;
  const double inward = best_k == 0 ? kEndProbe * (hi - lo) : -kEndProbe * (hi - lo);
  if (!at_end || !(total_at(best_a + inward) >= best))
    best_a = brent_minimum(total_at, std::max(best_a - step, lo), std::min(best_a + step, hi),
                           best_a, best, kRefineTolerance * (hi - lo), best);
  // the standard brake (append_brake) when it is as short: its results stay as they were
  scratch.profile.reset(start);
  if (append_brake(start, limits, scratch.profile) &&
      !(total_after(target, solve_limits, scratch) > best))
    return append_brake(start, limits, profile);
  return append_brake_member(start, limits, settled_of(best_a), profile);
}

}  // namespace mjarm
