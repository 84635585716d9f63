#pragma once
/// @file
/// `HandFingerForce`: the motor-mode finger controller of one hand of a `TeleopSession` — a thin
/// adapter of `FingerForceController` (control/finger_force.hpp: PD positioning in free motion,
/// a set squeeze once the fingers touch). It adds two things the bimanual session needs and the
/// controller, written for one gripper and one known object, does not do:
///
/// - its own closing command (`set_command`): a `Simulation` hands the same `Reference` to every
///   controller, with one `gripper` value, while each hand of a bimanual robot has its own;
/// - "the object" is whatever the hand meets: every geom outside the gripper's body subtree (the
///   hand body, which carries the fingers, and everything below it), since a person can grasp
///   anything in the scene.

#include <string_view>

#include "mjarm/control/finger_force.hpp"

namespace mjarm {

/// The defaults of a hand's finger force control (per finger, along its joint): free motion
/// K 1000 N/m, D 5 N·s/m; on an object a squeeze of 20 N, D 20 N·s/m, centring 2000 N/m;
/// |f| ≤ 30 N; torque commands with gravity compensation.
FingerForceOptions hand_finger_force_defaults();

class HandFingerForce final : public Controller {
 public:
  /// @param fingers the finger joints of one hand (limited), e.g. {"left_finger_left",
  ///        "left_finger_right"}
  /// @param options gains and forces; `command` must be torque, `finger_geoms` and
  ///        `object_geoms` are filled here (given ones are an error)
  /// @throws Error as `FingerForceController`, or for given geom lists or a position command.
  explicit HandFingerForce(const Chain& fingers,
                           const FingerForceOptions& options = hand_finger_force_defaults());

  std::string_view name() const noexcept override { return "hand-fingers"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return fingers_.chain(); }
  /// `FingerForceController::compute` with this hand's closing fraction as the reference's
  /// gripper (@p reference is otherwise ignored). Allocation-free.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  void reset() noexcept override;

  /// The closing fraction s ∈ [0, 1] (0 open, 1 closed; clamped, NaN ignored).
  void set_command(double closed) noexcept;
  double command() const noexcept { return own_.gripper; }
  /// Fingers on something outside the gripper at the last `compute`.
  int touching_count() const noexcept { return fingers_.touching_count(); }
  const FingerForceController& controller() const noexcept { return fingers_; }

  std::span<const std::string> internal_names() const noexcept override {
    return fingers_.internal_names();
  }
  std::span<const double> internal_values() const noexcept override {
    return fingers_.internal_values();
  }

 private:
  FingerForceController fingers_;
  Reference own_;  // only `gripper` is read by the controller
};

}  // namespace mjarm
