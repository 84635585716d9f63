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
};

/// Appends to @p profile (which must end at @p start) the brake of brake_family(@p start) that
/// minimizes its duration plus the minimum duration from its end to @p target under
/// @p solve_limits (the limits step 1 solves with; the brake keeps @p limits). The duration of a
/// member is a function of its settled velocity f_e on a bounded interval; it is minimized over
/// a grid of 8 members (uniform in the end acceleration −√(2j(v_max − f_e)), where the duration
/// varies smoothly), then by Brent's method between the best one's neighbours (an end of the
/// family the duration rises from is kept as is), and compared with append_brake()'s member,
/// which it never lengthens. A start with no choice gets append_brake(). @return false only when
/// @p profile is full.
/// Never allocates, never throws.
bool append_optimal_brake(const KinematicState& start, const KinematicState& target,
                          const JerkLimits& limits, const JerkLimits& solve_limits,
                          JerkProfile& profile, OptimalBrakeScratch& scratch) noexcept;

}  // namespace mjarm
