#pragma once
/// @file
/// The brake pre-trajectory of the jerk-limited generator: from a state whose acceleration
/// exceeds its limit, or whose velocity exceeds its limit or must exceed it (v + a·|a|/(2j) beyond
/// v_max: ramping the acceleration to zero at full jerk still overshoots), back into the states
/// from which a profile within the limits exists, as fast as full jerk and full acceleration
/// allow.

#include "mjarm/trajectory/jerk_limited_profile.hpp"

namespace mjarm {

/// True when a profile within @p limits can start at @p s: |a| ≤ a_max, |v| ≤ v_max and
/// |v + a·|a|/(2 j_max)| ≤ v_max (each with a relative slack of 1e-12).
bool is_startable(const KinematicState& s, const JerkLimits& limits) noexcept;

/// True when a profile within @p limits can end at @p s: |a| ≤ a_max, |v| ≤ v_max and
/// |v − a·|a|/(2 j_max)| ≤ v_max (the state was reached without overshooting).
bool is_reachable(const KinematicState& s, const JerkLimits& limits) noexcept;

/// Appends to @p profile (which must start at @p start and be empty) the brake phases that
/// bring @p start into an is_startable() state: full jerk towards the limit acceleration of the
/// braking direction, then a hold at that acceleration, and when that overshoots to the other
/// side (a deceleration far beyond its limit), one more such pass — at most 4 phases. Appends
/// nothing when @p start is already startable.
/// @return false when that does not suffice (limits where a²_max/(2 j_max) > 2 v_max, in which
/// braking to v_max already overshoots −v_max). Never allocates, never throws.
bool append_brake(const KinematicState& start, const JerkLimits& limits,
                  JerkProfile& profile) noexcept;

}  // namespace mjarm
