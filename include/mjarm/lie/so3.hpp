#pragma once
/// @file
/// The rotation group SO(3): hat/vee, exponential map (Rodrigues) and logarithm.
///
/// A rotation vector ω ∈ ℝ³ (rad) is an axis times an angle θ = ‖ω‖; exp(ω) = exp(ω̂) is the
/// rotation by θ about ω/θ. log is its inverse on ‖ω‖ ≤ π (principal branch). Both are accurate
/// to machine precision near θ = 0 (Taylor series) and near θ = π (log goes through a unit
/// quaternion extracted with the largest-pivot method, never through acos of the trace).
///
/// The functions here are the arithmetic of the hot loops: they check nothing (NaN in, NaN
/// out). Numbers from users are checked where they enter (the `Pose` factories, the IK targets
/// and controller references, the Python bindings).

#include <Eigen/Core>

namespace mjarm::so3 {

/// Skew-symmetric matrix ω̂ with ω̂·u = ω × u.
/// @param w 3-vector (any units; the result carries them)
/// @return 3×3 skew-symmetric matrix
Eigen::Matrix3d hat(const Eigen::Vector3d& w) noexcept;

/// Inverse of hat: the vector of the skew-symmetric part of `W`, ½(W − Wᵀ)∨.
/// For an exactly skew-symmetric `W` this is the ω with ω̂ = W.
/// @param W 3×3 matrix
/// @return 3-vector
Eigen::Vector3d vee(const Eigen::Matrix3d& W) noexcept;

/// Exponential map so(3) → SO(3) (Rodrigues): R = I + (sin θ/θ) ω̂ + ((1 − cos θ)/θ²) ω̂².
/// @param w rotation vector (rad), any norm
/// @return rotation matrix R (3×3, orthonormal, det +1)
Eigen::Matrix3d exp(const Eigen::Vector3d& w) noexcept;

/// Logarithm SO(3) → so(3), principal branch: the ω with exp(ω) = R and ‖ω‖ ≤ π.
/// At exactly θ = π both ±ω are valid; one of them is returned.
/// @param R rotation matrix (3×3, orthonormal); small deviations from orthonormality are
///          tolerated (the nearest unit quaternion is used)
/// @return rotation vector (rad), ‖ω‖ ∈ [0, π]
Eigen::Vector3d log(const Eigen::Matrix3d& R) noexcept;

/// Rotation angle of R, θ = ‖log(R)‖ ∈ [0, π] (rad), computed without acos.
/// @param R rotation matrix (3×3)
double angle(const Eigen::Matrix3d& R) noexcept;

}  // namespace mjarm::so3
