#pragma once
/// @file
/// Step 3 of the jerk-limited generator for one DoF: a profile of a given duration (at least the
/// DoF's minimum and outside its blocked intervals), used to synchronize it with the others.

#include "mjarm/trajectory/otg/profile.hpp"
#include "mjarm/trajectory/otg/reach.hpp"

namespace mjarm {

/// A jerk-limited profile of exactly @p duration [s] from @p start to @p target, in @p profile.
///
/// The profiles of one duration that end at the target velocity and acceleration form a convex
/// set, and their end positions fill the interval [p_min, p_max] of otg/reach.hpp. When
/// the target position lies in it, the blend λ·(profile to p_max) + (1 − λ)·(profile to p_min)
/// with λ = (p_f − p_min)/(p_max − p_min) — jerk blended phase by phase over the union of both
/// profiles' switching times, at most 13 phases — reaches it: its velocity and acceleration are
/// the same blend of two motions within the limits, so they stay within them, and its jerk is
/// within ±j_max. This finds a profile for every duration that has one, with no case left
/// uncovered. For a rest-to-rest move it is the time-optimal profile of the longer duration
/// scaled down (the classic synchronization by scaling).
///
/// Preconditions as min_time_profile(). @return false when no profile of that duration exists
/// (below the minimum or inside a blocked interval). Never allocates, never throws.
bool fixed_time_profile(const KinematicState& start, const KinematicState& target,
                        const JerkLimits& limits, double duration, JerkProfile& profile) noexcept;

/// As fixed_time_profile(), but appends the phases to @p profile, which must end at @p start
/// (after a brake, say) and have room for 13 more phases. On failure @p profile may hold some of
/// the phases.
bool append_fixed_time_profile(const KinematicState& start, const KinematicState& target,
                               const JerkLimits& limits, double duration,
                               JerkProfile& profile) noexcept;

/// The blend of fixed_time_profile() from @p reach, computed already for @p duration [s] and the
/// target's velocity and acceleration, appended to @p profile (which must end at the start of
/// @p reach). False when @p target.p is out of reach or the profile is full.
bool append_blended_profile(const JerkReach& reach, const KinematicState& target, double duration,
                            JerkProfile& profile) noexcept;

}  // namespace mjarm
