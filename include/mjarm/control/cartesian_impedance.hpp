#pragma once
/// @file
/// `CartesianImpedanceController` ("cic"): the operational-space impedance of
/// `OperationalSpaceController` with the measured external wrench (F/T sensor or momentum
/// observer), an integral term for arms with joint friction (held in contact), and the friction
/// feed-forward.

#include <array>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/control/wrench_source.hpp"
#include "mjarm/dynamics/friction_feed_forward.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Which inertia the closed loop shows to contact.
enum class CicInertia {
  /// The arm's own task inertia Λ(q): Λ·ë + D·ė + K·e = −F_c. Needs no measurement and is
  /// passive whatever the measurement's delay; the default.
  natural,
  /// The desired inertia M_d, rendered through the measured wrench F_m: the law cancels it
  /// (−Jᵀ·F_m) and feeds it back through M_d⁻¹ (Λ·M_d⁻¹·F_m), so M_d·ë + D·ė + K·e = −F_c when
  /// F_m = F_c. A force feedback of gain Λ·M_d⁻¹ − I: a lagging measurement (the observer's
  /// ~0.1 s, or the sensor's one step) against a stiff contact loses damping.
  exact
};

/// When the integral term runs.
enum class CicIntegral {
  automatic,  ///< on when a chain joint has friction (dof_frictionloss > 0), off otherwise
  on,         ///< always
  off         ///< never
};

constexpr auto declared_names(const CicInertia*) {
  return std::array{EnumName{CicInertia::natural, "natural", "the arm's own task inertia Λ(q)"},
                    EnumName{CicInertia::exact, "exact", "M_d through the measured wrench"}};
}

constexpr auto declared_names(const CicIntegral*) {
  using I = CicIntegral;
  return std::array{EnumName{I::automatic, "automatic", "on when a chain joint has friction"},
                    EnumName{I::on, "on", "always"}, EnumName{I::off, "off", "never"}};
}

/// Settings of a `CartesianImpedanceController`. Task entries are [x, y, z, rx, ry, rz] in world
/// axes (a 6-D pose task).
struct CartesianImpedanceOptions {
  /// K [N/m; N·m/rad] (> 0): the stiffness contact meets, in real units for either inertia.
  Vector6d stiffness = (Vector6d() << 1000, 1000, 1000, 100, 100, 100).finished();
  /// D [N·s/m; N·m·s/rad]; a negative entry means critical: 2ζ·√(m_i·K_i) with m_i = Λ_ii
  /// (natural, every tick) or M_d,i (exact).
  Vector6d damping = Vector6d::Constant(-1.0);
  double damping_ratio = 1.0;                ///< ζ of the automatic damping entries (> 0)
  CicInertia inertia = CicInertia::natural;  ///< natural Λ or exact M_d
  /// M_d [kg; kg·m²] (> 0), used with `CicInertia::exact`.
  Vector6d desired_inertia = (Vector6d() << 2, 2, 2, 0.1, 0.1, 0.1).finished();
  /// When the integral term on the position error runs.
  CicIntegral integral = CicIntegral::automatic;
  double integral_gain = 150.0;  ///< k_i on x, y, z [N/(m·s)] (> 0); rotation has none
  double integral_bound = 10.0;  ///< |k_i·∫e| ≤ this per axis [N] (> 0): anti-windup
  /// ∫e is held while the measured force ‖f_m‖ ≥ this [N] (> 0): in contact the integral
  /// would otherwise wind up against the obstacle.
  double integral_hold_force = 1.0;
  double nullspace_damping = 5.0;    ///< D_n [N·m·s/rad] (≥ 0)
  double nullspace_stiffness = 0.0;  ///< K_n towards reference.joint.q [N·m/rad] (≥ 0)
  /// Add the friction feed-forward of the model's dof_frictionloss (an exact no-op without
  /// friction). Its damping term is off: the law already cancels qfrc_passive (joint damping).
  bool friction_feed_forward = true;
  /// Mode and scales of the feed-forward (velocity mode by default; its `damping` field is
  /// ignored: by_controller).
  FrictionFeedForwardOptions friction{.mode = FrictionMode::velocity};
  /// Where the measured wrench comes from (none, F/T sensor, observer).
  WrenchSourceOptions force;
  /// The floor that bounds Λ near singularities.
  TaskSpaceOptions task_space;
  /// The repulsive joint-limit term of the law (off by default; `JointLimitAvoidance`).
  JointLimitOptions joint_limits;
};

constexpr auto declared_fields(const CartesianImpedanceOptions*) {
  using S = CartesianImpedanceOptions;
  return declare<S>(
      "cic",
      field("stiffness", &S::stiffness, "N/m; N·m/rad", Range::positive(),
            "K, the stiffness contact meets"),
      field("damping", &S::damping, "N·s/m; N·m·s/rad", Range::finite(),
            "D; a negative entry: critical, 2ζ·√(m_i·K_i)"),
      field("damping_ratio", &S::damping_ratio, "", Range::positive(),
            "ζ of the automatic damping entries"),
      field("inertia", &S::inertia, "natural Λ or exact M_d"),
      field("desired_inertia", &S::desired_inertia, "kg; kg·m²", Range::positive(),
            "M_d, used with exact inertia"),
      field("integral", &S::integral, "when the integral term runs"),
      field("integral_gain", &S::integral_gain, "N/(m·s)", Range::positive(), "k_i on x, y, z"),
      field("integral_bound", &S::integral_bound, "N", Range::positive(),
            "|k_i·∫e| ≤ this per axis"),
      field("integral_hold_force", &S::integral_hold_force, "N", Range::positive(),
            "∫e held while ‖f_m‖ ≥ this"),
      field("nullspace_damping", &S::nullspace_damping, "N·m·s/rad", Range::non_negative(),
            "D_n, null-space joint damping"),
      field("nullspace_stiffness", &S::nullspace_stiffness, "N·m/rad", Range::non_negative(),
            "K_n, null-space posture stiffness"),
      field("friction_feed_forward", &S::friction_feed_forward,
            "add the friction feed-forward of dof_frictionloss"),
      field("friction", &S::friction, "mode and scales of the feed-forward"),
      field("force", &S::force, "where the measured wrench comes from"),
      field("task_space", &S::task_space, "the floor of Λ near singularities"),
      field("joint_limits", &S::joint_limits, "the repulsive joint-limit term"));
}

/// Outcome of the last `CartesianImpedanceController::compute`.
enum class CicStatus {
  ok,              ///< the law ran with the exact Λ
  damped,          ///< the law ran near a singularity (Λ floored)
  invalid_target,  ///< target pose, twist, acceleration or wrench not finite, or the target's
                   ///< rotation not a rotation: the hold command was sent
  invalid_wrench,  ///< the measurement was not finite: taken as zero this tick, the law ran
  invalid_state    ///< the state (q, q̇, h, E's pose) or the law's torque was not finite: hold
};

constexpr auto declared_names(const CicStatus*) {
  using S = CicStatus;
  return std::array{EnumName{S::ok, "ok", "the law ran with the exact Λ"},
                    EnumName{S::damped, "damped", "the law ran with Λ floored"},
                    EnumName{S::invalid_target, "invalid_target", "bad target: hold command"},
                    EnumName{S::invalid_wrench, "invalid_wrench", "bad measurement: taken as 0"},
                    EnumName{S::invalid_state, "invalid_state", "bad state: hold command"}};
}

/// Cartesian impedance control (CIC). Each tick, with F_m the measured wrench of the environment
/// on E (world axes, about E's origin; `WrenchSource`, taken before the law runs), e and ė the
/// errors of `task_error` (e = x_d − x):
///
///     natural:  F = Λ·(A_WD − J̇·q̇) + K·e + D·ė + K_i·∫e + F_ext
///     exact:    F = Λ·(A_WD + M_d⁻¹·(K·e + D·ė + K_i·∫e + F_m + F_ext) − J̇·q̇) − F_m
///     τ₁ = Jᵀ·F + h − τ_passive + Nᵀ·(K_n·(q_ref − q) − D_n·q̇)     (OperationalSpaceController,
///          with its joint-limit term when `joint_limits.enabled`)
///     τ  = τ₁ + f⊙tanh(q̇/v₀)                      (friction feed-forward, velocity mode: default)
///     τ  = τ₁ + f⊙tanh(s·τ_m/f),  τ_m = τ₁ − h + τ_passive                       (torque mode)
///
/// The integral runs on x, y, z only, when `integral` says so (automatic: the chain has joint
/// friction), ∫e clamped to ±bound/k_i, held while ‖f_m‖ ≥ `integral_hold_force`. In torque
/// mode the feed-forward's sign follows the part of the torque that moves the joint (τ_m, τ₁
/// without the bias and passive compensation): following the whole τ₁ would push every joint
/// against gravity at rest. Velocity mode is the default: on a tracked circle with joint
/// friction it leaves a fraction of torque mode's error (whose τ_m also carries inertial and
/// coupling torques that do not point along the motion; docs/control.md). With the observer as
/// source, the tick's final τ is recorded for the next estimate.
///
/// `compute` never allocates, never throws, and never sends a non-finite torque: the hold
/// command is τ = h − τ_passive − D_n·q̇ (zero when that is not finite).
///
/// A tick that sends the hold command skips the observer's update (its state is not trusted):
/// the next estimate then carries a one-tick transient.
///
/// Internals: position_error [m], orientation_error [rad], force, moment (‖f_m‖ [N], ‖τ_m‖
/// [N·m]), integral_x … integral_z [m·s], integral_held (0/1), friction_ff (‖feed-forward‖
/// [N·m]), lambda_damped (0/1), wrench_valid (0/1), status (the enum's value).
class CartesianImpedanceController final : public Controller {
 public:
  /// @throws Error when a gain, inertia or bound is out of range or not finite (stiffness must
  ///         be positive: a stiffness matrix that is not positive definite is refused), or from
  ///         `WrenchSource` (a missing F/T sensor names the site).
  explicit CartesianImpedanceController(const Chain& chain,
                                        const CartesianImpedanceOptions& options = {});

  std::string_view name() const noexcept override { return "cic"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return impedance_.chain(); }
  const CartesianImpedanceOptions& options() const noexcept { return options_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  /// Clears the integral, the measurement and the observer.
  void reset() noexcept override;

  CicStatus status() const noexcept { return status_; }            ///< of the last compute
  bool integral_enabled() const noexcept { return integral_on_; }  ///< as resolved
  /// The measured wrench used by the last compute (world axes, about E) [N; N·m].
  const Vector6d& measured_wrench() const noexcept { return impedance_.measured_wrench(); }
  /// The friction feed-forward added by the last compute (n) [N·m].
  const Eigen::VectorXd& friction_torque() const noexcept { return friction_torque_; }
  /// The operational-space controller that runs the law (Λ, ∫e, task force).
  const OperationalSpaceController& impedance() const noexcept { return impedance_; }
  const WrenchSource& wrench_source() const noexcept { return source_; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  void hold(const mjData& data, Eigen::Ref<Eigen::VectorXd> tau, CicStatus status) noexcept;
  void write_values(const Vector6d& e) noexcept;

  CartesianImpedanceOptions options_;
  bool integral_on_ = false;
  OperationalSpaceController impedance_;
  WrenchSource source_;
  FrictionFeedForward friction_;
  bool friction_on_ = false;
  CicStatus status_ = CicStatus::ok;
  // workspace
  Eigen::VectorXd moving_;           // n: τ₁ − h + τ_passive
  Eigen::VectorXd friction_torque_;  // n
  std::array<std::string, 12> names_{"position_error", "orientation_error", "force",
                                     "moment",         "integral_x",        "integral_y",
                                     "integral_z",     "integral_held",     "friction_ff",
                                     "lambda_damped",  "wrench_valid",      "status"};
  std::array<double, 12> values_{};
};

}  // namespace mjarm
