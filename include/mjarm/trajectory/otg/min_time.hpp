#pragma once
/// @file
/// Step 1 of the jerk-limited generator for one DoF: the time-optimal profile from a state within
/// the limits to a target state, every other extremal profile, and the blocked intervals of
/// durations.

#include "mjarm/trajectory/otg/block.hpp"
#include "mjarm/trajectory/otg/profile.hpp"

namespace mjarm {

/// Tolerances of the profile solvers.
struct JerkTolerance {
  /// A profile counts as reaching the target when |Δp|, |Δv|, |Δa| at its end are each below
  /// this times max(1, |target value|) — for the position, times max(1, the largest position
  /// magnitude the computation involves: start, target, the reachable extremes), since double
  /// precision cannot place an end closer than its round-off (a move over 10⁶ units, say).
  static constexpr double kTarget = 1e-9;
  /// A profile counts as within the limits when every extremum is within (1 + this)·limit.
  static constexpr double kLimits = 1e-12;
};

/// The time-optimal jerk-limited profile of one DoF from @p start to @p target, every other
/// extremal profile, and the blocked intervals of durations, in @p block.
///
/// The durations a DoF can take are those T for which the target position lies in the interval
/// of positions reachable at T (otg/reach.hpp); its ends are reached by the seven-phase
/// profiles with jerk (+j, 0, −j, 0, −j, 0, +j) and holds on the limits, in either direction. So
/// the ends of the feasible set of durations are the durations of those profiles that reach the
/// target position. Each structure is solved in closed form or from a polynomial of degree ≤ 4:
/// - a cruise at v_max: the rise and the fall in closed form, the cruise closes the distance;
/// - holds at +a_max and −a_max, no cruise: a quadratic in the second hold's length;
/// - a hold at +a_max only: a quartic in the lowest acceleration w (−a_max: the same for the
///   time-reversed problem);
/// - no hold: a quartic in w, the peak u = (w³ + F·w + E/3)/(w² + M).
/// Every root becomes a profile, kept when its durations are ≥ 0, it stays within the limits
/// (checked at its analytic extrema) and reaches the target (JerkTolerance). The shortest is the
/// optimum; between two consecutive durations found, the interval is blocked when the target
/// position is out of reach at its midpoint.
///
/// Preconditions (checked by the generator, not here): limits positive and finite; the start
/// startable and the target reachable (otg/brake.hpp), all finite.
/// @return false when no structure gives a valid profile (the block is then unspecified).
/// Never allocates, never throws.
bool min_time_profile(const KinematicState& start, const KinematicState& target,
                      const JerkLimits& limits, JerkBlock& block) noexcept;

/// True when @p profile from phase @p first_phase on ends at @p target (JerkTolerance::kTarget)
/// and keeps @p limits (JerkTolerance::kLimits).
bool reaches_within_limits(const JerkProfile& profile, const KinematicState& target,
                           const JerkLimits& limits, int first_phase = 0) noexcept;

}  // namespace mjarm
