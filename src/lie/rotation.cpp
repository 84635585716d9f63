#include "mjarm/lie/rotation.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

Eigen::Matrix3d rotation_from_quaternion(const Eigen::Vector4d& q_wxyz) {
  const double n = q_wxyz.norm();
  if (!std::isfinite(n) || n < 1e-12) {
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer), "(%.17g, %.17g, %.17g, %.17g)", q_wxyz(0), q_wxyz(1),
                  q_wxyz(2), q_wxyz(3));
    throw Error(std::string("rotation_from_quaternion: quaternion (w, x, y, z) = ") + buffer +
                " cannot be normalised; expected a finite quaternion with norm >= 1e-12");
  }
  const Eigen::Quaterniond q(q_wxyz(0) / n, q_wxyz(1) / n, q_wxyz(2) / n, q_wxyz(3) / n);
  return q.toRotationMatrix();
}

Eigen::Matrix3d rotation_from_quaternion(double w, double x, double y, double z) {
  return rotation_from_quaternion(Eigen::Vector4d(w, x, y, z));
}

Eigen::Vector4d quaternion_from_rotation(const Eigen::Matrix3d& R) noexcept {
  Eigen::Quaterniond q(R);
  q.normalize();
  // the double cover: pick the representative with non-negative scalar part
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  return sign * Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
}

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) noexcept {
  const double cr = std::cos(roll), sr = std::sin(roll);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  Eigen::Matrix3d R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      -sp, cp * sr, cp * cr;
  return R;
}

Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy) noexcept {
  return rotation_from_rpy(rpy(0), rpy(1), rpy(2));
}

Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R) noexcept {
  // cos(pitch) from the first column is >= 0; atan2 keeps pitch accurate near ±π/2
  const double cp = std::hypot(R(0, 0), R(1, 0));
  const double pitch = std::atan2(-R(2, 0), cp);
  // roll alone is ill-conditioned near gimbal lock (entries scale with cos(pitch)); at exact
  // lock only yaw ∓ roll is defined and roll is set to 0
  const double roll = cp < 1e-12 ? 0.0 : std::atan2(R(2, 1), R(2, 2));
  // yaw ∓ roll comes from O(1) entries of the upper-right 2×2 block:
  //   R12 − R01 = (1 + sin p) sin(y − r),  R11 + R02 = (1 + sin p) cos(y − r)
  //   R12 + R01 = −(1 − sin p) sin(y + r), R11 − R02 = (1 − sin p) cos(y + r)
  // pick the pair whose factor is >= 1, so R is reproduced to rounding even near lock
  double yaw;
  if (R(2, 0) <= 0.0) {  // sin(pitch) >= 0
    yaw = roll + std::atan2(R(1, 2) - R(0, 1), R(1, 1) + R(0, 2));
  } else {
    yaw = std::atan2(-(R(1, 2) + R(0, 1)), R(1, 1) - R(0, 2)) - roll;
  }
  return Eigen::Vector3d(roll, pitch, std::remainder(yaw, 2.0 * std::numbers::pi));
}

}  // namespace mjarm
