#include "mjarm/ik/targets.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/pose_error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

FrameErrors frame_errors(const Pose& X_WE, const Pose& X_WT) noexcept {
  FrameErrors errors;
  errors.position = (X_WT.p - X_WE.p).norm();
  errors.orientation = so3::angle(X_WE.R.transpose() * X_WT.R);
  return errors;
}

Matrix6d log_jacobian_times_local(const Matrix6d& J_log, const Eigen::Matrix3d& R_WE) noexcept {
  Matrix6d M;
  M.leftCols<3>().noalias() = J_log.leftCols<3>() * R_WE.transpose();
  M.rightCols<3>().noalias() = J_log.rightCols<3>() * R_WE.transpose();
  return M;
}

void check_position_target(const Eigen::Vector3d& p_WT, std::string_view what) {
  if (!p_WT.allFinite()) {
    throw Error(std::string(what) + " must be finite, got [" + number_text(p_WT.x()) + ", " +
                number_text(p_WT.y()) + ", " + number_text(p_WT.z()) + "] m");
  }
}

bool is_valid_pose(const Pose& X_WT) noexcept {
  if (!X_WT.p.allFinite() || !X_WT.R.allFinite()) return false;
  const double orthogonality = (X_WT.R.transpose() * X_WT.R - Eigen::Matrix3d::Identity()).norm();
  return orthogonality <= 1e-6 && X_WT.R.determinant() > 0.0;
}

void check_pose_target(const Pose& X_WT, std::string_view what) {
  // messages are built only on failure: the check runs on every solve
  if (is_valid_pose(X_WT)) return;
  if (!X_WT.p.allFinite()) check_position_target(X_WT.p, std::string(what) + " position");
  if (!X_WT.R.allFinite()) throw Error(std::string(what) + " rotation holds NaN/inf");
  const double orthogonality = (X_WT.R.transpose() * X_WT.R - Eigen::Matrix3d::Identity()).norm();
  if (orthogonality > 1e-6 || X_WT.R.determinant() <= 0.0) {
    throw Error(std::string(what) +
                " rotation is not a rotation matrix (‖RᵀR − I‖ = " + number_text(orthogonality) +
                ", det = " + number_text(X_WT.R.determinant()) + ")");
  }
}

void check_weights(const FrameTarget& target) {
  const auto positive = [](double w) { return std::isfinite(w) && w > 0.0; };
  if (!positive(target.position_weight) || !positive(target.orientation_weight)) {
    throw Error("target on '" + target.frame + "' needs finite positive weights, got position " +
                number_text(target.position_weight) + " and orientation " +
                number_text(target.orientation_weight));
  }
}

FrameErrors evaluate_target(const ChainKinematics& kin, TargetKind kind, const Pose& X_WT,
                            Eigen::Ref<Eigen::VectorXd> e, Eigen::Ref<Eigen::MatrixXd> J_task,
                            Eigen::Ref<Matrix6Xd> J_scratch) noexcept {
  const Pose& X_WE = kin.pose();
  if (kind == TargetKind::position) {
    e = X_WT.p - X_WE.p;
    kin.jacobian(J_scratch, JacobianFrame::world_aligned);
    J_task = J_scratch.topRows<3>();
    return FrameErrors{e.norm(), 0.0};
  }
  const Vector6d e_E = log_error(X_WE, X_WT);
  e = e_E;
  // world-aligned Jacobian rotated into E inside the 6×6 factor (no temporary); the log error's
  // rotation part never exceeds π, far inside Jlog's domain (‖ω‖ < 2π); a non-finite error is
  // left for the caller's NaN guard
  kin.jacobian(J_scratch, JacobianFrame::world_aligned);
  const Matrix6d J_log = e_E.allFinite() ? log_error_jacobian(e_E) : Matrix6d::Identity();
  J_task.noalias() = log_jacobian_times_local(J_log, X_WE.R) * J_scratch;
  return FrameErrors{(X_WT.p - X_WE.p).norm(), e_E.tail<3>().norm()};
}

}  // namespace mjarm
