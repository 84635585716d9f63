#pragma once
/// @file
/// What every inverse-kinematics solver returns.

#include <Eigen/Core>

#include "mjarm/fields.hpp"

namespace mjarm {

/// How an IK solve ended.
enum class IkStatus {
  converged,      ///< every target within tolerance, joints within limits
  not_converged,  ///< iteration limit or stall: `q` is the best iterate found
  timeout,        ///< the time budget ran out: `q` is the best iterate found
  invalid_input   ///< a NaN appeared mid-solve (guarded): `q` is the last finite iterate
};

constexpr auto declared_names(const IkStatus*) {
  using S = IkStatus;
  return std::array{EnumName{S::converged, "converged", "every target within tolerance"},
                    EnumName{S::not_converged, "not_converged", "iteration limit or stall"},
                    EnumName{S::timeout, "timeout", "the time budget ran out"},
                    EnumName{S::invalid_input, "invalid_input", "a NaN appeared mid-solve"}};
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
