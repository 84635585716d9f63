#pragma once
// Allocation-free validation of a target pose for the IK solvers of this folder (the message is
// only built when the check fails, so per-step target updates stay allocation-free).

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::detail {

/// @throws Error naming @p what when the pose holds NaN/inf or its rotation is not orthonormal
/// with determinant +1 (to 1e-6).
inline void validate_pose(const Pose& X, const char* what) {
  if (!X.p.allFinite() || !X.R.allFinite()) {
    throw Error(std::string(what) + " holds NaN/inf");
  }
  const double orthogonality = (X.R.transpose() * X.R - Eigen::Matrix3d::Identity()).norm();
  const double det = X.R.determinant();
  if (!(orthogonality <= 1e-6) || !(std::abs(det - 1.0) <= 1e-6)) {
    throw Error(std::string(what) + " rotation is not a rotation matrix (‖RᵀR − I‖ = " +
                number_text(orthogonality) + ", det = " + number_text(det) + ")");
  }
}

/// @throws Error naming @p what when the position holds NaN/inf.
inline void validate_position(const Eigen::Vector3d& p, const char* what) {
  if (!p.allFinite()) throw Error(std::string(what) + " holds NaN/inf");
}

}  // namespace mjarm::detail
