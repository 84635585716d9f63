#include "mjarm/lie/pose.hpp"

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

// the factories' inputs: a NaN or inf there would come out of every later product unnoticed
template <class Derived>
void check_pose_input(const Eigen::MatrixBase<Derived>& values, const char* factory,
                      const char* what) {
  for (Eigen::Index c = 0; c < values.cols(); ++c)
    for (Eigen::Index r = 0; r < values.rows(); ++r)
      if (!std::isfinite(values(r, c)))
        throw Error(std::string("Pose::") + factory + ": " + what + " holds " +
                    number_text(values(r, c)) + "; expected finite numbers");
}

}  // namespace

Pose Pose::identity() noexcept { return Pose{}; }

Pose Pose::from_isometry(const Eigen::Isometry3d& X) {
  check_pose_input(X.linear(), "from_isometry", "the rotation");
  check_pose_input(X.translation(), "from_isometry", "the translation");
  return Pose{X.linear(), X.translation()};
}

Pose Pose::from_matrix(const Eigen::Matrix4d& M) {
  check_pose_input(M.topLeftCorner<3, 3>(), "from_matrix", "R");
  check_pose_input(M.topRightCorner<3, 1>(), "from_matrix", "p");
  return Pose{M.topLeftCorner<3, 3>(), M.topRightCorner<3, 1>()};
}

Pose Pose::from_quaternion(const Eigen::Vector3d& p, const Eigen::Vector4d& q_wxyz) {
  check_pose_input(p, "from_quaternion", "p");
  return Pose{rotation_from_quaternion(q_wxyz), p};
}

Pose Pose::from_rotation_vector(const Eigen::Vector3d& p, const Eigen::Vector3d& phi) {
  check_pose_input(p, "from_rotation_vector", "p");
  check_pose_input(phi, "from_rotation_vector", "phi");
  return Pose{so3::exp(phi), p};
}

Pose Pose::from_rpy(const Eigen::Vector3d& p, const Eigen::Vector3d& rpy) {
  check_pose_input(p, "from_rpy", "p");
  check_pose_input(rpy, "from_rpy", "rpy");
  return Pose{rotation_from_rpy(rpy), p};
}

Eigen::Isometry3d Pose::to_isometry() const noexcept {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

Eigen::Matrix4d Pose::matrix() const noexcept {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M.topLeftCorner<3, 3>() = R;
  M.topRightCorner<3, 1>() = p;
  return M;
}

Pose Pose::inverse() const noexcept {
  const Eigen::Matrix3d Rt = R.transpose();
  return Pose{Rt, -(Rt * p)};
}

Eigen::Vector3d Pose::act(const Eigen::Vector3d& point) const noexcept { return R * point + p; }

Eigen::Vector3d Pose::rotate(const Eigen::Vector3d& vector) const noexcept { return R * vector; }

Pose Pose::operator*(const Pose& X_BC) const noexcept { return Pose{R * X_BC.R, R * X_BC.p + p}; }

bool Pose::is_approx(const Pose& other, double tolerance) const noexcept {
  return (R - other.R).cwiseAbs().maxCoeff() <= tolerance &&
         (p - other.p).cwiseAbs().maxCoeff() <= tolerance;
}

}  // namespace mjarm
