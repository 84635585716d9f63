#pragma once
/// @file
/// The brake pre-trajectory of the jerk-limited generator: from a state whose acceleration
/// exceeds its limit, or whose velocity exceeds its limit or must exceed it (v + a·|a|/(2j) beyond
/// v_max: ramping the acceleration to zero at full jerk still overshoots), back into the states
/// from which a profile within the limits exists, for any limits.

#include "mjarm/trajectory/otg/profile.hpp"

namespace mjarm {

/// True when a profile within @p limits can start at @p s: |a| ≤ a_max, |v| ≤ v_max and
/// |v + a·|a|/(2 j_max)| ≤ v_max (each with a relative slack of 1e-12).
bool is_startable(const KinematicState& s, const JerkLimits& limits) noexcept;

/// True when a profile within @p limits can end at @p s: |a| ≤ a_max, |v| ≤ v_max and
/// |v − a·|a|/(2 j_max)| ≤ v_max (the state was reached without overshooting).
bool is_reachable(const KinematicState& s, const JerkLimits& limits) noexcept;

/// Appends to @p profile (which must end at @p start) the brake phases that bring @p start into
/// an is_startable() state; appends nothing when it is startable already. With the settled
/// velocity f = v + a·|a|/(2j) (where a ramp of the acceleration to zero at full jerk ends):
/// - |f| ≤ v_max: that ramp, stopped as soon as |a| ≤ a_max and |v| ≤ v_max (f is constant along
///   it and v moves towards f);
/// - f > v_max (f < −v_max mirrored): a deceleration beyond −a_max ramps up to it first; then full
///   jerk down (v + a²/(2j) stays constant), a hold at −a_max when reached, and full jerk back up
///   (v − a²/(2j) stays constant, = f_e), timed so that the brake ends where v = v_max, with
///   f_e = max(v_max − a_max²/(2j), 0) — when a_max²/(2j) < v_max that is a hold at −a_max until
///   v = v_max; else the state then settles at rest velocity. A brake that held at −a_max until
///   v = v_max would overshoot −v_max afterwards when a_max²/(2j) > 2 v_max; this one never does.
/// At most 3 phases. @return false only when @p profile is full. Never allocates, never throws.
bool append_brake(const KinematicState& start, const JerkLimits& limits,
                  JerkProfile& profile) noexcept;

}  // namespace mjarm
