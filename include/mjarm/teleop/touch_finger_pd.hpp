#pragma once
/// @file
/// `TouchFingerPd`: PD on a gripper's finger joints whose gains change when the fingers touch
/// something: stiff and lightly damped while the fingers travel, softer and more damped once a
/// finger is in contact, so that a grasp squeezes with a bounded, steady force instead of
/// ringing against the object. The motor mode of the teleoperation session drives each hand's
/// fingers with one.
///
/// Self-contained on purpose: the pick-and-place work (branch h/pickplace, control/finger_force)
/// brings finger force control with contact-dependent gains to control/; once it is on main this
/// controller should become a thin use of it.

#include <mujoco/mujoco.h>

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/joint_pd.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"

namespace mjarm {

/// Settings of a `TouchFingerPd`. The defaults suit the Franka Hand fingers (0.015 kg slides with
/// 0.01 kg armature, 2 ms Euler steps).
struct TouchFingerPdOptions {
  /// Gains while no finger touches anything outside its own hand: Kp [N/m], Kd [N·s/m].
  JointPdGains free = JointPdGains::uniform(1000.0, 5.0);
  /// Gains while a finger touches: lower stiffness, more damping (a steady squeeze).
  JointPdGains touch = JointPdGains::uniform(400.0, 20.0);
  /// Largest |τ| per finger [N] (> 0): bounds the squeeze.
  double max_force = 30.0;
  /// Adds the gravity forces on the fingers (`ChainDynamics::gravity`) before the clamp.
  bool gravity_compensation = true;
};

/// PD on the finger joints of one gripper (the controller's chain), driven by a closing fraction
/// set with `set_command` (not by `Reference::gripper`, so that several grippers on one robot
/// take different commands in the same tick):
///
///     q_d = open + s·(closed − open)     (open: each joint's upper limit, closed: its lower)
///     touch = a contact between a finger geom and a geom outside the gripper's body subtree
///     τ   = clamp(Kp·(q_d − q) − Kd·q̇ [+ g], ±max_force),  (Kp, Kd) = touch ? touch : free
///
/// The contact test reads `data.contact` (the last collision pass), allocation-free.
/// Internals: fraction, touching (0/1), squeeze [N] (mean |τ| over the fingers).
class TouchFingerPd final : public Controller {
 public:
  /// @param fingers the finger joints (limited), e.g. {"left_finger_left", "left_finger_right"}
  /// @throws Error for gains of the wrong size or value, max_force not positive and finite, or a
  ///         finger joint without a finite range.
  explicit TouchFingerPd(const Chain& fingers, const TouchFingerPdOptions& options = {});

  std::string_view name() const noexcept override { return "touch-finger-pd"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  void reset() noexcept override;

  /// The closing fraction s ∈ [0, 1] (0 open, 1 closed; clamped, NaN ignored).
  void set_command(double closed) noexcept;
  double command() const noexcept { return fraction_; }
  /// True when a finger touched something outside its gripper at the last `compute`.
  bool touching() const noexcept { return touching_; }
  /// True when @p data holds a contact between a finger and a geom outside the gripper.
  bool touches(const mjData& data) const noexcept;

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  JointPdGains free_;
  JointPdGains touch_;
  double max_force_;
  bool gravity_;
  ChainDynamics dynamics_;
  std::vector<char> finger_body_;  // per body: a finger
  std::vector<char> own_body_;     // per body: in the gripper's subtree (hand and fingers)
  double fraction_ = 0.0;
  bool touching_ = false;
  std::array<std::string, 3> names_{"fraction", "touching", "squeeze"};
  std::array<double, 3> values_{};
};

}  // namespace mjarm
