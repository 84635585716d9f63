#pragma once
/// @file
/// What every inverse-kinematics solver returns.

#include <Eigen/Core>

namespace mjarm {

/// How an IK solve ended.
enum class IkStatus {
  converged,      ///< every target within tolerance, joints within limits
  not_converged,  ///< iteration limit or stall: `q` is the best iterate found
  timeout,        ///< the time budget ran out: `q` is the best iterate found
  invalid_input   ///< a NaN appeared mid-solve (guarded): `q` is the last finite iterate
};

/// Human name of a status ("converged", ...).
constexpr const char* to_string(IkStatus status) noexcept {
  switch (status) {
    case IkStatus::converged: return "converged";
    case IkStatus::not_converged: return "not_converged";
    case IkStatus::timeout: return "timeout";
    case IkStatus::invalid_input: return "invalid_input";
  }
  return "unknown";
}

/// The outcome of an IK solve: always the best configuration found, with its errors.
struct IkResult {
  Eigen::VectorXd q;               ///< joint values in chain order (n)
  IkStatus status = IkStatus::not_converged;
  double position_error = 0.0;     ///< ‖p_target − p‖ [m] (worst target for multi-target)
  double orientation_error = 0.0;  ///< rotation angle between target and achieved [rad]
  int iterations = 0;              ///< iterations run (all restarts together)
  bool ok() const noexcept { return status == IkStatus::converged; }
};

}  // namespace mjarm
