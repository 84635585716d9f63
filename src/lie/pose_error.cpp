#include "mjarm/lie/pose_error.hpp"

#include "mjarm/lie/coefficients.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/se3_jacobian.hpp"

namespace mjarm {

Vector6d log_error(const Pose& X_WE, const Pose& X_WT) noexcept {
  // X_ET = X_EW·X_WT = [R_WEᵀ R_WT, R_WEᵀ (p_WT − p_WE)]
  const Eigen::Matrix3d R_EW = X_WE.R.transpose();
  return se3::log(Pose{R_EW * X_WT.R, R_EW * (X_WT.p - X_WE.p)});
}

Vector6d log_error_world_aligned(const Pose& X_WE, const Pose& X_WT) noexcept {
  const Vector6d e_E = log_error(X_WE, X_WT);
  Vector6d e_W;
  e_W << X_WE.R * e_E.head<3>(), X_WE.R * e_E.tail<3>();
  return e_W;
}

Matrix6d log_error_jacobian(const Vector6d& e_E) {
  lie::require_inverse_domain(e_E.tail<3>().norm(), "log_error_jacobian");
  return se3::left_jacobian_inverse(e_E);
}

Matrix6d log_error_world_aligned_jacobian(const Vector6d& e_W) {
  lie::require_inverse_domain(e_W.tail<3>().norm(), "log_error_world_aligned_jacobian");
  // angular columns: Jl⁻¹ + ad = Jr⁻¹
  Matrix6d J = se3::left_jacobian_inverse(e_W);
  J.rightCols<3>() += se3::ad(e_W).rightCols<3>();
  return J;
}

}  // namespace mjarm
