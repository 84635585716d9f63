#pragma once
/// @file
/// The per-component pose acceptance test of the TRAC-IK benchmark protocol: the 6-D error of
/// the reached frame E, expressed in the TARGET frame T, must be within a bound on each of
/// x, y, z (m) and the three rotation-vector components "roll, pitch, yaw" (rad).
///
///     e_T = [R_WTᵀ·(p_WE − p_WT);  log(R_WTᵀ·R_WE)]   (6, frame T, linear first)
///
/// The rotation part is the rotation vector of R_TE (‖·‖ ≤ π), not Euler angles.

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Per-component bounds on the target-frame error e_T: [x, y, z] (m) then [roll, pitch, yaw]
/// (rad, rotation-vector components). The default 1e-5 everywhere is the TRAC-IK criterion.
struct PoseTolerance {
  Vector6d bound = Vector6d::Constant(1e-5);  ///< |e_T[i]| ≤ bound[i] for every i (> 0)

  /// The same bound on all six components (m for x, y, z; rad for the rotation).
  static PoseTolerance uniform(double value) noexcept {
    PoseTolerance t;
    t.bound.setConstant(value);
    return t;
  }
};

/// The 6-D error e_T of a reached pose X_WE against a target X_WT, expressed in T (see the file
/// comment): [R_WTᵀ(p_WE − p_WT); log(R_WTᵀ R_WE)] (m; rad).
Vector6d target_frame_error(const Pose& X_WE, const Pose& X_WT) noexcept;

/// True when every |e_T[i]| ≤ tolerance.bound[i] (false if e_T holds NaN).
bool within_tolerance(const Vector6d& e_T, const PoseTolerance& tolerance) noexcept;

/// @throws Error when a bound is not finite and positive.
void check_tolerance(const PoseTolerance& tolerance);

}  // namespace mjarm
