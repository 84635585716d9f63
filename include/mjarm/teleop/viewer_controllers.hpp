#pragma once
/// @file
/// The two small controllers the interactive viewer needs beside the library's task-space ones:
/// joint position targets passed to servos, and a gripper driven by the panel's 0…1 command.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <string_view>

#include "mjarm/control/controller.hpp"

namespace mjarm {

/// Sends `reference.joint.q` (chain order, [rad or m]) as position targets to the chain's
/// position servos: the "position" mode of the viewer, where inverse kinematics produces the
/// targets. A reference of the wrong size keeps the previous command.
class JointTargetController final : public Controller {
 public:
  /// @param chain the joints whose servos receive the targets
  explicit JointTargetController(const Chain& chain);

  std::string_view name() const noexcept override { return "joint-target"; }
  CommandKind command_kind() const noexcept override { return CommandKind::position; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;

 private:
  Chain chain_;
};

/// Position targets for the gripper joints from `reference.gripper` ∈ [0, 1] (0 open, 1 closed;
/// clamped, NaN counts as open): each joint's target is q = upper + g·(lower − upper), i.e. its
/// upper limit is "open" (true of the bundled Franka Hand, whose fingers range from 0 closed to
/// 0.04 m open), sent to the joints' position servos. Torque-driven grippers use
/// `GripperPdController` (control/gripper_pd.hpp), which maps the command the same way.
class GripperTargetController final : public Controller {
 public:
  /// @param chain the gripper joints (each limited)
  /// @throws Error when a joint has no finite range.
  explicit GripperTargetController(const Chain& chain);

  std::string_view name() const noexcept override { return "gripper-target"; }
  CommandKind command_kind() const noexcept override { return CommandKind::position; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;

  /// The joint targets for a gripper command @p closed ∈ [0, 1] (clamped), written into @p q
  /// (chain.size() entries) [m or rad].
  void targets(double closed, Eigen::Ref<Eigen::VectorXd> q) const noexcept;

 private:
  Chain chain_;
};

}  // namespace mjarm
