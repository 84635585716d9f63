#pragma once
/// @file
/// The positions one DoF can reach at a given time: from a start state, every jerk-limited
/// motion of duration T that ends at velocity v_f and acceleration a_f within the limits ends at
/// a position in an interval [p_min(T), p_max(T)] — the motions form a convex set (the limits
/// are convex, the end state is linear in the jerk), and the end position is linear in them.
///
/// The highest position is reached by the "up" profile of seven phases with jerk (+j, 0, −j, 0,
/// −j, 0, +j) whose holds sit on the limits (acceleration +a_max, velocity +v_max, acceleration
/// −a_max): Pontryagin's principle for a linear objective makes the jerk +j, −j, +j between
/// the constraint arcs. Once T is fixed, each structure is closed form:
/// - no hold: u − w = S = (J·T + a₀ − a_f)/2 and u² − w² = K, so u + w = K/S
///   (u, w the two acceleration levels; K = J·(v_f − v₀) + (a₀² − a_f²)/2);
/// - hold at +a_max: w² − 2A·w + K + A² − A·J·T + A·(a_f − a₀) = 0;
/// - hold at −a_max: the same for the time-reversed problem;
/// - holds at both: two linear equations in the two hold lengths;
/// - a cruise at +v_max: the rise to (v_max, 0) and the fall from it in closed form, the cruise
///   takes the rest of T.
/// The lowest position is the mirror image. Step 3 of the generator blends the two
/// (otg/fixed_time.hpp); step 1 uses the interval to tell blocked intervals of durations
/// from free ones (otg/min_time.hpp).

#include "mjarm/trajectory/otg/profile.hpp"

namespace mjarm {

/// The interval of positions reachable at one time, with the profiles that reach its ends.
struct JerkReach {
  double p_min = 0.0;  ///< lowest reachable position [u]
  double p_max = 0.0;  ///< highest reachable position [u]
  JerkPhases lowest;   ///< a profile ending at p_min
  JerkPhases highest;  ///< a profile ending at p_max
};

/// The positions reachable from @p start in exactly @p duration [s] with final velocity
/// @p v_target and acceleration @p a_target within @p limits, in @p reach.
/// Preconditions as min_time_profile(). @return false when no motion of that duration reaches
/// (v_target, a_target) at all. Never allocates, never throws.
bool reach_range(const KinematicState& start, double v_target, double a_target,
                 const JerkLimits& limits, double duration, JerkReach& reach) noexcept;

/// True when @p position lies in [p_min, p_max] of @p reach, to the target tolerance
/// (JerkTolerance::kTarget relative to max(1, |position|)).
bool reach_contains(const JerkReach& reach, double position) noexcept;

/// True when a profile of exactly @p duration [s] from @p start to @p target exists:
/// reach_range() holds target.p, to the target tolerance (JerkTolerance::kTarget).
bool duration_feasible(const KinematicState& start, const KinematicState& target,
                       const JerkLimits& limits, double duration) noexcept;

}  // namespace mjarm
