#pragma once
/// @file
/// Step 3 of the jerk-limited generator for one DoF: a profile of a given duration (longer than
/// the DoF's minimum and outside its blocked intervals), used to synchronize it with the others.

#include "mjarm/trajectory/jerk_limited_profile.hpp"

namespace mjarm {

/// A jerk-limited profile of exactly @p duration [s] from @p start to @p target, in @p profile.
///
/// Structures tried, in both directions (all states negated for the other):
/// - a cruise at a free velocity v_c with zero acceleration (phase 4), reached by jerk +j then
///   −j (with a plateau at +a_max when needed) and left by −j then +j or by +j then −j (each
///   with an optional plateau at the limit): one unknown once the duration is fixed;
/// - no cruise, jerk (+j, −j, +j) with a constant-acceleration hold at a free level after the
///   first or after the second ramp.
/// - a reduced jerk (+j_r, −j_r, +j_r), j_r ≤ j_max;
/// - when the target (start) is at rest and nothing above fits: the time-optimal profile with a
///   rest after (before) it.
/// Each reduces to a polynomial in one unknown (degree ≤ 8); the valid profile found first is
/// returned (every valid one has the requested duration; they differ in shape only).
///
/// Preconditions as min_time_profile(). @return false when no structure gives a valid profile
/// (the duration is then below the minimum, inside a blocked interval, or in a case the
/// structures above do not cover). Never allocates, never throws.
bool fixed_time_profile(const KinematicState& start, const KinematicState& target,
                        const JerkLimits& limits, double duration, JerkProfile& profile) noexcept;

}  // namespace mjarm
