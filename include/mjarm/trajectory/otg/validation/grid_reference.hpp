#pragma once
/// @file
/// An independent check of the jerk-limited solvers, for validation (tests and
/// `mjarm bench otg`): does ANY motion of duration T take one DoF from a start state to a target
/// state within its limits? Decided numerically on a time grid, with none of the
/// profile-structure code: the jerk is piecewise constant on N equal steps (N unknowns in
/// [−j_max, j_max]); the end state is a linear function of them (three equality rows); velocity
/// and acceleration at every grid node are two-sided inequality rows. A dense QP (minimum
/// ‖jerk‖², qp/dense_qp.hpp) is feasible exactly when such a grid motion exists.
///
/// Grid-feasible implies truly feasible: the acceleration is linear within a step, so its
/// extremes are at the nodes; the velocity can bulge between nodes by at most j_max·h²/8, so the
/// velocity rows are tightened by that much. A feasible answer certifies that a motion of
/// duration T exists; an infeasible one says only that none with jerk switching on this grid
/// does (a finer grid gets closer to the true set).

#include "mjarm/trajectory/otg/profile.hpp"

namespace mjarm {

/// Whether a grid motion of @p duration [s] with @p steps equal jerk steps exists (see the
/// file). Allocates (a QP of @p steps variables per call): for validation, not for control.
/// @throws Error when @p steps < 1 or @p duration is not positive and finite.
bool grid_motion_exists(const KinematicState& start, const KinematicState& target,
                        const JerkLimits& limits, double duration, int steps);

}  // namespace mjarm
