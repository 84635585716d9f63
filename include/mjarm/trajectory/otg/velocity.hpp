#pragma once
/// @file
/// The velocity interface of the jerk-limited generator for one DoF: reach a target velocity and
/// acceleration (position free) time-optimally under the acceleration and jerk limits, or in a
/// given duration (for synchronization).

#include "mjarm/trajectory/otg/block.hpp"
#include "mjarm/trajectory/otg/profile.hpp"

namespace mjarm {

/// The time-optimal profile from @p start to velocity @p v_target and acceleration @p a_target
/// under limits.acceleration and limits.jerk, and the blocked intervals of durations, in
/// @p block (the velocity limit is not a constraint of this interface; the targets must
/// respect it).
///
/// The extremal profiles take the acceleration from a₀ to a level u and on to a_f at full jerk,
/// with a plateau at a_max when the level would pass it: Δv = (2u² − a₀² − a_f²)/(2j) + u·h for
/// the rising form (u ≥ max(a₀, a_f), both signs of u), mirrored for the falling form. The
/// shortest valid one is optimal; with a₀ and a_f of one sign, the velocity gained while the
/// acceleration turns around can block a range of longer durations, found from the others as
/// in min_time_profile().
/// Preconditions: |start.a|, |a_target| ≤ a_max; limits positive. @return false only when no
/// form is valid (never for valid input). Never allocates, never throws.
bool min_time_velocity_profile(const KinematicState& start, double v_target, double a_target,
                               const JerkLimits& limits, JerkBlock& block) noexcept;

/// A profile of exactly @p duration [s] (≥ the minimum) to @p v_target, @p a_target: a rising
/// or falling level (a quadratic in u once the duration is fixed), or a monotone ramp from a₀ to
/// a_f with a hold at an intermediate level. @return false when none is valid.
bool fixed_time_velocity_profile(const KinematicState& start, double v_target, double a_target,
                                 const JerkLimits& limits, double duration,
                                 JerkProfile& profile) noexcept;

/// As fixed_time_velocity_profile(), but appends the phases to @p profile, which must end at
/// @p start and have room for 3 more phases (on failure nothing is appended).
bool append_fixed_time_velocity_profile(const KinematicState& start, double v_target,
                                        double a_target, const JerkLimits& limits, double duration,
                                        JerkProfile& profile) noexcept;

}  // namespace mjarm
