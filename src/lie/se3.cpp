#include "mjarm/lie/se3.hpp"

#include "mjarm/lie/coefficients.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm::se3 {

Eigen::Matrix4d hat(const Vector6d& xi) noexcept {
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  M.topLeftCorner<3, 3>() = so3::hat(xi.tail<3>());
  M.topRightCorner<3, 1>() = xi.head<3>();
  return M;
}

Vector6d vee(const Eigen::Matrix4d& xi_hat) noexcept {
  Vector6d xi;
  xi << xi_hat.topRightCorner<3, 1>(), so3::vee(xi_hat.topLeftCorner<3, 3>());
  return xi;
}

Pose exp(const Vector6d& xi) noexcept {
  const Eigen::Vector3d v = xi.head<3>();
  const Eigen::Vector3d w = xi.tail<3>();
  const lie::SeriesCoefficients k = lie::series_coefficients(w.norm());
  // R = I + sinc·ω̂ + a·ω̂², p = Jl(ω)·v = v + a·ω×v + b·ω×(ω×v)
  const Eigen::Matrix3d W = so3::hat(w);
  const Eigen::Matrix3d W2 = W * W;
  const Eigen::Vector3d wxv = w.cross(v);
  return Pose{Eigen::Matrix3d::Identity() + k.sinc * W + k.a * W2,
              v + k.a * wxv + k.b * w.cross(wxv)};
}

Vector6d log(const Pose& X) noexcept {
  const Eigen::Vector3d w = so3::log(X.R);
  // ‖ω‖ ≤ π here, inside the domain of Jl⁻¹ = I − ½ω̂ + e·ω̂²
  const lie::InverseCoefficients k = lie::inverse_coefficients(w.norm());
  const Eigen::Vector3d wxp = w.cross(X.p);
  Vector6d xi;
  xi << X.p - 0.5 * wxp + k.e * w.cross(wxp), w;
  return xi;
}

Matrix6d adjoint(const Pose& X_AB) noexcept {
  Matrix6d Ad;
  Ad.topLeftCorner<3, 3>() = X_AB.R;
  Ad.topRightCorner<3, 3>() = so3::hat(X_AB.p) * X_AB.R;
  Ad.bottomLeftCorner<3, 3>().setZero();
  Ad.bottomRightCorner<3, 3>() = X_AB.R;
  return Ad;
}

Matrix6d ad(const Vector6d& xi) noexcept {
  const Eigen::Matrix3d W = so3::hat(xi.tail<3>());
  Matrix6d m;
  m.topLeftCorner<3, 3>() = W;
  m.topRightCorner<3, 3>() = so3::hat(xi.head<3>());
  m.bottomLeftCorner<3, 3>().setZero();
  m.bottomRightCorner<3, 3>() = W;
  return m;
}

Matrix6d coadjoint(const Pose& X_AB) noexcept {
  Matrix6d m;
  m.topLeftCorner<3, 3>() = X_AB.R;
  m.topRightCorner<3, 3>().setZero();
  m.bottomLeftCorner<3, 3>() = so3::hat(X_AB.p) * X_AB.R;
  m.bottomRightCorner<3, 3>() = X_AB.R;
  return m;
}

Vector6d transform_twist(const Pose& X_AB, const Vector6d& V_B) noexcept {
  const Eigen::Vector3d w_A = X_AB.R * V_B.tail<3>();
  Vector6d V_A;
  V_A << X_AB.R * V_B.head<3>() + X_AB.p.cross(w_A), w_A;
  return V_A;
}

Vector6d transform_wrench(const Pose& X_AB, const Vector6d& F_B) noexcept {
  const Eigen::Vector3d f_A = X_AB.R * F_B.head<3>();
  Vector6d F_A;
  F_A << f_A, X_AB.R * F_B.tail<3>() + X_AB.p.cross(f_A);
  return F_A;
}

}  // namespace mjarm::se3
