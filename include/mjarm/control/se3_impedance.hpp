#pragma once
/// @file
/// `Se3ImpedanceController`: impedance control of the chain's frame E on the Lie group SE(3)
/// (Kim et al., IEEE T-RO 2025, the impedance part): the closed loop A·λ̈ + D·λ̇ + K·λ = γ holds
/// on the exponential coordinates λ = log(X_EW·X_WD) of the target seen from E, with full 6×6
/// A, D, K, and a contact-triggered release of chosen stiffness axes.

#include <array>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/joint_limit_avoidance.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/friction_feed_forward.hpp"
#include "mjarm/dynamics/task_space.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Which stiffness axes give way once E touches something, and how fast.
struct StiffnessRelease {
  /// The λ axes [x, y, z, rx, ry, rz] (E's own axes) whose stiffness goes to zero. None by
  /// default: then nothing is ever released.
  std::array<bool, 6> axes{};
  /// Trigger: the norm of the force part of the measured wrench (`set_measured_wrench`) [N]
  /// (> 0). The first tick at or above it starts the release; `start_release` starts it by hand.
  double contact_force = 2.0;
  /// Duration of the smoothstep ramp s(x) = x²(3 − 2x), x = (t − t₀)/duration [s] (> 0).
  double duration = 0.25;
};

// `axes` (six flags) stays undeclared: it is bound by hand
constexpr auto declared_fields(const StiffnessRelease*) {
  using S = StiffnessRelease;
  return declare<S>(
      "se3",
      field("contact_force", &S::contact_force, "N", Range::positive(),
            "the measured force that starts the release"),
      field("duration", &S::duration, "s", Range::positive(), "of the smoothstep ramp"));
}

/// Settings of an `Se3ImpedanceController`. Matrices act on λ = [v; ω] in E's axes (linear
/// first): rows and columns [x, y, z, rx, ry, rz].
struct Se3ImpedanceOptions {
  /// A_λ: desired apparent inertia [kg; kg·m²] (6×6, symmetric positive definite).
  Matrix6d inertia = Matrix6d::Identity();
  /// D_λ: damping [N·s/m; N·m·s/rad] (6×6, symmetric positive definite). The default is
  /// critical for the default A and K: 2·√(1·400) = 40.
  Matrix6d damping = 40.0 * Matrix6d::Identity();
  /// K: stiffness [N/m; N·m/rad] (6×6, symmetric positive semi-definite; positive definite on
  /// the axes that `release` does not name: only a released axis may start at zero stiffness).
  Matrix6d stiffness = 400.0 * Matrix6d::Identity();
  /// Contact-triggered release of stiffness axes.
  StiffnessRelease release;
  /// D_n: null-space joint damping [N·m·s/rad or N·s/m] (≥ 0).
  double nullspace_damping = 5.0;
  /// K_n: null-space posture stiffness towards reference.joint.q [N·m/rad or N/m] (≥ 0), used
  /// when reference.joint.q has n entries.
  double nullspace_stiffness = 0.0;
  /// Cancels the model's passive forces (joint damping, springs: qfrc_passive).
  bool compensate_passive = true;
  /// The floor that bounds Λ near singularities.
  TaskSpaceOptions task_space;
  /// The repulsive joint-limit term (off by default; `JointLimitAvoidance`).
  JointLimitOptions joint_limits;
  /// Feed the desired wrench F_d = reference.task.F_ext (world axes, what E should exert) forward
  /// through the spring: the target is moved by K_ii⁻¹·F_d,i along each of D's axes i that is not
  /// released and has K_ii > 0 (exact for a diagonal K). Off: F_ext is ignored.
  bool wrench_feed_forward = false;
  /// Add the friction feed-forward of the model's dof_frictionloss (a no-op without friction).
  bool friction_feed_forward = false;
  /// Mode and scales of the feed-forward (velocity mode by default). Its `damping` field is
  /// ignored: by_controller with `compensate_passive`, feed_forward without.
  FrictionFeedForwardOptions friction{.mode = FrictionMode::velocity};
};

// the 6×6 matrices stay undeclared: they are checked (symmetric, definite) and bound by hand
constexpr auto declared_fields(const Se3ImpedanceOptions*) {
  using S = Se3ImpedanceOptions;
  return declare<S>("se3",
                    field("release", &S::release, "contact-triggered release of stiffness axes"),
                    field("nullspace_damping", &S::nullspace_damping, "N·m·s/rad or N·s/m",
                          Range::non_negative(), "D_n, null-space joint damping"),
                    field("nullspace_stiffness", &S::nullspace_stiffness, "N·m/rad or N/m",
                          Range::non_negative(), "K_n, null-space posture stiffness"),
                    field("compensate_passive", &S::compensate_passive, "cancel qfrc_passive"),
                    field("task_space", &S::task_space, "the floor of Λ near singularities"),
                    field("joint_limits", &S::joint_limits, "the repulsive joint-limit term"),
                    field("wrench_feed_forward", &S::wrench_feed_forward,
                          "feed F_d = reference.task.F_ext forward through the spring"),
                    field("friction_feed_forward", &S::friction_feed_forward,
                          "add the friction feed-forward of dof_frictionloss"),
                    field("friction", &S::friction, "mode and scales of the feed-forward"));
}

/// Outcome of the last `Se3ImpedanceController::compute`.
enum class Se3ImpedanceStatus {
  ok,              ///< the impedance law ran with the exact Λ
  damped,          ///< the law ran near a singularity: Λ was floored (`TaskSpaceDynamics`)
  invalid_target,  ///< the target pose, twist or acceleration is not finite, or the target's
                   ///< rotation is not a rotation (not orthonormal to 1e-6, or a reflection):
                   ///< the hold command was sent
  invalid_wrench,  ///< the measured wrench is not finite: it was ignored (taken as zero) this
                   ///< tick, the law ran without it
  invalid_state    ///< the state (q, q̇, M, h, J) is not finite or M is not positive definite:
                   ///< the hold command (or zero torque when h is not finite) was sent
};

constexpr auto declared_names(const Se3ImpedanceStatus*) {
  using S = Se3ImpedanceStatus;
  return std::array{EnumName{S::ok, "ok", "the law ran with the exact Λ"},
                    EnumName{S::damped, "damped", "the law ran with Λ floored"},
                    EnumName{S::invalid_target, "invalid_target", "bad target: hold command"},
                    EnumName{S::invalid_wrench, "invalid_wrench", "bad measurement: ignored"},
                    EnumName{S::invalid_state, "invalid_state", "bad state: hold command"}};
}

/// Impedance control on SE(3). Symbols (the paper's → ours; twists linear first [v; ω], every
/// twist and wrench below in E's axes):
///
///     T = X_WE, T_d = X_WD (reference.task.X_WE), T̃ = T⁻¹·T_d = X_ED
///     λ  = log(T̃) = log_error(X_WE, X_WD)                      (‖ω‖ ≤ π, principal branch)
///     V  = body twist of E, V_d = body twist of D, Ṽ = Ad_T̃·V_d − V = vee(dT̃/dt·T̃⁻¹)
///     E  = dexp(λ) = se3::left_jacobian(λ)  (the paper's "right-trivialized" dexp:
///          vee(dT̃/dt·T̃⁻¹) = E·λ̇), λ̇ = E⁻¹·Ṽ, Ė = se3::left_jacobian_derivative(λ, λ̇)
///     γ  = Eᵀ·F̃,  F̃ = −F_E  (F_E: measured wrench of the environment on E, `set_measured_wrench`)
///     λ̈_ref = A⁻¹·(γ − D·λ̇ − K(t)·λ)
///     V̇_ref = Ad_T̃·V̇_d − E·λ̈_ref + ad_Ṽ·V − Ė·λ̇
///     q̈  = J̄_b·(V̇_ref − J̇_b·q̇) + M⁻¹·Nᵀ·τ₀,  τ₀ = K_n·(q_ref − q) − D_n·q̇
///     τ  = M·q̈ + h − τ_passive − J_bᵀ·F_E   [+ the joint-limit term, `joint_limits`]
///     τ += f⊙tanh(q̇/v₀)  or  f⊙tanh(s·τ_m/f), τ_m = τ − h + τ_passive   (`friction_feed_forward`)
///
/// With `wrench_feed_forward`, T_d above is T_d·exp(δ), δ_i = F_d,i/K_ii on D's kept axes
/// (F_d = reference.task.F_ext in D's axes): at rest in contact the spring then pushes with F_d.
///
/// J_b is the body Jacobian of E (V = J_b·q̇), J̄_b = M⁻¹·J_bᵀ·Λ_b its dynamically consistent
/// inverse, N = I − J̄_b·J_b. With the model exact, the measured wrench exact (or zero in free
/// space) and E away from singularities, the λ coordinates then obey A·λ̈ + D·λ̇ + K·λ = γ
/// exactly (not only to first order): the free-space response of λ is that of a linear
/// mass-spring-damper. K(t) = S·K·S with S = diag(1 − s(t)·released_i) during a release.
///
/// Status and hold: see `Se3ImpedanceStatus`; the hold command is τ = h − τ_passive − D_n·q̇.
/// `compute` never throws and never allocates; the torque is always finite.
///
/// Internals: lambda_x … lambda_rz [m; rad], lambda_dot_x … lambda_dot_rz [m/s; rad/s],
/// dexp_condition (σ_max/σ_min of E), task_condition (λ_max/λ_min of J·M⁻¹·Jᵀ), task_damped (1
/// when Λ was floored), release (s ∈ [0, 1], 0 before a release), status (the enum's value). The
/// two condition numbers need an SVD / eigen solve that `compute` does not pay for: they are
/// computed when `internal_values` is read.
class Se3ImpedanceController final : public Controller {
 public:
  /// @throws Error when A or D is not symmetric positive definite, K is not symmetric positive
  /// semi-definite or not positive definite on the axes not released, a release setting or a
  /// null-space gain is out of range, or any entry is not finite.
  explicit Se3ImpedanceController(const Chain& chain, const Se3ImpedanceOptions& options = {});

  std::string_view name() const noexcept override { return "se3"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  const Se3ImpedanceOptions& options() const noexcept { return options_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;

  /// Clears the measured wrench and the release.
  void reset() noexcept override;

  /// The wrench F_E = [f; τ] the environment exerts on E, in E's axes, torque about E's origin
  /// [N; N·m] (from an F/T sensor or an observer), used by the following `compute` calls until
  /// changed. Zero after construction and `reset`. A non-finite wrench is ignored by `compute`
  /// (status invalid_wrench).
  void set_measured_wrench(const Vector6d& F_E) noexcept { wrench_ = F_E; }
  /// The wrench last given to `set_measured_wrench`.
  const Vector6d& measured_wrench() const noexcept { return wrench_; }

  /// Starts the stiffness release at simulated time @p time [s] (no effect when one has
  /// already started or no axis is released).
  void start_release(double time) noexcept;
  /// Disarmed: any release is undone (full stiffness from the next `compute`) and contact
  /// starts none; armed again (the default, and after `reset`): contact starts one.
  void set_release_armed(bool armed) noexcept;
  /// True once a release has started (by contact force or `start_release`).
  bool release_started() const noexcept { return release_started_; }
  /// Release progress s ∈ [0, 1] at the last `compute`.
  double release_fraction() const noexcept { return release_; }
  /// The stiffness K(t) = S·K·S used by the last `compute` [N/m; N·m/rad].
  const Matrix6d& stiffness() const noexcept { return stiffness_now_; }

  /// Status of the last `compute`.
  Se3ImpedanceStatus status() const noexcept { return status_; }
  /// λ = log(X_EW·X_WD) at the last `compute` [m; rad].
  const Vector6d& error() const noexcept { return lambda_; }
  /// λ̇ at the last `compute` [m/s; rad/s].
  const Vector6d& error_rate() const noexcept { return lambda_dot_; }
  /// The reference body acceleration V̇_ref of the last `compute` [m/s²; rad/s²], E's axes.
  const Vector6d& reference_acceleration() const noexcept { return accel_ref_; }
  /// E = dexp(λ) of the last `compute`.
  const Matrix6d& dexp() const noexcept { return dexp_; }
  /// The joint-limit term (its torque of the last `compute` when enabled).
  const JointLimitAvoidance& joint_limits() const noexcept { return limits_; }
  /// The friction feed-forward added by the last `compute` (n; zero when off) [N·m].
  const Eigen::VectorXd& friction_torque() const noexcept { return friction_torque_; }
  /// The target the law used at the last `compute`: reference.task.X_WE moved by the wrench
  /// feed-forward.
  const Pose& shifted_target() const noexcept { return target_; }
  /// The task-space dynamics of the last `compute` (world-aligned Jacobian: Λ_b and J̄_b are
  /// the same up to the rotation blkdiag(R_WE, R_WE)).
  const TaskSpaceDynamics& task_space() const noexcept { return task_space_; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  /// Fills the two condition numbers on demand.
  std::span<const double> internal_values() const noexcept override;

 private:
  /// τ = h − τ_passive − D_n·q̇ (zero when that is not finite), with @p status.
  void hold(const mjData& data, Eigen::Ref<Eigen::VectorXd> tau,
            Se3ImpedanceStatus status) noexcept;
  /// Updates release_ and stiffness_now_ for time @p t.
  void update_release(double t) noexcept;
  void write_values() noexcept;

  Se3ImpedanceOptions options_;
  ChainDynamics dynamics_;
  TaskSpaceDynamics task_space_;
  JointLimitAvoidance limits_;
  FrictionFeedForward friction_;
  bool friction_on_ = false;
  Pose target_;
  Matrix6d inertia_inverse_ = Matrix6d::Identity();
  Vector6d release_mask_ = Vector6d::Zero();  // 1 on released axes
  Vector6d wrench_ = Vector6d::Zero();
  bool release_started_ = false;
  bool release_armed_ = true;
  double release_start_ = 0.0;
  double release_ = 0.0;
  Matrix6d stiffness_now_ = Matrix6d::Zero();
  Se3ImpedanceStatus status_ = Se3ImpedanceStatus::ok;
  Vector6d lambda_ = Vector6d::Zero();
  Vector6d lambda_dot_ = Vector6d::Zero();
  Vector6d accel_ref_ = Vector6d::Zero();
  Matrix6d dexp_ = Matrix6d::Identity();
  // workspace
  Eigen::VectorXd tau0_;             // n
  Eigen::VectorXd null_;             // n
  Eigen::VectorXd passive_;          // n
  Eigen::VectorXd moving_;           // n: τ − h + τ_passive
  Eigen::VectorXd friction_torque_;  // n
  std::array<std::string, 17> names_{
      "lambda_x",      "lambda_y",      "lambda_z",       "lambda_rx",      "lambda_ry",
      "lambda_rz",     "lambda_dot_x",  "lambda_dot_y",   "lambda_dot_z",   "lambda_dot_rx",
      "lambda_dot_ry", "lambda_dot_rz", "dexp_condition", "task_condition", "task_damped",
      "release",       "status"};
  mutable std::array<double, 17> values_{};  // [12], [13] filled by internal_values()
};

}  // namespace mjarm
