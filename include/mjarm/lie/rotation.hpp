#pragma once
/// @file
/// Conversions between rotation matrices, unit quaternions (w, x, y, z) and roll-pitch-yaw.
///
/// Quaternions are stored as Eigen::Vector4d in (w, x, y, z) order, the order MuJoCo uses.
/// Roll-pitch-yaw (rad) are extrinsic X-Y-Z angles: R = Rz(yaw)·Ry(pitch)·Rx(roll), i.e. first
/// roll about the fixed x axis, then pitch about the fixed y axis, then yaw about the fixed z.

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace mjarm {

/// Rotation matrix of a quaternion; the quaternion is normalised first.
/// @param q_wxyz quaternion (w, x, y, z), any non-zero finite norm
/// @return rotation matrix (3×3)
/// @throws mjarm::Error if the quaternion is zero (norm < 1e-12) or not finite
Eigen::Matrix3d rotation_from_quaternion(const Eigen::Vector4d& q_wxyz);

/// Same as rotation_from_quaternion(Vector4d(w, x, y, z)).
/// @throws mjarm::Error if the quaternion is zero (norm < 1e-12) or not finite
Eigen::Matrix3d rotation_from_quaternion(double w, double x, double y, double z);

/// Unit quaternion of a rotation matrix, canonicalised to w ≥ 0 (largest-pivot method, accurate
/// at every angle).
/// @param R rotation matrix (3×3, orthonormal)
/// @return quaternion (w, x, y, z), unit norm, w ≥ 0
Eigen::Vector4d quaternion_from_rotation(const Eigen::Matrix3d& R) noexcept;

/// Rotation matrix R = Rz(yaw)·Ry(pitch)·Rx(roll) (extrinsic X-Y-Z).
/// @param roll  angle about the fixed x axis (rad)
/// @param pitch angle about the fixed y axis (rad)
/// @param yaw   angle about the fixed z axis (rad)
Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) noexcept;

/// Same as rotation_from_rpy(rpy(0), rpy(1), rpy(2)). @param rpy (roll, pitch, yaw) (rad)
Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy) noexcept;

/// Roll-pitch-yaw of R with R = Rz(yaw)·Ry(pitch)·Rx(roll).
/// Ranges: roll, yaw ∈ [−π, π], pitch ∈ [−π/2, π/2]. Near gimbal lock (|pitch| → π/2) roll and
/// yaw separately are ill-conditioned but yaw ∓ roll is not; yaw is computed from yaw ∓ roll so
/// that rotation_from_rpy(rpy_from_rotation(R)) reproduces R to rounding at every pitch. At
/// exact lock (cos(pitch) < 1e-12) roll is set to 0 and the whole rotation about z goes to yaw.
/// @param R rotation matrix (3×3, orthonormal)
/// @return (roll, pitch, yaw) (rad)
Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R) noexcept;

/// @p angle wrapped into [−π, π] (the nearest equivalent angle: `std::remainder` by 2π, exact);
/// NaN for NaN or ±infinity.
inline double wrap_to_pi(double angle) noexcept {
  return std::remainder(angle, 2.0 * std::numbers::pi);
}

}  // namespace mjarm
