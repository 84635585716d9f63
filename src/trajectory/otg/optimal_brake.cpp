#include "mjarm/trajectory/otg/optimal_brake.hpp"

#include <cmath>
#include <limits>

#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"

namespace mjarm {

namespace {

constexpr int kGrid = 16;                   // members tried before the refinement
constexpr double kRefineTolerance = 1e-12;  // of the end-acceleration range

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
  if (family.side == 0.0) return append_brake(start, limits, profile);
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
  double best_a = lo, best = member_total(settled_of(lo));
  int best_k = 0;
  for (int k = 1; k < kGrid; ++k) {
    const double a_end = lo + (hi - lo) * k / (kGrid - 1);
    const double total = member_total(settled_of(a_end));
    if (total < best) best = total, best_a = a_end, best_k = k;
  }
  // golden section between the best grid member's neighbours
  const double step = (hi - lo) / (kGrid - 1);
  double x0 = best_k > 0 ? best_a - step : best_a, x3 = best_k < kGrid - 1 ? best_a + step : best_a;
  constexpr double kGolden = 0.6180339887498949;
  double x1 = x3 - kGolden * (x3 - x0), x2 = x0 + kGolden * (x3 - x0);
  double f1 = member_total(settled_of(x1)), f2 = member_total(settled_of(x2));
  while (x3 - x0 > kRefineTolerance * (hi - lo) && x3 - x0 > 0.0) {
    if (f1 <= f2) {
      x3 = x2, x2 = x1, f2 = f1;
      x1 = x3 - kGolden * (x3 - x0);
      f1 = member_total(settled_of(x1));
    } else {
      x0 = x1, x1 = x2, f1 = f2;
      x2 = x0 + kGolden * (x3 - x0);
      f2 = member_total(settled_of(x2));
    }
  }
  if (f1 < best) best = f1, best_a = x1;
  if (f2 < best) best = f2, best_a = x2;
  // the standard brake (append_brake) when it is as short: its results stay as they were
  scratch.profile.reset(start);
  if (append_brake(start, limits, scratch.profile) &&
      !(total_after(target, solve_limits, scratch) > best))
    return append_brake(start, limits, profile);
  return append_brake_member(start, limits, settled_of(best_a), profile);
}

}  // namespace mjarm
