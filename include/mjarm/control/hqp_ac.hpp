#pragma once
/// @file
/// `HqpAcController` ("hqp-ac"): hierarchical QP control with adaptive compliance — a main QP
/// in the joint accelerations for a force-adaptive task-space impedance, a null-space QP for
/// singularity avoidance and posture, both under hard joint velocity, position and torque
/// bounds over a look-ahead horizon.

#include <Eigen/Core>
#include <array>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/adaptive_compliance.hpp"
#include "mjarm/control/controller.hpp"
#include "mjarm/control/wrench_source.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/friction_feed_forward.hpp"
#include "mjarm/dynamics/task_space.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/kinematics/manipulability.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/qp/dense_qp.hpp"
#include "mjarm/workspace_ptr.hpp"

namespace mjarm {

/// A force pushed along the insertion axis while E is in contact: ramped in linearly when
/// contact starts, ramped out linearly when it is lost (no latch until `reset`).
struct HqpAcPreload {
  double force = 0.0;  ///< P [N] (≥ 0); 0 (default) disables the preload
  /// The insertion axis in E's own axes (non-zero; normalized): the preload pushes E along it.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double ramp_time = 0.5;      ///< from 0 to P over this [s] (> 0)
  double contact_force = 2.0;  ///< contact starts when the measured ‖f‖ reaches this [N] (> 0)
  /// Contact is lost when the measured ‖f‖ falls below release_ratio·contact_force (in (0, 1]:
  /// the hysteresis keeps a noisy measurement near the threshold from toggling it).
  double release_ratio = 0.5;
  double release_time = 0.2;  ///< from P to 0 over this once contact is lost [s] (> 0)
};

constexpr auto declared_fields(const HqpAcPreload*) {
  using S = HqpAcPreload;
  return declare<S>(
      "hqp-ac", field("force", &S::force, "N", Range::non_negative(), "P; 0: no preload"),
      field("axis", &S::axis, "", Range::finite(), "insertion axis in E's axes (non-zero)"),
      field("ramp_time", &S::ramp_time, "s", Range::positive(), "from 0 to P over this"),
      field("contact_force", &S::contact_force, "N", Range::positive(),
            "contact starts when the measured ‖f‖ reaches this"),
      field("release_ratio", &S::release_ratio, "", Range::open_closed(0.0, 1.0),
            "contact lost below release_ratio·contact_force"),
      field("release_time", &S::release_time, "s", Range::positive(),
            "from P to 0 once contact is lost"));
}

/// Settings of an `HqpAcController`. Defaults are the where it gives them (dt_p, ω_th,
/// k_sa, posture gains, r_min) and ours otherwise (documented in docs/control.md).
struct HqpAcOptions {
  /// K0, the force adaptation and the floor of Λ^½ (see `AdaptiveCompliance`).
  AdaptiveComplianceOptions compliance;
  HqpAcPreload preload;   ///< optional preload along the insertion axis
  double horizon = 0.05;  ///< look-ahead dt_p of the velocity and position bounds [s] (> 0)
  /// |q̇_i| ≤ v_max,i [rad/s or m/s] (> 0): one entry for every joint, or n entries (MJCF has
  /// no joint velocity limit).
  Eigen::VectorXd max_velocity = Eigen::VectorXd::Constant(1, 1.5);
  /// |τ_i| ≤ τ_max,i [N·m or N] (> 0, +inf allowed): empty (default) reads each joint's
  /// actuator range (`joint_torque_range`), one entry for every joint, or n entries.
  Eigen::VectorXd max_torque;
  /// ε of the main QP's Hessian JᵀJ + ε·(tr(JᵀJ)/tr(M))·M (> 0): makes it positive definite
  /// and picks, among the accelerations that realize the task, the one of least kinetic
  /// metric (J̄·b as ε → 0); relative task error ≈ ε/λ_min(J·M⁻¹·Jᵀ)·tr(M)/tr(JᵀJ).
  double regularization = 1e-6;
  double manipulability_threshold = 0.08;  ///< ω_th: singularity avoidance below it (> 0)
  double singularity_gain = 500.0;         ///< k_sa [1/s² per unit ω²] (≥ 0)
  double posture_stiffness = 5.0;          ///< K_p towards the start configuration [1/s²] (≥ 0)
  double posture_damping = 10.0;           ///< D_p [1/s] (≥ 0)
  bool compensate_passive = true;  ///< ĥ = h − τ_passive (cancels joint damping and springs)
  /// Add the friction feed-forward of the model's dof_frictionloss (a no-op without friction);
  /// the torque rows keep room for it (|τ_ff,i| ≤ f_i).
  bool friction_feed_forward = true;
  /// Mode and scales of the feed-forward (velocity mode by default, as for CIC; no damping term:
  /// ĥ cancels the damping with `compensate_passive`, and nothing does without it).
  FrictionFeedForwardOptions friction{.mode = FrictionMode::velocity};
  WrenchSourceOptions force;    ///< where the measured wrench comes from
  TaskSpaceOptions task_space;  ///< the floor of Λ near singularities
  qp::QpSettings qp;            ///< both QPs' solver settings
};

// `qp` stays undeclared: its settings were never checked here (≤ 0 iterations is the default)
constexpr auto declared_fields(const HqpAcOptions*) {
  using S = HqpAcOptions;
  return declare<S>(
      "hqp-ac", field("compliance", &S::compliance, "K0, the force adaptation, the floor of Λ^½"),
      field("preload", &S::preload, "optional preload along the insertion axis"),
      field("horizon", &S::horizon, "s", Range::positive(), "look-ahead dt_p of the bounds"),
      field("max_velocity", &S::max_velocity, "rad/s or m/s", Range::positive(),
            "|q̇_i| ≤ v_max,i: one entry for every joint, or n"),
      field("max_torque", &S::max_torque, "N·m or N", Range::positive().or_infinity(),
            "|τ_i| ≤ τ_max,i: empty (the actuators'), one entry for every joint, or n"),
      field("regularization", &S::regularization, "", Range::positive(),
            "ε of the main QP's Hessian"),
      field("manipulability_threshold", &S::manipulability_threshold, "", Range::positive(),
            "ω_th: singularity avoidance below it"),
      field("singularity_gain", &S::singularity_gain, "1/s² per unit ω²", Range::non_negative(),
            "k_sa"),
      field("posture_stiffness", &S::posture_stiffness, "1/s²", Range::non_negative(),
            "K_p towards the start configuration"),
      field("posture_damping", &S::posture_damping, "1/s", Range::non_negative(), "D_p"),
      field("compensate_passive", &S::compensate_passive,
            "cancel the passive forces (joint damping, springs): ĥ = h − τ_passive"),
      field("friction_feed_forward", &S::friction_feed_forward,
            "add the friction feed-forward of dof_frictionloss"),
      field("friction", &S::friction, "mode and scales of the feed-forward"),
      field("force", &S::force, "where the measured wrench comes from"),
      field("task_space", &S::task_space, "the floor of Λ near singularities"));
}

/// Outcome of the last `HqpAcController::compute`, most severe first in this order:
/// invalid_state, invalid_target, least_squares, null_space_dropped, invalid_wrench, damped, ok.
enum class HqpAcStatus {
  ok,                  ///< both QPs solved; every hard bound holds for q̈ and τ
  damped,              ///< both solved; Λ was floored near a singularity
  invalid_wrench,      ///< the measured wrench was not finite: taken as zero, the QPs ran
  null_space_dropped,  ///< the null-space QP failed: q̈ = the main QP's (bounds hold)
  least_squares,       ///< the main QP failed (infeasible bounds, iteration limit): q̈ = the
                       ///< unconstrained least-squares one clamped into the velocity/position
                       ///< box, τ clipped to the torque limits; the bounds may not all hold
  invalid_target,      ///< target not finite or not a rotation: the hold command
  invalid_state        ///< state not finite or M not positive definite: the hold command
};

constexpr auto declared_names(const HqpAcStatus*) {
  using S = HqpAcStatus;
  return std::array{
      EnumName{S::ok, "ok", "both QPs solved, every bound holds"},
      EnumName{S::damped, "damped", "both solved, Λ floored"},
      EnumName{S::invalid_wrench, "invalid_wrench", "bad measurement: taken as zero"},
      EnumName{S::null_space_dropped, "null_space_dropped", "the null-space QP failed"},
      EnumName{S::least_squares, "least_squares", "the main QP failed: clamped least squares"},
      EnumName{S::invalid_target, "invalid_target", "bad target: hold command"},
      EnumName{S::invalid_state, "invalid_state", "bad state: hold command"}};
}

/// What happened in one tick.
struct HqpAcTick {
  HqpAcStatus status = HqpAcStatus::ok;
  qp::QpStatus main_qp = qp::QpStatus::solved;  ///< status of the main QP (solved if it ran ok)
  qp::QpStatus null_qp = qp::QpStatus::solved;  ///< status of the null-space QP
  bool null_qp_ran = false;     ///< false when the main QP failed (then no null-space step)
  int main_iterations = 0;      ///< active-set steps of the main QP
  int null_iterations = 0;      ///< of the null-space QP
  bool wrench_valid = true;     ///< the measurement was finite
  bool task_damped = false;     ///< Λ floored
  bool torque_clipped = false;  ///< τ had to be clipped to the torque limits (fallback only)
  bool in_contact = false;      ///< the preload's contact state (with hysteresis, no latch)
  double manipulability = 0.0;  ///< ω = √det(J·Jᵀ) of the 6-row J
};

/// Per-tick figures of the two QP solves of the last `compute`, for a recorder or the CLI. Zero
/// when the tick sent the hold command (no QP ran).
struct HqpAcSolveDiagnostics {
  int iterations = 0;          ///< active-set steps of both QPs together
  int main_iterations = 0;     ///< of the main QP
  int null_iterations = 0;     ///< of the null-space QP (0 when it did not run)
  int main_active = 0;         ///< constraints in the main QP's final working set
  int null_active = 0;         ///< in the null-space QP's (its equality rows included)
  int main_constraints = 0;    ///< the main QP's constraints: n torque rows + n bounds
  int null_constraints = 0;    ///< the null-space QP's: 6 equality + n torque rows + n bounds
  double solve_time_us = 0.0;  ///< steady-clock time of both solves [µs] (wall clock: not
                               ///< reproducible, hence not among the internals)
};

constexpr auto declared_fields(const HqpAcSolveDiagnostics*) {
  using S = HqpAcSolveDiagnostics;
  return declare<S>(
      "hqp-ac solve", field("iterations", &S::iterations, "", "active-set steps of both QPs"),
      field("main_iterations", &S::main_iterations, "", "of the main QP"),
      field("null_iterations", &S::null_iterations, "", "of the null-space QP"),
      field("main_active", &S::main_active, "", "constraints active in the main QP"),
      field("null_active", &S::null_active, "", "active in the null-space QP (equalities too)"),
      field("main_constraints", &S::main_constraints, "", "constraints of the main QP"),
      field("null_constraints", &S::null_constraints, "", "constraints of the null-space QP"),
      field("solve_time_us", &S::solve_time_us, "µs", "time of both solves"));
}

/// Counts since construction or `reset` (a fallback is never silent).
struct HqpAcCounters {
  std::int64_t ticks = 0;               ///< computes
  std::int64_t least_squares = 0;       ///< main QP failed
  std::int64_t null_space_dropped = 0;  ///< null-space QP failed
  std::int64_t torque_clipped = 0;      ///< τ clipped (only in a fallback)
  std::int64_t invalid_wrench = 0;
  std::int64_t invalid_target = 0;
  std::int64_t invalid_state = 0;
};

/// Hierarchical QP control with adaptive compliance (HQP-AC). Symbols, world axes, twists and
/// wrenches linear first; e = [p − p_d; −log(R_d·Rᵀ)] = −task_error (x − x_d), Δν = V − V_d:
///
///     K_r, D_r    = AdaptiveCompliance(F_m, Λ⁻¹)          F_m: measured wrench (`WrenchSource`)
///     F_r         = −D_r·Δν − K_r·e
///     F_p         = ramp·P·[R_WE·a; 0]         (ramp rises in contact, falls after;
///     `HqpAcPreload`) b           = A_d + Λ⁻¹·(F_r + F_p) − J̇·q̇              (Λ⁻¹ = J·M⁻¹·Jᵀ,
///     exact)
///   main QP:      min ½‖J·q̈ − b‖² + ½ε_s·q̈ᵀ·M·q̈              → q̈₁
///   null QP:      min ½(q̈ − q̈₁ − q̈₀)ᵀ·M·(q̈ − q̈₁ − q̈₀)  s.t.  J·q̈ = J·q̈₁   → q̈
///                 q̈₀ = k_sa·(ω_th − ω)⁺·∇ω + K_p·(q_start − q) − D_p·q̇
///   both subject to, for every joint i (look-ahead dt_p):
///                 |q̇_i + dt_p·q̈_i| ≤ v_max,i
///                 q_lo,i ≤ q_i + dt_p·q̇_i + ½dt_p²·q̈_i ≤ q_hi,i
///                 τ_lo,i + f_i ≤ (M·q̈ + ĥ)_i ≤ τ_hi,i − f_i        (f_i: friction room)
///     τ = M·q̈ + ĥ + τ_ff,   ĥ = h − τ_passive
///
/// The null QP in the M metric with J·q̈ = J·q̈₁ is the dynamically consistent projection: with
/// no bound active its solution is q̈₁ + N·q̈₀, N = I − J̄·J (J̄ = M⁻¹·Jᵀ·Λ), and it changes
/// neither the task acceleration nor (with the main QP exact) the task-space force. Without
/// contact and with no bound active, Λ·(ë) + D_r·ė + K_r·e = F_p: the closed loop of an
/// impedance with the arm's own inertia, whose damping D_r is critical for commuting Λ, K_r.
///
/// Fallbacks, counted (`counters`) and reported (`last_tick`): the main QP failing gives the
/// least-squares q̈ (the main QP's unconstrained minimizer) clamped into the velocity/position
/// box and τ clipped to the torque limits (`least_squares`); the null-space QP failing drops
/// the null-space step (`null_space_dropped`). The torque is always finite and within the
/// torque limits.
///
/// Internals: position_error [m], orientation_error [rad], force_effective [N],
/// stiffness_scale, preload [N], manipulability, main_iterations, null_iterations,
/// least_squares, null_space_dropped (counts), torque_clipped, status (the enum's value),
/// main_active, null_active (`HqpAcSolveDiagnostics`; its wall-clock time is not an internal).
class HqpAcController final : public Controller {
 public:
  /// @throws Error when an option is out of range (K0 not symmetric positive definite, a
  ///         non-positive horizon, velocity or torque limit, a zero preload axis, a size that is
  ///         neither 1 nor n), or from `WrenchSource` (a missing F/T sensor names the site).
  explicit HqpAcController(const Chain& chain, const HqpAcOptions& options = {});
  ~HqpAcController() override;
  HqpAcController(HqpAcController&& other) noexcept;
  HqpAcController& operator=(HqpAcController&& other) noexcept;

  std::string_view name() const noexcept override { return "hqp-ac"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  const HqpAcOptions& options() const noexcept { return options_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  /// Forgets the start configuration, the contact state and preload, the counters, the observer and
  /// the QPs' warm starts.
  void reset() noexcept override;

  const HqpAcTick& last_tick() const noexcept { return tick_; }
  /// Iterations, active constraints and time of the last compute's QP solves.
  const HqpAcSolveDiagnostics& solve_diagnostics() const noexcept { return diagnostics_; }
  /// The preload's level of the last compute, in [0, 1] (F_p = level·P along the axis).
  double preload_level() const noexcept { return preload_level_; }
  HqpAcStatus status() const noexcept { return tick_.status; }
  const HqpAcCounters& counters() const noexcept { return counters_; }

  /// The commanded joint acceleration q̈ of the last compute (n) [rad/s²].
  const Eigen::VectorXd& acceleration() const noexcept { return qdd_; }
  /// The main QP's solution q̈₁ (n) [rad/s²].
  const Eigen::VectorXd& task_acceleration() const noexcept { return qdd1_; }
  /// The null-space goal q̈₀ (n) [rad/s²].
  const Eigen::VectorXd& nullspace_goal() const noexcept { return qdd0_; }
  /// The bounds of the last compute on q̈ (n each) [rad/s²]: the velocity/position box …
  const Eigen::VectorXd& acceleration_lower() const noexcept { return lb_; }
  const Eigen::VectorXd& acceleration_upper() const noexcept { return ub_; }
  /// … and on τ = M·q̈ + ĥ (+ the friction room) [N·m]: the limits the torque respects.
  const Eigen::VectorXd& torque_lower() const noexcept { return tau_lo_; }
  const Eigen::VectorXd& torque_upper() const noexcept { return tau_hi_; }
  /// The joint velocity limits in use (n).
  const Eigen::VectorXd& velocity_limit() const noexcept { return v_max_; }
  /// The main QP's target b (task acceleration minus J̇·q̇) [m/s²; rad/s²].
  const Vector6d& target() const noexcept { return b_; }
  /// The preload force F_p of the last compute (world) [N].
  const Eigen::Vector3d& preload_force() const noexcept { return preload_force_; }
  /// The measured wrench used by the last compute (world axes, about E) [N; N·m].
  const Vector6d& measured_wrench() const noexcept { return wrench_; }
  const AdaptiveCompliance& compliance() const noexcept { return compliance_; }
  const ChainDynamics& dynamics() const noexcept { return dynamics_; }
  const TaskSpaceDynamics& task_space() const noexcept { return task_space_; }
  const WrenchSource& wrench_source() const noexcept { return source_; }
  /// The start configuration the posture pulls towards (n; set by the first compute).
  const Eigen::VectorXd& start_configuration() const noexcept { return q_start_; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  void hold(const mjData& data, Eigen::Ref<Eigen::VectorXd> tau, HqpAcStatus status) noexcept;
  void update_bias(const mjData& data) noexcept;
  void build_bounds() noexcept;
  bool solve_main() noexcept;
  void least_squares() noexcept;
  void null_goal() noexcept;
  bool solve_null() noexcept;
  void finish(HqpAcStatus status) noexcept;
  /// Contact (with hysteresis) from the measured ‖f‖ @p force, and the preload's level.
  void update_preload(double force, double time) noexcept;
  void record_solve(std::chrono::steady_clock::time_point start, int iterations, int active,
                    bool null_space) noexcept;

  HqpAcOptions options_;
  ChainDynamics dynamics_;
  TaskSpaceDynamics task_space_;
  AdaptiveCompliance compliance_;
  Manipulability manipulability_;
  WrenchSource source_;
  FrictionFeedForward friction_;
  bool friction_on_ = false;
  qp::DenseQp main_qp_;
  qp::DenseQp null_qp_;
  // the Cholesky factors of the fallback's least squares and of J·Jᵀ (in the .cpp:
  // Eigen/Cholesky)
  struct Factors;
  WorkspacePtr<Factors> factors_;
  // fixed per chain
  Eigen::VectorXd v_max_, tau_min_, tau_max_, friction_room_, q_lo_, q_hi_;
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();
  // state across ticks
  Eigen::VectorXd q_start_;
  bool has_start_ = false;
  bool in_contact_ = false;
  double preload_level_ = 0.0;  // in [0, 1]
  double preload_from_ = 0.0;   // the level when contact last changed
  double contact_time_ = 0.0;   // when contact last changed [s]
  HqpAcTick tick_;
  HqpAcSolveDiagnostics diagnostics_;
  HqpAcCounters counters_;
  // workspace
  Vector6d wrench_ = Vector6d::Zero();
  Vector6d b_ = Vector6d::Zero();
  Eigen::Vector3d preload_force_ = Eigen::Vector3d::Zero();
  Eigen::MatrixXd H_, M_;            // n×n
  Eigen::VectorXd g_, h_hat_;        // n
  Eigen::VectorXd lb_, ub_;          // n: the velocity/position box on q̈
  Eigen::VectorXd tau_lo_, tau_hi_;  // n: torque limits less the friction room
  Eigen::VectorXd row_lo_, row_hi_;  // n: the torque rows' limits on M·q̈
  Eigen::VectorXd null_lb_, null_ub_, null_row_lo_, null_row_hi_;  // n: widened for the null QP
  Eigen::VectorXd qdd1_, qdd0_, qdd_, gradient_, goal_, beq_, tau_ff_;  // n
  Eigen::MatrixXd J_;                                                   // 6×n
  Matrix6d gram_ = Matrix6d::Zero();                                    // J·Jᵀ
  std::array<std::string, 14> names_{"position_error",     "orientation_error", "force_effective",
                                     "stiffness_scale",    "preload",           "manipulability",
                                     "main_iterations",    "null_iterations",   "least_squares",
                                     "null_space_dropped", "torque_clipped",    "status",
                                     "main_active",        "null_active"};
  std::array<double, 14> values_{};
};

}  // namespace mjarm
