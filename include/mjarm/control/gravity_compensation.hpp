#pragma once
/// @file
/// Gravity compensation: for arms driven by position servos (`ServoBiasCompensation`,
/// `GravityCompensationController`) and for torque-driven arms (`GravityHoldController`).

#include <Eigen/Core>
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// Which bias forces a compensation cancels.
enum class BiasTerm {
  gravity,  ///< g(q) only (`ChainDynamics::gravity`)
  full      ///< h = C(q, q̇)·q̇ + g(q), MuJoCo's qfrc_bias (`ChainDynamics::bias`)
};

constexpr auto declared_names(const BiasTerm*) {
  return std::array{EnumName{BiasTerm::gravity, "gravity", "g(q) only"},
                    EnumName{BiasTerm::full, "full", "h = C(q, q̇)·q̇ + g(q)"}};
}

/// The bias forces that make position-servoed joints sag, and the servo-target offset that
/// cancels them.
///
/// A position servo (force = kp·(ctrl − gear·q) − kv·gear·q̇, generalized force = gear·force)
/// settles where its spring holds the bias force b: q = q_d − b / k with joint stiffness
/// k = gear²·kp. Shifting the target by b / k moves that equilibrium onto q_d:
///
///     ctrl-side joint target  q_cmd = q_d + b / k            (offset(), apply())
///
/// The compensation goes through the servo on purpose, rather than as an extra qfrc_applied: the
/// actuator's forcerange still bounds the total force (as on a real drive), the recorded actuator
/// forces include it, and no force is left behind in qfrc_applied for the next tick to clear. The
/// price is that the shifted target is clipped to ctrlrange (= the joint range in the bundled
/// models), so at a joint limit pulled outwards by gravity part of the compensation is lost.
///
/// Use: after `mj_forward` / `mj_step1`, `update(data)`, then `apply(targets)` on the position
/// targets (chain order, [rad or m]) before writing them to ctrl. Use one compensation only: a
/// simulation that also adds the bias forces to qfrc_applied (`SimulationOptions::
/// gravity_compensation` in position mode) must have it switched off, or the bias counts twice
/// and the arm settles b / k above its target.
class ServoBiasCompensation {
 public:
  /// @throws Error naming the joint when a chain joint has no actuator, or its first actuator is
  /// not a position servo (ActuatorKind::position) with kp > 0.
  explicit ServoBiasCompensation(const Chain& chain, BiasTerm term = BiasTerm::gravity);

  const Chain& chain() const noexcept { return dynamics_.chain(); }
  BiasTerm term() const noexcept { return term_; }

  /// Reads the bias forces from @p data (state already computed; never written).
  void update(const mjData& data) noexcept;

  /// The bias forces b on the chain's dofs at the last `update()` [N·m or N] (n).
  const Eigen::VectorXd& bias() const noexcept { return bias_; }
  /// Joint stiffness k = gear²·kp of each joint's servo [N·m/rad or N/m] (n).
  const Eigen::VectorXd& stiffness() const noexcept { return stiffness_; }
  /// The target offset b / k [rad or m] at the last `update()` (n).
  const Eigen::VectorXd& offset() const noexcept { return offset_; }
  /// Adds `offset()` to @p targets (n joint targets, chain order).
  void apply(Eigen::Ref<Eigen::VectorXd> targets) const noexcept { targets += offset_; }

 private:
  BiasTerm term_;
  ChainDynamics dynamics_;
  Eigen::VectorXd stiffness_;
  Eigen::VectorXd bias_;
  Eigen::VectorXd offset_;
};

/// Holds reference.joint.q with position servos that do not sag: command kind position, value =
/// q_d + b / k (see `ServoBiasCompensation`). When reference.joint.q does not have n entries, the
/// joint positions at the first `compute` after construction or `reset` are held.
///
/// Internals: bias_norm [N·m] (norm of b), max_offset [rad or m] (largest |b / k|).
class GravityCompensationController final : public Controller {
 public:
  /// @throws Error as `ServoBiasCompensation`.
  explicit GravityCompensationController(const Chain& chain, BiasTerm term = BiasTerm::gravity);

  std::string_view name() const noexcept override { return "gravity-servo"; }
  CommandKind command_kind() const noexcept override { return CommandKind::position; }
  /// True: the targets carry the bias offset b / k.
  bool compensates_bias() const noexcept override { return true; }
  const Chain& chain() const noexcept override { return compensation_.chain(); }
  const ServoBiasCompensation& compensation() const noexcept { return compensation_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  /// Forgets the held position.
  void reset() noexcept override { latched_ = false; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  ServoBiasCompensation compensation_;
  Eigen::VectorXd hold_;
  bool latched_ = false;
  std::array<std::string, 2> names_{"bias_norm", "max_offset"};
  std::array<double, 2> values_{};
};

/// Torque that holds a torque-driven arm against gravity: τ = g(q) (BiasTerm::gravity) or
/// τ = h(q, q̇) (BiasTerm::full, also cancelling Coriolis and centrifugal forces). At rest
/// M·q̈ = τ − g = 0, so the arm stays where it is and can be moved by hand (or by contact); it
/// does not return anywhere. Ignores the reference.
///
/// Internals: bias_norm [N·m] (norm of τ).
class GravityHoldController final : public Controller {
 public:
  explicit GravityHoldController(const Chain& chain, BiasTerm term = BiasTerm::gravity);

  std::string_view name() const noexcept override { return "gravity"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  BiasTerm term_;
  ChainDynamics dynamics_;
  std::array<std::string, 1> names_{"bias_norm"};
  std::array<double, 1> values_{};
};

}  // namespace mjarm
