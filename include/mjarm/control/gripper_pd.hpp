#pragma once
/// @file
/// `GripperPdController`: PD on the finger joints of a gripper, driven by an open/close fraction,
/// with a force clamp.

#include <Eigen/Core>
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/joint_pd.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// Settings of a `GripperPdController`. The defaults suit the bundled grippers (Franka Hand and
/// arm6: slide fingers of ~0.025 kg with armature, 0.002 s Euler steps).
struct GripperPdOptions {
  /// Kp [N/m or N·m/rad] and Kd [N·s/m or N·m·s/rad] per finger (or one for all), ≥ 0.
  JointPdGains gains = JointPdGains::uniform(1000.0, 5.0);
  /// Largest |τ| per finger [N or N·m] (> 0): bounds the squeeze on a grasped object.
  double max_force = 20.0;
  /// Finger positions at reference.gripper = 0 (open) and = 1 (closed) [m or rad], one per finger.
  /// Empty: open at each joint's upper limit, closed at its lower limit (the bundled fingers
  /// slide outwards with positive q).
  Eigen::VectorXd open;
  Eigen::VectorXd closed;
  /// Adds the gravity forces on the fingers (`ChainDynamics::gravity`) before the clamp.
  bool gravity_compensation = true;
};

constexpr auto declared_fields(const GripperPdOptions*) {
  using S = GripperPdOptions;
  return declare<S>(
      "gripper-pd", field("gains", &S::gains, "Kp and Kd per finger (or one for all)"),
      field("max_force", &S::max_force, "N or N·m", Range::positive(), "largest |τ| per finger"),
      field("open", &S::open, "m or rad", Range::finite(),
            "finger positions when open, one per finger; empty: the upper limits"),
      field("closed", &S::closed, "m or rad", Range::finite(),
            "finger positions when closed, one per finger; empty: the lower limits"),
      field("gravity_compensation", &S::gravity_compensation,
            "add the gravity forces on the fingers"));
}

/// PD on prismatic or hinge finger joints (the controller's chain, e.g.
/// `Chain(robot, {"finger_left", "finger_right"}, "tcp")`):
///
///     s   = clamp(reference.gripper, 0, 1)               (NaN keeps the previous s)
///     q_d = open + s·(closed − open)
///     τ   = clamp(Kp·(q_d − q) − Kd·q̇ [+ g], ±max_force)
///
/// When the fingers close on an object the position error stays and the squeeze settles at
/// min(Kp·|q_d − q|, max_force).
///
/// Internals: fraction (s), width_error [m or rad] (norm of q_d − q), saturated (number of
/// fingers at the clamp).
class GripperPdController final : public Controller {
 public:
  /// @throws Error when gains, max_force, open or closed have the wrong size or value, or a finger
  /// joint has no finite range while open/closed are not given.
  GripperPdController(const Chain& fingers, const GripperPdOptions& options = {});

  std::string_view name() const noexcept override { return "gripper-pd"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  /// Finger positions at fraction 0 and 1 (n each).
  const Eigen::VectorXd& open() const noexcept { return open_; }
  const Eigen::VectorXd& closed() const noexcept { return closed_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference, JointCommand& command) noexcept override;
  /// Back to fully open as the fallback fraction.
  void reset() noexcept override { fraction_ = 0.0; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  JointPdGains gains_;
  double max_force_ = 20.0;
  bool gravity_ = true;
  ChainDynamics dynamics_;
  Eigen::VectorXd open_;
  Eigen::VectorXd closed_;
  double fraction_ = 0.0;
  std::array<std::string, 3> names_{"fraction", "width_error", "saturated"};
  std::array<double, 3> values_{};
};

}  // namespace mjarm
