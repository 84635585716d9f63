#pragma once
/// @file
/// IK targets for a frame of a chain: what is asked (a position or a full pose), how it is
/// weighted and prioritised, and its residual and task Jacobian for the local solvers.
///
/// Residual conventions (both vanish exactly at the target, and J_task·Δq ≈ e(q) − e(q + Δq)):
/// - position: e = p_WT − p_WE (3, world axes, m), J_task = rows 0..2 of the world-aligned
///   Jacobian J_{E[W]};
/// - pose: the body log error e = log(X_WE⁻¹·X_WT) = [v; ω] (6, frame E, m and rad) and
///   J_task = Jlog(e)·J_E, with Jlog = dexp⁻¹(e) (lie/pose_error.hpp) and J_E the local (body)
///   Jacobian, because ė = −Jlog(e)·V_E for a body twist V_E = J_E·q̇.

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/pose.hpp"

namespace mjarm {

/// What a target constrains.
enum class TargetKind {
  position,  ///< the frame origin only (3 rows)
  pose       ///< origin and orientation (6 rows)
};

constexpr auto declared_names(const TargetKind*) {
  using K = TargetKind;
  return std::array{EnumName{K::position, "position", "the frame origin only (3 rows)"},
                    EnumName{K::pose, "pose", "origin and orientation (6 rows)"}};
}

/// Number of task rows of a target kind: 3 (position) or 6 (pose).
constexpr int task_rows(TargetKind kind) noexcept { return kind == TargetKind::position ? 3 : 6; }

/// A target for one frame (site or body) moved by a chain's joints.
struct FrameTarget {
  std::string frame;                   ///< site or body name
  TargetKind kind = TargetKind::pose;  ///< what is constrained
  Pose X_WT;                           ///< target pose in W (position targets use X_WT.p only)
  double position_weight = 1.0;        ///< row weight of the position error (> 0)
  double orientation_weight = 1.0;     ///< row weight of the orientation error (> 0, pose only)
  int priority = 0;                    ///< 0 is the most important; equal priorities are stacked
};

/// Position and orientation distance between a frame and its target.
struct FrameErrors {
  double position = 0.0;     ///< ‖p_WT − p_WE‖ [m]
  double orientation = 0.0;  ///< angle of R_WE⁻¹·R_WT [rad], in [0, π]
};

/// Distances between the pose X_WE of a frame and its target X_WT.
FrameErrors frame_errors(const Pose& X_WE, const Pose& X_WT) noexcept;

/// @throws Error naming @p what when the position holds NaN/inf.
void check_position_target(const Eigen::Vector3d& p_WT, std::string_view what = "target position");

/// True when @p X_WT is finite and its rotation is orthonormal with determinant +1 (to 1e-6).
bool is_valid_pose(const Pose& X_WT) noexcept;

/// @throws Error naming @p what when the pose holds NaN/inf or its rotation is not orthonormal
/// with determinant +1 (to 1e-6).
void check_pose_target(const Pose& X_WT, std::string_view what = "target pose");

/// @throws Error when the weights are not finite and positive.
void check_weights(const FrameTarget& target);

/// Jlog·blockdiag(R_WEᵀ, R_WEᵀ) (6×6): multiplied by the world-aligned Jacobian J_{E[W]} it gives
/// the pose task Jacobian Jlog·J_E, since the local Jacobian is J_E = blockdiag(R_WEᵀ,
/// R_WEᵀ)·J_{E[W]}.
/// @param J_log dexp⁻¹ of the body error (log_error_jacobian) @param R_WE orientation of E in W
Matrix6d log_jacobian_times_local(const Matrix6d& J_log, const Eigen::Matrix3d& R_WE) noexcept;

/// Residual and task Jacobian of a target at the last `kin.update()`, unweighted.
/// @param kin kinematics of the target's frame, already updated at the current q
/// @param kind position (3 rows) or pose (6 rows)
/// @param X_WT target pose in W
/// @param e output residual (task_rows(kind))
/// @param J_task output task Jacobian (task_rows(kind) × n)
/// @param J_scratch workspace, 6 × n
/// @return the frame's position and orientation errors (orientation 0 for position targets)
FrameErrors evaluate_target(const ChainKinematics& kin, TargetKind kind, const Pose& X_WT,
                            Eigen::Ref<Eigen::VectorXd> e, Eigen::Ref<Eigen::MatrixXd> J_task,
                            Eigen::Ref<Matrix6Xd> J_scratch) noexcept;

}  // namespace mjarm
