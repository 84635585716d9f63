#pragma once
/// @file
/// Step 1 of the jerk-limited generator for one DoF: the time-optimal profile from a state within
/// the limits to a target state, and the blocked intervals of durations.

#include "mjarm/trajectory/jerk_limited_block.hpp"
#include "mjarm/trajectory/jerk_limited_profile.hpp"

namespace mjarm {

/// Tolerances of the profile solvers.
struct JerkTolerance {
  /// A profile counts as reaching the target when |Δp|, |Δv|, |Δa| at its end are each below
  /// this times max(1, |target value|).
  static constexpr double kTarget = 1e-9;
  /// A profile counts as within the limits when every extremum is within (1 + this)·limit.
  static constexpr double kLimits = 1e-12;
};

/// The time-optimal jerk-limited profile of one DoF from @p start to @p target, and the blocked
/// intervals of durations, in @p block.
///
/// Enumerates the seven-phase structures with jerk (+j, 0, −j, 0, −j, 0, +j) in both directions
/// — each constant-jerk phase either absent or on a limit: acceleration at ±a_max in phases 2 and
/// 6, velocity at ±v_max in phase 4 — solves each structure's equations (closed form with a
/// velocity plateau; otherwise a polynomial of degree ≤ 8 in one unknown, see
/// jerk_limited_roots.hpp), and keeps the profiles whose phase durations are ≥ 0, that stay
/// within the limits (checked at the analytic extrema) and reach the target. The shortest is the
/// optimum.
///
/// Preconditions (checked by the generator, not here): limits positive and finite; the start
/// and the target within the limits (|v| ≤ v_max, |a| ≤ a_max), all finite.
/// @return false when no structure gives a valid profile (the block is then unspecified).
/// Never allocates, never throws.
bool min_time_profile(const KinematicState& start, const KinematicState& target,
                      const JerkLimits& limits, JerkBlock& block) noexcept;

/// True when @p profile starts at @p start, ends at @p target (JerkTolerance::kTarget) and keeps
/// @p limits (JerkTolerance::kLimits).
bool reaches_within_limits(const JerkProfile& profile, const KinematicState& target,
                           const JerkLimits& limits) noexcept;

}  // namespace mjarm
