#pragma once
/// @file
/// `FingerForceController`: a parallel gripper that positions its fingers in free motion and
/// squeezes with a set force once they touch the object — force control with contact-dependent
/// gains, for grasps held by friction alone.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// Settings of a `FingerForceController`. Forces are per finger, along its joint [N or N·m].
struct FingerForceOptions {
  /// What the controller writes: torques (finger motors) or position targets (finger servos,
  /// the target chosen so that the servo produces the force of the law below).
  CommandKind command = CommandKind::torque;
  double free_stiffness = 1000.0;  ///< K_free [N/m]: positioning while not touching (> 0)
  double free_damping = 10.0;      ///< D_free [N·s/m] (≥ 0)
  double contact_damping = 20.0;   ///< D_contact [N·s/m]: once touching (≥ 0)
  /// K_centre [N/m] (≥ 0): once touching, each finger's force grows by K_centre times how much
  /// more open it is than the fingers' mean, which keeps the object centred between them (the
  /// squeeze alone would let it sit anywhere along the closing axis).
  double centering_stiffness = 2000.0;
  /// F_grasp: the squeeze of each finger on the object [N] (> 0). In position mode it is also
  /// bounded by what the servo can push from where the finger stands (kp·(q − lower end of
  /// ctrlrange)), so the target is never clipped.
  double grasp_force = 10.0;
  double max_force = 20.0;  ///< |force| bound in free motion [N] (≥ grasp_force)
  /// Finger positions at reference.gripper = 0 (open) and 1 (closed), one per finger; empty:
  /// each joint's upper and lower limit (the bundled fingers slide outwards with positive q).
  Eigen::VectorXd open;
  Eigen::VectorXd closed;
  /// Geom ids of each finger (one list per chain joint) and of the object: a finger is "in
  /// contact" while MuJoCo's contact list holds a contact between one of its geoms and the
  /// object's. Empty object list: the fingers never count as touching (a position gripper).
  std::vector<std::vector<int>> finger_geoms;
  std::vector<int> object_geoms;
  /// Torque mode: adds the gravity force on the fingers (`ChainDynamics::gravity`). In position
  /// mode the `Simulation` compensates the servo-driven dofs itself.
  bool gravity_compensation = true;
};

// the geom lists stay undeclared: checked against the model and bound by hand
constexpr auto declared_fields(const FingerForceOptions*) {
  using S = FingerForceOptions;
  return declare<S>(
      "fingers", field("command", &S::command, "torques or position targets"),
      field("free_stiffness", &S::free_stiffness, "N/m", Range::positive(),
            "K_free, positioning while not touching"),
      field("free_damping", &S::free_damping, "N·s/m", Range::non_negative(), "D_free"),
      field("contact_damping", &S::contact_damping, "N·s/m", Range::non_negative(),
            "D_contact, once touching"),
      field("centering_stiffness", &S::centering_stiffness, "N/m", Range::non_negative(),
            "K_centre, keeps the object centred"),
      field("grasp_force", &S::grasp_force, "N", Range::positive(),
            "F_grasp, each finger's squeeze"),
      field("max_force", &S::max_force, "N", Range::positive(),
            "|force| bound in free motion (≥ grasp_force)"),
      field("open", &S::open, "m or rad", Range::finite(),
            "finger positions when open, one per finger; empty: the upper limits"),
      field("closed", &S::closed, "m or rad", Range::finite(),
            "finger positions when closed, one per finger; empty: the lower limits"),
      field("gravity_compensation", &S::gravity_compensation,
            "torque mode: add the gravity force on the fingers"));
}

/// Per finger i, with s = clamp(reference.gripper, 0, 1) (NaN keeps the previous s),
/// q_d = open + s·(closed − open), e = q_d − q, c = ±1 the closing direction of the joint, and
/// o = c·(closed − q) ≥ 0 how far it stands open (ō the fingers' mean):
///
///     touching the object while ō_d < ō (the reference asks the fingers to close further than
///     they stand, on average, ō_d = (1 − s)·|open − closed| averaged):
///               f = c·(F_grasp + K_centre·(o − ō)) − D_contact·q̇
///     otherwise f = K_free·e − D_free·q̇
///     then      f = clamp(f, ±max_force)
///
/// The gains depend on the contact: in free motion a stiff PD puts the fingers where the
/// fraction says; on the object the position loop gives way to force control — each finger
/// pushes with F_grasp whatever the object's size (the measured squeeze equals F_grasp,
/// tests/control/finger_force_test.cpp), and the centring term, which sums to zero over the two
/// fingers, keeps the object midway between them as a mechanically coupled gripper would (pure
/// force control would leave it wherever the first finger pushed it). Opening (s decreasing)
/// moves ō_d past ō: the PD takes over for every finger at the same tick and they leave
/// together (one finger still pushing while the other leaves shoves the object aside).
///
/// Torque mode: τ = f (+ gravity). Position mode: the servo force kp·(ctrl − q) − kv·q̇ equals f
/// for ctrl = q + (f + kv·q̇)/kp (kp, kv read from each finger's actuator), with f bounded so
/// that ctrl stays inside ctrlrange — a servo can push at most kp·(q − ctrl lower) closed.
///
/// Contacts are read from data.contact (geometry: fresh inside a control tick); constraint forces
/// are not (MuJoCo computes them later in the step) — a grasp monitor reads those after the step.
/// Internals: fraction, touching (fingers in contact), force_command (mean |f| of the fingers
/// in contact, 0 when none) [N].
class FingerForceController final : public Controller {
 public:
  /// @throws Error for non-positive or non-finite gains or forces, open/closed of the wrong size
  ///         or without finite joint ranges, finger geom lists that do not match the chain,
  ///         geom ids out of range, or (position mode) a finger without a position servo.
  FingerForceController(const Chain& fingers, const FingerForceOptions& options = {});

  std::string_view name() const noexcept override { return "fingers"; }
  CommandKind command_kind() const noexcept override { return options_.command; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  const FingerForceOptions& options() const noexcept { return options_; }
  const Eigen::VectorXd& open() const noexcept { return open_; }
  const Eigen::VectorXd& closed() const noexcept { return closed_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  void reset() noexcept override;

  /// Whether finger i touched the object at the last `compute`.
  bool touching(int i) const noexcept { return i >= 0 && i < 8 && touching_[i]; }
  /// Number of fingers touching the object at the last `compute`.
  int touching_count() const noexcept;
  /// The force f of finger i at the last `compute` [N] (joint axis; negative closes the bundled
  /// fingers).
  double force(int i) const noexcept { return forces_[i]; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  FingerForceOptions options_;
  ChainDynamics dynamics_;
  Eigen::VectorXd open_, closed_;
  Eigen::VectorXd servo_kp_, servo_kv_, ctrl_lower_, ctrl_upper_;  // position mode
  std::vector<std::uint8_t> finger_of_geom_;  // per geom: 1 + finger index, 0 = not a finger
  std::vector<std::uint8_t> object_geom_;     // per geom: 1 when part of the object
  Eigen::VectorXd forces_;
  std::array<bool, 8> touching_{};
  double fraction_ = 0.0;
  std::array<std::string, 3> names_{"fraction", "touching", "force_command"};
  std::array<double, 3> values_{};
};

}  // namespace mjarm
