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

/// The brakes a start beyond its velocity limit may take (docs/trajectory_otg.md, "Brake"): seen
/// on the side s of the violation (s = sign(f) when |f| > v_max, else sign(v)), after the forced
/// ramp of an acceleration beyond its limit, full jerk down (−s·j), a hold at −s·a_max, and one
/// release at full jerk up (+s·j), ending where the state becomes startable: at s·v = v_max with
/// the settled velocity s·(v − a²/(2j)) = f_e. The members differ by f_e ∈ [lowest, highest].
struct BrakeFamily {
  double side = 0.0;     ///< s; 0 when the start has no choice (startable, or only a beyond)
  double lowest = 0.0;   ///< the lowest f_e (the release as late as allowed) [u/s]
  double highest = 0.0;  ///< the highest f_e (the release as early as allowed) [u/s]
};

/// The family of brakes from @p start (side 0 when append_brake() is the only brake).
BrakeFamily brake_family(const KinematicState& start, const JerkLimits& limits) noexcept;

/// Appends to @p profile (which must end at @p start) the member of brake_family(start) whose
/// settled velocity is @p settled (clamped into [lowest, highest]); append_brake() when the
/// family has side 0. @return false only when @p profile is full.
bool append_brake_member(const KinematicState& start, const JerkLimits& limits, double settled,
                         JerkProfile& profile) noexcept;

}  // namespace mjarm
