#pragma once
/// @file
/// `ComputedTorqueController`: joint-space inverse-dynamics (computed-torque) tracking.

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

/// Settings of a `ComputedTorqueController`.
struct ComputedTorqueOptions {
  /// Kp [1/s²] and Kd [1/s]: accelerations per unit error (the loop has unit inertia). The default
  /// closes every joint at ω = 30 rad/s, critically damped.
  JointPdGains gains = JointPdGains::critically_damped(30.0);
  /// Also cancels the model's passive forces (joint damping, springs: qfrc_passive), which are
  /// not part of h.
  bool compensate_passive = true;
};

constexpr auto declared_fields(const ComputedTorqueOptions*) {
  using S = ComputedTorqueOptions;
  return declare<S>("ct", field("gains", &S::gains, "Kp [1/s²] and Kd [1/s] per joint"),
                    field("compensate_passive", &S::compensate_passive, "cancel qfrc_passive"));
}

/// Computed torque (inverse-dynamics control) on torque-driven joints:
///
///     e = q_d − q,  ė = q̇_d − q̇
///     τ = M(q)·(q̈_d + Kp·e + Kd·ė) + h(q, q̇) [− τ_passive]
///
/// M·(…) is MuJoCo's sparse mj_mulM on the state (`ChainDynamics::inverse_dynamics`), h its
/// qfrc_bias. With the model exact and no contact the error obeys ë + Kd·ė + Kp·e = 0 on every
/// joint independently. q̇_d and q̈_d count as zero when reference.joint.qd / qdd do not have n
/// entries; the position term is dropped when reference.joint.q does not.
///
/// Internals: position_error [rad or m], velocity_error [rad/s or m/s] (norms), reference_ok.
class ComputedTorqueController final : public Controller {
 public:
  /// @throws Error when a gain vector has the wrong size or a negative / non-finite entry.
  ComputedTorqueController(const Chain& chain, const ComputedTorqueOptions& options = {});

  std::string_view name() const noexcept override { return "ct"; }
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
  bool compensate_passive_ = true;
  ChainDynamics dynamics_;
  Eigen::VectorXd qdd_;  // commanded joint acceleration (n)
  std::array<std::string, 3> names_{"position_error", "velocity_error", "reference_ok"};
  std::array<double, 3> values_{};
};

}  // namespace mjarm
