#pragma once
/// @file
/// `JointPdController`: joint-space PD with optional gravity compensation, and `JointPdGains`, the
/// per-joint (or scalar) gains the joint-space controllers share.

#include <Eigen/Core>
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// PD gains in joint space. Each vector holds one entry per chain joint, or a single entry used
/// for every joint.
struct JointPdGains {
  Eigen::VectorXd kp = Eigen::VectorXd::Constant(1, 100.0);  ///< stiffness [N·m/rad or N/m], ≥ 0
  Eigen::VectorXd kd = Eigen::VectorXd::Constant(1, 20.0);   ///< damping [N·m·s/rad or N·s/m], ≥ 0

  /// The same @p kp and @p kd on every joint.
  static JointPdGains uniform(double kp, double kd);

  /// Gains for an error that closes like ë + 2ωė + ω²e = 0 (critically damped, natural frequency
  /// @p omega [rad/s]): kp = ω², kd = 2ω. Meant for unit-inertia loops (computed torque), where
  /// they are accelerations per unit error [1/s², 1/s].
  static JointPdGains critically_damped(double omega);

  /// The gains spread over @p n joints (a single entry repeated).
  /// @throws Error naming @p owner when a vector has neither 1 nor @p n entries, or holds a
  /// negative or non-finite value.
  JointPdGains expanded(int n, std::string_view owner) const;
};

// units per controller: N·m/rad and N·m·s/rad for joint PD, 1/s² and 1/s for computed torque
constexpr auto declared_fields(const JointPdGains*) {
  using S = JointPdGains;
  return declare<S>("joint PD gains",
                    field("kp", &S::kp, "", Range::non_negative(),
                          "stiffness, one per chain joint or one for all"),
                    field("kd", &S::kd, "", Range::non_negative(),
                          "damping, one per chain joint or one for all"));
}

/// Settings of a `JointPdController`.
struct JointPdOptions {
  JointPdGains gains;
  /// Adds the gravity torques g(q) (`ChainDynamics::gravity`), so that the PD only corrects the
  /// error instead of also holding the arm up.
  bool gravity_compensation = true;
};

constexpr auto declared_fields(const JointPdOptions*) {
  using S = JointPdOptions;
  return declare<S>("joint-pd", field("gains", &S::gains, "Kp and Kd per joint"),
                    field("gravity_compensation", &S::gravity_compensation, "add g(q)"));
}

/// Joint-space PD on torque-driven joints:
///
///     τ = Kp·(q_d − q) + Kd·(q̇_d − q̇) [+ g(q)]
///
/// with q, q̇ read from the state and q_d, q̇_d from reference.joint (q̇_d = 0 when
/// reference.joint.qd does not have n entries; the position term is dropped when reference.joint.q
/// does not). Kp and Kd are diagonal. Without the gravity term the arm settles below the target
/// by Kp⁻¹·g(q).
///
/// Internals: position_error [rad or m] and velocity_error [rad/s or m/s] (Euclidean norms),
/// reference_ok (1 when reference.joint.q had n entries).
class JointPdController final : public Controller {
 public:
  /// @throws Error when a gain vector has the wrong size or a negative / non-finite entry.
  JointPdController(const Chain& chain, const JointPdOptions& options = {});

  std::string_view name() const noexcept override { return "joint-pd"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  /// The gains, expanded to one entry per joint.
  const JointPdGains& gains() const noexcept { return gains_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference, JointCommand& command) noexcept override;

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  JointPdGains gains_;
  bool gravity_ = true;
  ChainDynamics dynamics_;
  std::array<std::string, 3> names_{"position_error", "velocity_error", "reference_ok"};
  std::array<double, 3> values_{};
};

}  // namespace mjarm
