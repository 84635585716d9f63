#pragma once
/// @file
/// `FrictionFeedForward`: joint friction and damping compensation from the model's
/// dof_frictionloss and dof_damping, in torque mode or velocity mode, and the modelled passive
/// resistance the momentum observer subtracts.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// Which signal sets the sign of the friction feed-forward.
enum class FrictionMode {
  /// τ_i += f_i·tanh(s·τ_i / f_i): follows the commanded torque (works at rest, where the
  /// velocity carries no sign yet).
  torque,
  /// τ_i += f_i·tanh(q̇_i / v₀): follows the joint velocity.
  velocity
};

constexpr auto declared_names(const FrictionMode*) {
  return std::array{EnumName{FrictionMode::torque, "torque", "the sign follows the torque"},
                    EnumName{FrictionMode::velocity, "velocity", "the sign follows q̇"}};
}

/// Who cancels the viscous damping d⊙q̇.
enum class DampingCompensation {
  /// The feed-forward adds d⊙q̇ (for a controller that does not touch qfrc_passive).
  feed_forward,
  /// The controller already cancels qfrc_passive (which holds −d⊙q̇, see
  /// `OperationalSpaceOptions::compensate_passive`): the feed-forward adds no damping term, so
  /// damping is compensated exactly once.
  by_controller
};

constexpr auto declared_names(const DampingCompensation*) {
  using D = DampingCompensation;
  return std::array{EnumName{D::feed_forward, "feed_forward", "the feed-forward adds d⊙q̇"},
                    EnumName{D::by_controller, "by_controller", "the controller cancels it"}};
}

/// Tuning of the feed-forward.
struct FrictionFeedForwardOptions {
  FrictionMode mode = FrictionMode::torque;  ///< torque or velocity
  double torque_sharpness = 2.0;             ///< s in tanh(s·τ/f) [1] (> 0)
  double velocity_scale = 0.01;              ///< v₀ in tanh(q̇/v₀) [rad/s or m/s] (> 0)
  DampingCompensation damping = DampingCompensation::feed_forward;  ///< who cancels d⊙q̇
};

constexpr auto declared_fields(const FrictionFeedForwardOptions*) {
  using S = FrictionFeedForwardOptions;
  return declare<S>(
      "friction feed-forward", field("mode", &S::mode, "which signal sets the sign"),
      field("torque_sharpness", &S::torque_sharpness, "", Range::positive(), "s in tanh(s·τ/f)"),
      field("velocity_scale", &S::velocity_scale, "rad/s or m/s", Range::positive(),
            "v₀ in tanh(q̇/v₀)"),
      field("damping", &S::damping, "who cancels the viscous damping d⊙q̇"));
}

/// The options that fit a controller: `by_controller` damping when @p controller_cancels_passive
/// (an `OperationalSpaceController` with compensate_passive = true), `feed_forward` otherwise.
FrictionFeedForwardOptions friction_options_for(bool controller_cancels_passive,
                                                FrictionMode mode = FrictionMode::torque) noexcept;

/// Friction and damping feed-forward for a chain, from the model's dof_frictionloss f [N·m or N]
/// and dof_damping d [N·m·s/rad or N·s/m] of the chain's dofs:
///
///     torque mode:    τ ← τ + f⊙tanh(s·τ/f) + d⊙q̇
///     velocity mode:  τ ← τ + f⊙tanh(q̇/v₀)  + d⊙q̇
///
/// (the damping term only with `DampingCompensation::feed_forward`). A dof with f = 0 gets no
/// friction term and a dof with d = 0 no damping term: on a model without friction and damping
/// `apply` leaves τ bit-identical. In MuJoCo frictionloss is a constraint force (in
/// qfrc_constraint, never in qfrc_passive) and damping a passive force (qfrc_passive).
/// `apply` and `model_force` allocate nothing and never throw.
class FrictionFeedForward {
 public:
  /// Reads f and d of the chain's dofs from its model.
  /// @throws Error when torque_sharpness or velocity_scale is not > 0 and finite.
  explicit FrictionFeedForward(const Chain& chain, FrictionFeedForwardOptions options = {});

  int size() const noexcept { return static_cast<int>(friction_.size()); }         ///< n
  const FrictionFeedForwardOptions& options() const noexcept { return options_; }  ///< as built
  const Eigen::VectorXd& friction() const noexcept { return friction_; }  ///< f (n) [N·m or N]
  const Eigen::VectorXd& damping() const noexcept { return damping_; }    ///< d (n)
  /// True when some dof has f > 0 or (with the feed-forward damping term) d > 0.
  bool active() const noexcept;

  /// Adds the feed-forward to @p tau in place (n entries, the commanded torque on entry) for the
  /// chain velocities @p qd (n). Unchecked sizes.
  void apply(const Eigen::Ref<const Eigen::VectorXd>& qd,
             Eigen::Ref<Eigen::VectorXd> tau) const noexcept;

  /// The modelled passive resistance on each dof, −f⊙tanh(q̇/v₀) − d⊙q̇ (the force friction and
  /// damping exert on the joints; the damping term always, whatever `options().damping`), into
  /// @p out (n). Unchecked sizes.
  void model_force(const Eigen::Ref<const Eigen::VectorXd>& qd,
                   Eigen::Ref<Eigen::VectorXd> out) const noexcept;

 private:
  FrictionFeedForwardOptions options_;
  Eigen::VectorXd friction_;
  Eigen::VectorXd damping_;
};

}  // namespace mjarm
