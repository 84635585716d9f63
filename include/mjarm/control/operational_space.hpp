#pragma once
/// @file
/// `OperationalSpaceController`: operational-space impedance control (Khatib's formulation) of the
/// chain's frame E, in translation and rotation, with an external-wrench term, null-space
/// damping/posture and an optional integral term with anti-windup.

#include <array>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/joint_limit_avoidance.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/task_space.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Settings of an `OperationalSpaceController`. Task entries are [x, y, z, rx, ry, rz] in world
/// axes; in `TaskMode::position` only the first three are used (and checked).
struct OperationalSpaceOptions {
  TaskMode mode = TaskMode::pose;  ///< 6-D pose or 3-D position task
  /// K: stiffness [N/m; N·m/rad] (≥ 0).
  Vector6d stiffness = Vector6d::Constant(400.0);
  /// D: damping [N·s/m; N·m·s/rad]. A negative entry means "critical": 2ζ·√(m_i·K_i), with m_i
  /// the desired inertia (or Λ_ii with `task_inertia`).
  Vector6d damping = Vector6d::Constant(-1.0);
  /// ζ used for the negative (automatic) damping entries (> 0; 1 = critical).
  double damping_ratio = 1.0;
  /// M_d: desired apparent inertia [kg; kg·m²] (> 0). The default of 1 makes K and D per unit
  /// mass: every direction then closes at ω_n = √K.
  Vector6d inertia = Vector6d::Ones();
  /// Keep the arm's own task inertia (M_d = Λ(q), no inertia shaping) instead of `inertia`:
  /// the closed loop is then a passive spring-damper Λ·ë + D·ė + K·e = f_contact.
  bool task_inertia = false;
  /// K_i: integral gain [N/(m·s); N·m/(rad·s)] (≥ 0); 0 disables the integral term.
  Vector6d integral_gain = Vector6d::Zero();
  /// Anti-windup: each entry of ∫e dt is clamped to ±limit [m·s; rad·s] (≥ 0).
  Vector6d integral_limit = (Vector6d() << 0.02, 0.02, 0.02, 0.05, 0.05, 0.05).finished();
  /// D_n: null-space joint damping [N·m·s/rad or N·s/m] (≥ 0).
  double nullspace_damping = 5.0;
  /// K_n: null-space posture stiffness towards reference.joint.q [N·m/rad or N/m] (≥ 0), used
  /// when reference.joint.q has n entries.
  double nullspace_stiffness = 0.0;
  /// Cancels the model's passive forces (joint damping, springs: qfrc_passive).
  bool compensate_passive = true;
  /// Render the desired inertia M_d exactly against contact with the measured wrench F_m
  /// (`set_measured_wrench`): F = Λ·(A_WD + M_d⁻¹·(f + F_m + F_ext) − J̇·q̇) − F_m, so that
  /// M_d·ë + D·ė + K·e = −(F_c + F_ext) with F_c the true contact wrench when F_m = F_c. Off:
  /// F_m is not used by the law (contact then meets the arm's own Λ). No effect with
  /// `task_inertia` (M_d = Λ needs no measurement).
  bool wrench_feedback = false;
  /// The integral ∫e is held (not integrated) while the force part of the measured wrench has
  /// a norm ≥ this [N] (> 0; +infinity, the default: never held).
  double integral_hold_force = std::numeric_limits<double>::infinity();
  /// The floor that bounds Λ near singularities.
  TaskSpaceOptions task_space;
  /// The repulsive joint-limit term (off by default), split between the null space and the
  /// full joint space (`JointLimitAvoidance`).
  JointLimitOptions joint_limits;
};

constexpr auto declared_fields(const OperationalSpaceOptions*) {
  using S = OperationalSpaceOptions;
  return declare<S>(
      "osc", field("mode", &S::mode, "6-D pose or 3-D position task"),
      field("stiffness", &S::stiffness, "N/m; N·m/rad", Range::non_negative(), "K"),
      field("damping", &S::damping, "N·s/m; N·m·s/rad", Range::finite(),
            "D; a negative entry: critical, 2ζ·√(m_i·K_i)"),
      field("damping_ratio", &S::damping_ratio, "", Range::positive(),
            "ζ of the automatic damping entries"),
      field("inertia", &S::inertia, "kg; kg·m²", Range::positive(), "M_d, desired inertia"),
      field("task_inertia", &S::task_inertia, "keep the arm's own Λ instead of M_d"),
      field("integral_gain", &S::integral_gain, "N/(m·s); N·m/(rad·s)", Range::non_negative(),
            "K_i; 0: no integral term"),
      field("integral_limit", &S::integral_limit, "m·s; rad·s", Range::non_negative(),
            "anti-windup bound on each entry of ∫e"),
      field("nullspace_damping", &S::nullspace_damping, "N·m·s/rad or N·s/m", Range::non_negative(),
            "D_n, null-space joint damping"),
      field("nullspace_stiffness", &S::nullspace_stiffness, "N·m/rad or N/m", Range::non_negative(),
            "K_n, null-space posture stiffness"),
      field("compensate_passive", &S::compensate_passive, "cancel qfrc_passive"),
      field("wrench_feedback", &S::wrench_feedback, "render M_d with the measured wrench"),
      field("integral_hold_force", &S::integral_hold_force, "N", Range::positive().or_infinity(),
            "∫e held while ‖f_m‖ ≥ this; +inf: never"),
      field("task_space", &S::task_space, "the floor of Λ near singularities"),
      field("joint_limits", &S::joint_limits, "the repulsive joint-limit term"));
}

/// Operational-space impedance control. Each tick, with J the world-aligned Jacobian (its first
/// 3 rows in position mode), Λ = (J·M⁻¹·Jᵀ)⁻¹ (bounded near singularities, `TaskSpaceDynamics`)
/// and N = I − J̄·J its dynamically consistent null-space projector:
///
///     e  = task_error(X_WE, X_WD),  ė = V_WD − J·q̇,  ∫e += e·Δt (clamped to ±limit)
///     f  = K·e + D·ė + K_i·∫e                                   (impedance wrench, m rows)
///     u  = A_WD + M_d⁻¹·f                                        (desired task acceleration)
///     F  = Λ·(u − J̇·q̇) + F_ext           (with task_inertia: F = Λ·(A_WD − J̇·q̇) + f + F_ext;
///                                          with wrench_feedback, see the option)
///     τ  = Jᵀ·F + h − τ_passive + Nᵀ·(K_n·(q_ref − q) − D_n·q̇)  [+ the joint-limit term]
///
/// h = C·q̇ + g is MuJoCo's qfrc_bias on the chain's dofs, τ_passive its qfrc_passive. With the
/// model exact and no contact, M_d·ë + D·ė + K·e = 0 in free motion (to first order in the
/// orientation error); F_ext (reference.task.F_ext) is the wrench E should exert on the
/// environment, fed forward. Δt is the change of data.time since the previous compute (0 on the
/// first call after `reset`). Reads reference.task and, for the posture, reference.joint.q.
///
/// Internals: position_error [m], orientation_error [rad], lambda_condition (condition number of
/// J·M⁻¹·Jᵀ), lambda_damped (1 when Λ was floored), integral_x … integral_rz [m·s, rad·s].
/// lambda_condition needs the eigenvalues of J·M⁻¹·Jᵀ, which the fast path of
/// `TaskSpaceDynamics` skips: it is computed when `internal_values` is read, not in `compute`.
class OperationalSpaceController final : public Controller {
 public:
  /// @throws Error when a gain, inertia, ratio or limit is out of range or not finite.
  explicit OperationalSpaceController(const Chain& chain,
                                      const OperationalSpaceOptions& options = {});

  std::string_view name() const noexcept override { return "osc"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  const OperationalSpaceOptions& options() const noexcept { return options_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;

  /// Clears the integral and the time of the previous tick.
  void reset() noexcept override;

  /// The wrench F_m the environment exerts on E (world axes, torque about E's origin) [N; N·m],
  /// from an F/T sensor or an observer (`WrenchSource`), used by the following `compute` calls
  /// until changed: by the law with `wrench_feedback`, and to hold the integral
  /// (`integral_hold_force`). Zero after construction and `reset`. A non-finite wrench is taken
  /// as zero.
  void set_measured_wrench(const Vector6d& F_W) noexcept { wrench_ = F_W; }
  /// The wrench last given to `set_measured_wrench`.
  const Vector6d& measured_wrench() const noexcept { return wrench_; }
  /// True when the last `compute` held the integral (measured force at or above the threshold).
  bool integral_held() const noexcept { return integral_held_; }
  /// The joint-limit term (its torque of the last `compute` when enabled).
  const JointLimitAvoidance& joint_limits() const noexcept { return limits_; }
  /// The joint-space dynamics of the last `compute` (M, h, J, pose of E).
  const ChainDynamics& dynamics() const noexcept { return dynamics_; }

  /// ∫e dt after the last `compute` (first m entries used) [m·s; rad·s].
  const Vector6d& integral() const noexcept { return integral_; }
  /// Task-space force F of the last `compute` (first m entries used) [N; N·m].
  const Vector6d& task_force() const noexcept { return force_; }
  /// The task-space dynamics of the last `compute` (Λ, J̄, N, status).
  const TaskSpaceDynamics& task_space() const noexcept { return task_space_; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  /// Fills lambda_condition on demand (an eigenvalue solve `compute` does not pay for).
  std::span<const double> internal_values() const noexcept override;

 private:
  OperationalSpaceOptions options_;
  int rows_ = 6;
  ChainDynamics dynamics_;
  TaskSpaceDynamics task_space_;
  JointLimitAvoidance limits_;
  Vector6d damping_ = Vector6d::Zero();  // D with the automatic entries resolved (fixed M_d)
  Vector6d integral_ = Vector6d::Zero();
  Vector6d force_ = Vector6d::Zero();
  Vector6d wrench_ = Vector6d::Zero();  // measured F_m
  bool integral_held_ = false;
  double last_time_ = 0.0;
  bool has_last_time_ = false;
  // workspace
  Eigen::VectorXd tau0_;     // n
  Eigen::VectorXd null_;     // n
  Eigen::VectorXd passive_;  // n
  std::array<std::string, 10> names_{
      "position_error", "orientation_error", "lambda_condition", "lambda_damped", "integral_x",
      "integral_y",     "integral_z",        "integral_rx",      "integral_ry",   "integral_rz"};
  mutable std::array<double, 10> values_{};  // [2] filled by internal_values()
};

}  // namespace mjarm
