#pragma once
/// @file
/// The action spaces of an environment and their settings: what an action means, its bounds,
/// and the gains of the controllers that carry it out.

#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/operational_space.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// What one action commands (n = the task chain's joints).
enum class ActionSpace {
  /// n joint torques [N·m or N], bounded by the motors' limits; held over the control step.
  joint_torques,
  /// n joint position targets [rad or m] within the joint limits, tracked by a joint PD with
  /// gravity compensation.
  joint_positions,
  /// n joint position increments [rad or m] added to the previous target (which stays within
  /// the joint limits), tracked like joint_positions.
  joint_deltas,
  /// 6 end-effector pose increments [dx, dy, dz, rx, ry, rz] (world axes; m and a rotation
  /// vector in rad) applied to the goal pose, made feasible by the differential-IK QP (joint
  /// position and speed limits) and tracked by the operational-space controller.
  ee_pose_deltas,
  /// 6 end-effector velocities [vx, vy, vz, wx, wy, wz] (world axes; m/s, rad/s), integrated
  /// over the control step into the goal pose, then as ee_pose_deltas.
  ee_velocities
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const ActionSpace*) {
  using E = ActionSpace;
  return std::array{
      EnumName{E::joint_torques, "joint_torques", "n torques [N m], held over the step"},
      EnumName{E::joint_positions, "joint_positions", "n joint targets [rad]"},
      EnumName{E::joint_deltas, "joint_deltas", "n increments of the joint target [rad]"},
      EnumName{E::ee_pose_deltas, "ee_pose_deltas",
               "[dx dy dz rx ry rz] of the goal pose (world axes; m, rotation vector rad)"},
      EnumName{E::ee_velocities, "ee_velocities",
               "[vx vy vz wx wy wz] (m/s, rad/s), integrated over the step"}};
}

/// Every action space, in the enum's order.
const std::vector<ActionSpace>& action_spaces();

/// The action space called @p name.
/// @throws Error naming @p name and the choices.
ActionSpace action_space(std::string_view name);

/// The operational-space settings the environments use by default: a pose task, K = 400 per
/// unit desired inertia on every axis (ω_n = 20 rad/s), critically damped, null-space posture
/// 10 N·m/rad towards the QP's joint step and damping 2 N·m·s/rad. The bandwidth is kept low
/// enough for the torques to be held over a 20 ms control step (ω_n·T = 0.4).
OperationalSpaceOptions environment_osc_options();

/// Bounds and gains of the action spaces.
struct ActionOptions {
  double max_joint_delta = 0.05;   ///< joint_deltas: |Δq| per step [rad or m] (> 0)
  double max_translation = 0.02;   ///< ee_pose_deltas: |Δp| per axis per step [m] (> 0)
  double max_rotation = 0.1;       ///< ee_pose_deltas: |r| per axis per step [rad] (> 0)
  double max_linear_speed = 0.5;   ///< ee_velocities: |v| per axis [m/s] (> 0)
  double max_angular_speed = 1.0;  ///< ee_velocities: |ω| per axis [rad/s] (> 0)
  /// Joint PD bandwidth ω [rad/s] (> 0): kp_i = ω²·M_ii and kd_i = 2ω·M_ii, M_ii the diagonal
  /// of the mass matrix at the model's `home` keyframe (qpos0 without one), so every joint
  /// closes alike and the gains stay stable when held over the control step.
  double joint_bandwidth = 20.0;
  /// Speed limit of every joint in the differential-IK QP [rad/s or m/s] (> 0).
  double max_joint_speed = 2.0;
  /// The operational-space controller of the end-effector spaces.
  OperationalSpaceOptions osc = environment_osc_options();

  /// @throws Error naming the first option that is out of range.
  void check() const;
};

/// `osc` is checked by its controller (its mode by `ActionOptions::check`).
constexpr auto declared_fields(const ActionOptions*) {
  using S = ActionOptions;
  return declare<S>("action options",
                    field("max_joint_delta", &S::max_joint_delta, "rad or m", Range::positive(),
                          "joint_deltas: |dq| per step"),
                    field("max_translation", &S::max_translation, "m", Range::positive(),
                          "ee_pose_deltas: |dp| per axis per step"),
                    field("max_rotation", &S::max_rotation, "rad", Range::positive(),
                          "ee_pose_deltas: |r| per axis per step"),
                    field("max_linear_speed", &S::max_linear_speed, "m/s", Range::positive(),
                          "ee_velocities: |v| per axis"),
                    field("max_angular_speed", &S::max_angular_speed, "rad/s", Range::positive(),
                          "ee_velocities: |w| per axis"),
                    field("joint_bandwidth", &S::joint_bandwidth, "rad/s", Range::positive(),
                          "joint PD bandwidth"),
                    field("max_joint_speed", &S::max_joint_speed, "rad/s or m/s", Range::positive(),
                          "joint speed limit of the differential-IK QP"));
}

}  // namespace mjarm
