#pragma once
/// @file
/// `ActionDriver`: turns an environment's actions into the reference of the controller that
/// carries them out — a torque pass-through, a joint PD, or the differential-IK QP feeding the
/// operational-space controller.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <memory>
#include <span>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/reference.hpp"
#include "mjarm/env/action_space.hpp"
#include "mjarm/env/array_spec.hpp"
#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// One action space on one chain. Per control step (period T):
/// - joint_torques: τ = action, held over the step (a pass-through controller "env-torque");
/// - joint_positions: q_d = action; joint_deltas: q_d ← clamp(q_d + action, limits), q_d
///   starting at the episode's start configuration; both tracked by a `JointPdController`
///   (gravity compensated, gains from `ActionOptions::joint_bandwidth`) towards q̇_d = 0;
/// - ee_pose_deltas: the goal moves by the action, X_WG ← (p_WG + Δp, exp(r)·R_WG);
///   ee_velocities: X_WG ← (p_WG + v·T, exp(ω·T)·R_WG); the goal starts at the episode's start
///   pose. The `DiffIk` QP (a pose task on the chain's frame, dt = T, joint speed limit
///   `max_joint_speed`, position limits) takes one step from the measured q (clamped into the
///   joint limits: a joint pushed past its soft limit never takes the reference out) towards
///   X_WG and gives q⁺ = q + v·T inside the joint limits; the reference of the
///   `OperationalSpaceController` is X_WR = FK(q⁺), V_WR = J(q⁺)·v, with q⁺ as its null-space
///   posture: always one feasible step ahead of the arm. Anti-windup: a goal the arm cannot
///   follow (out of reach, past a joint limit, blocked) is pulled back to at most two steps of
///   the largest action (√3·bound per step) from X_WR, in position and in rotation, so that it
///   never runs away. A zero action holds the goal. The goal integrates the actions and the arm
///   follows it about two steps behind, so a proportional policy on a pose error wants a gain
///   well below 1 (0.3 reaches the reach task's targets in under 25 steps).
/// With a gripper (a task whose `EnvTask::gripper_action()` is true) the action has one more
/// entry, last, in [0, 1]: the gripper command (0 open, 1 closed), written to the reference's
/// `gripper` field for the task's own finger controller.
/// `apply` allocates nothing.
class ActionDriver {
 public:
  /// @param chain the joints actions drive (each needs a torque motor in the simulation)
  /// @param control_period T [s] (> 0)
  /// @param gripper the action ends with a gripper command in [0, 1]
  /// @throws Error for options out of range (`ActionOptions::check`) or a bad period.
  ActionDriver(ActionSpace space, const Chain& chain, const ActionOptions& options,
               double control_period, bool gripper = false);
  ~ActionDriver();
  ActionDriver(const ActionDriver&) = delete;
  ActionDriver& operator=(const ActionDriver&) = delete;

  ActionSpace space() const noexcept { return space_; }
  /// True when the action's last entry is a gripper command.
  bool gripper() const noexcept { return gripper_; }
  /// The action's spec: name "action", shape [n] or [6] (+1 with a gripper), bounds of the
  /// space (and [0, 1] for the gripper).
  const ArraySpec& spec() const noexcept { return spec_; }
  /// The controller to add to the simulation (torque commands on the chain).
  Controller& controller() noexcept { return *controller_; }

  /// Starts an episode at the state in @p d (qpos current): the joint targets, the goal and the
  /// reference pose are the current ones.
  void reset(const mjData& d);
  /// The reference for the coming control step from a checked, clipped @p action (spec().size()
  /// values) and the state in @p d (qpos current). Allocation-free.
  const Reference& apply(std::span<const double> action, const mjData& d) noexcept;
  /// The reference of the last `apply` (or `reset`).
  const Reference& reference() const noexcept { return reference_; }
  /// The QP's last step (end-effector spaces; null otherwise).
  const DiffIkStep* ik_step() const noexcept;
  /// End-effector spaces: the QP's own kinematics of the chain's frame, for the environment's
  /// end-effector state after a step — the next `apply` then starts from that work at the same
  /// measured q instead of repeating it. Null for the joint spaces.
  ChainKinematics* measured_kinematics() noexcept;

 private:
  void read_q(const mjData& d) noexcept;

  ActionSpace space_;
  Chain chain_;
  ActionOptions options_;
  double period_;
  bool gripper_ = false;
  ArraySpec spec_;
  std::unique_ptr<Controller> controller_;
  Eigen::VectorXd torque_;  // joint_torques: the action, read by the pass-through controller
  std::unique_ptr<DiffIk> ik_;
  std::unique_ptr<ChainKinematics> kinematics_;
  Matrix6Xd J_;
  Pose X_WG_;  // the goal
  Pose X_WR_;  // the reference pose of the last step
  double max_lead_position_ = 0.0;  // anti-windup bounds of the goal's lead [m], [rad]
  double max_lead_rotation_ = 0.0;
  Eigen::VectorXd q_;
  Reference reference_;
};

}  // namespace mjarm
