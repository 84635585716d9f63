#pragma once
/// @file
/// The brake of the jerk-limited generator chosen for the whole motion: of the family of brakes a
/// start beyond its velocity limit may take (otg/brake.hpp, `brake_family`), the member after
/// which the brake and the time-optimal profile from its end (step 1) are shortest together.

#include "mjarm/trajectory/otg/block.hpp"
#include "mjarm/trajectory/otg/profile.hpp"

namespace mjarm {

/// Scratch storage of append_optimal_brake() (a profile and a block: no allocation per call).
struct OptimalBrakeScratch {
  JerkProfile profile;
  JerkBlock block;
  JerkBlock velocity;  ///< the velocity's extremal motions from a member's end (its edges)
};

/// Appends to @p profile (which must end at @p start) the brake of brake_family(@p start) that
/// minimizes its duration plus the minimum duration from its end to @p target under
/// @p solve_limits (the limits step 1 solves with; the brake keeps @p limits). The duration of a
/// member is a function of its end acceleration −√(2j(v_max − f_e)) on a bounded interval that
/// jumps where an island of short durations opens or closes. The islands located are those of a
/// window of durations bounded by the motions of the velocity alone from the member's end (to
/// the target's velocity and acceleration: its minimum, the ends of the interval it blocks):
/// their edges lie where one of those motions passes the target position (located to 1e-11 of
/// the interval) after their number changed (located to 1e-7). The duration is evaluated on a
/// grid of 8 members and on both sides of every such edge between them, then minimized by Brent's
/// method between the best one's neighbours (an end of the family the duration rises from is kept
/// as is), and compared with append_brake()'s member, which it never lengthens. A start with no
/// choice gets append_brake(). @return false only when @p profile is full. Never allocates, never
/// throws.
bool append_optimal_brake(const KinematicState& start, const KinematicState& target,
                          const JerkLimits& limits, const JerkLimits& solve_limits,
                          JerkProfile& profile, OptimalBrakeScratch& scratch) noexcept;

}  // namespace mjarm
