#pragma once
/// @file
/// A rigid transform (element of SE(3)) stored as a rotation matrix and a translation.
///
/// Monogram notation: `X_AB` is the pose of frame B in frame A, made of `R_AB` (orientation of B
/// in A) and `p_AB` (position of B's origin in A, metres). Composition X_AC = X_AB * X_BC; a
/// point p_B expressed in B maps to p_A = X_AB.act(p_B) = R_AB p_B + p_AB.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mjarm {

/// Pose X_AB of a frame B in a frame A: x_A = R·x_B + p. A default-constructed Pose is identity.
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< rotation R_AB (3×3, orthonormal)
  Eigen::Vector3d p = Eigen::Vector3d::Zero();      ///< translation p_AB (m)

  /// The identity transform.
  static Pose identity() noexcept;

  /// From an Eigen isometry (its linear part is taken as the rotation as is).
  /// @throws mjarm::Error if a number is not finite (as every factory below: a NaN pose would
  ///         flow through every later computation without a word)
  static Pose from_isometry(const Eigen::Isometry3d& X);

  /// From a 4×4 homogeneous matrix [R p; 0 1] (the bottom row is ignored).
  /// @throws mjarm::Error if a number of R or p is not finite
  static Pose from_matrix(const Eigen::Matrix4d& M);

  /// From a position (m) and a quaternion (w, x, y, z), normalised first.
  /// @throws mjarm::Error if the quaternion is zero or not finite, or p is not finite
  static Pose from_quaternion(const Eigen::Vector3d& p, const Eigen::Vector4d& q_wxyz);

  /// From a position (m) and roll-pitch-yaw (rad), R = Rz(yaw)·Ry(pitch)·Rx(roll).
  /// @throws mjarm::Error if a number is not finite
  static Pose from_rpy(const Eigen::Vector3d& p, const Eigen::Vector3d& rpy);

  /// From a position (m) and a rotation vector φ (rad; axis·angle), R = exp([φ]×).
  /// @throws mjarm::Error if a number is not finite
  static Pose from_rotation_vector(const Eigen::Vector3d& p, const Eigen::Vector3d& phi);

  /// As an Eigen isometry.
  Eigen::Isometry3d to_isometry() const noexcept;

  /// As a 4×4 homogeneous matrix [R p; 0 1].
  Eigen::Matrix4d matrix() const noexcept;

  /// Inverse transform: (X_AB)⁻¹ = X_BA = [Rᵀ, −Rᵀp].
  Pose inverse() const noexcept;

  /// Maps a point from B to A: R·point + p (m).
  Eigen::Vector3d act(const Eigen::Vector3d& point) const noexcept;

  /// Rotates a free vector from B to A (no translation): R·vector.
  Eigen::Vector3d rotate(const Eigen::Vector3d& vector) const noexcept;

  /// Composition X_AC = X_AB * X_BC.
  Pose operator*(const Pose& X_BC) const noexcept;

  /// True when rotation and translation agree entrywise to within `tolerance` (absolute).
  bool is_approx(const Pose& other, double tolerance = 1e-12) const noexcept;
};

}  // namespace mjarm
