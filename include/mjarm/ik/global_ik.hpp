#pragma once
/// @file
/// Global pose IK in the spirit of TRAC-IK: seeded random restarts of two different local
/// methods until a solution (or the best of several) is found or a time budget runs out.
///
/// Local methods, alternated per restart (the first attempt starts from the caller's seed, every
/// later one from a configuration drawn uniformly inside the joint limits):
/// - Levenberg–Marquardt on the 6-D world-aligned error e = [p_WT − p_WE; log(R_WT·R_WEᵀ)]
///   with the world-aligned Jacobian: Δq = Jᵀ(JJᵀ + λI)⁻¹e, λ = μ·½‖e‖² + λ₀ (adaptive: heavy
///   far from the target and across wrist singularities, vanishing at the solution for fast
///   final convergence), then q ← clamp(q + Δq). A step that raises the error is rejected and μ
///   grows.
/// - SQP-like: the differential-IK QP with the joint limits as constraints, iterated:
///   min ½‖JΔq − e‖² + ½λ‖Δq‖² s.t. lower − q ≤ Δq ≤ upper − q, |Δq_i| ≤ max_step (DenseQp),
///   same damping and acceptance. Its unconstrained minimizer is the LM step, so the QP is only
///   solved when that step leaves the box; a joint at a limit then slides along it instead of
///   being clipped, which is what rescues targets that LM's clamping gets stuck on.
/// An attempt ends as soon as the TRAC-IK criterion holds (PoseTolerance: every component of the
/// target-frame error within its bound; joints always within limits), or it restarts when the
/// error has not dropped enough over a few iterations (local minimum, joint stuck at a limit)
/// or after an iteration cap.
///
/// Determinism: the random generator is std::mt19937_64 seeded with `GlobalIkOptions::seed` at
/// the start of every solve, doubles are drawn from its raw 64-bit output, and nothing else
/// carries over between solves. The same seed, target and q_seed therefore give the same bits
/// whenever the solve ends for a reason other than the clock (a solution in `speed` mode, or
/// `max_restarts` reached); a timeout cuts the same sequence at a time-dependent point.

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <limits>
#include <optional>

#include "mjarm/ik/analytic_ik.hpp"
#include "mjarm/ik/pose_tolerance.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/qp/dense_qp.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

/// Which solution `GlobalIk` returns.
enum class GlobalIkMode {
  speed,     ///< the first solution found
  distance,  ///< the solution closest to the seed (‖q − q_seed‖₂) found before the budget ends
  manipulability  ///< the solution with the largest √det(J Jᵀ) found before the budget ends
};

/// Which local methods the restarts use.
enum class GlobalIkMethods {
  alternate,            ///< Levenberg–Marquardt, SQP, Levenberg–Marquardt, ... (default)
  levenberg_marquardt,  ///< Levenberg–Marquardt only
  sqp                   ///< iterated differential-IK QP only
};

constexpr auto declared_names(const GlobalIkMode*) {
  using M = GlobalIkMode;
  return std::array{EnumName{M::speed, "speed", "the first solution found"},
                    EnumName{M::distance, "distance", "the solution closest to the seed"},
                    EnumName{M::manipulability, "manipulability",
                             "the solution with the largest √det(J Jᵀ)"}};
}

constexpr auto declared_names(const GlobalIkMethods*) {
  using M = GlobalIkMethods;
  return std::array{
      EnumName{M::alternate, "alternate", "Levenberg–Marquardt and SQP in turn"},
      EnumName{M::levenberg_marquardt, "levenberg_marquardt", "Levenberg–Marquardt only"},
      EnumName{M::sqp, "sqp", "iterated differential-IK QP only"}};
}

/// The longest stall window of `GlobalIk` (`GlobalIkOptions::stall_iterations` ≤ this).
inline constexpr int kGlobalIkMaxStallWindow = 64;

/// Options of `GlobalIk`.
struct GlobalIkOptions {
  GlobalIkMode mode = GlobalIkMode::speed;               ///< which solution to return
  GlobalIkMethods methods = GlobalIkMethods::alternate;  ///< local methods used
  /// Wall-clock budget of one solve (finite, > 0). `distance` and `manipulability` use all of
  /// it unless `max_restarts` ends the search first. A budget beyond the steady clock's range
  /// (about 146 years) never expires.
  std::chrono::duration<double> timeout = std::chrono::milliseconds(5);
  PoseTolerance tolerance;  ///< acceptance test (default: TRAC-IK's 1e-5 on each component)
  /// Restarts after the first attempt (≥ 0); the default is unbounded (the timeout decides).
  int max_restarts = std::numeric_limits<int>::max();
  std::uint64_t seed = 0;  ///< seed of the restart generator
  // tuning of the local methods (defaults measured on panda, iiwa14 and ur5e)
  /// Iterations per attempt before a restart (≥ 1).
  int max_attempt_iterations = 40;
  /// Restart when ½‖e‖² has not dropped below stall_ratio × its value stall_iterations
  /// iterations ago (stall_iterations in [1, 64], stall_ratio in (0, 1)).
  int stall_iterations = 4;
  double stall_ratio = 0.5;  ///< see stall_iterations
  /// λ₀, the floor of the adaptive damping λ = μ·½‖e‖² + λ₀ [m², rad²] (> 0). Small, so that
  /// targets at singular configurations still converge fast.
  double damping = 1e-9;
  double max_step = 1.0;  ///< largest joint change per iteration [rad or m] (> 0)
  /// Pose targets in speed or distance mode: when the chain is a 6R arm of a closed-form family
  /// (analytic_ik.hpp) on a fixed base, try its branch closest to the seed within the limits
  /// first; the restarts run only when that branch misses the tolerance.
  bool analytic = true;
};

/// The fields of `GlobalIkOptions` but the timeout and the tolerance (checked by hand).
constexpr auto declared_fields(const GlobalIkOptions*) {
  using S = GlobalIkOptions;
  return declare<S>(
      "global IK", field("mode", &S::mode, "which solution to return"),
      field("methods", &S::methods, "local methods the restarts use"),
      field("max_restarts", &S::max_restarts, "", Range::non_negative(),
            "restarts after the first attempt"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of the restart generator"),
      field("max_attempt_iterations", &S::max_attempt_iterations, "", Range::at_least(1),
            "iterations per attempt before a restart"),
      field("stall_iterations", &S::stall_iterations, "", Range::closed(1, kGlobalIkMaxStallWindow),
            "window of the stall test"),
      field("stall_ratio", &S::stall_ratio, "", Range{0.0, 1.0, true, true, false},
            "restart when ½‖e‖² has not dropped below this × its value a window ago"),
      field("damping", &S::damping, "m², rad²", Range::positive(),
            "λ₀, the floor of the adaptive damping"),
      field("max_step", &S::max_step, "rad or m", Range::positive(),
            "largest joint change per iteration"),
      field("analytic", &S::analytic,
            "try the closed-form branches first (6R spherical-wrist or UR arms)"));
}

/// @throws Error naming the offending option.
void check(const GlobalIkOptions& options);

/// What the last `GlobalIk::solve` did (diagnostics).
struct GlobalIkStats {
  int attempts = 0;             ///< local runs started (1 + restarts)
  int solutions = 0;            ///< attempts that met the tolerance
  int lm_solutions = 0;         ///< ... of which by Levenberg–Marquardt
  int sqp_solutions = 0;        ///< ... of which by the SQP method
  double manipulability = 0.0;  ///< √det(J Jᵀ) at the returned q (0 without a solution)
  double elapsed = 0.0;         ///< wall-clock time of the solve [s]
  bool analytic = false;        ///< the solution is a closed-form branch (no attempt was run)
};

/// Global pose IK for one chain's frame (see the file comment). Construct once, solve many
/// times; after construction `solve(X_WT, q_seed, result)` allocates nothing once result.q has
/// n entries. Uses ChainKinematics only (no mjData).
class GlobalIk {
 public:
  /// @throws Error for invalid options.
  explicit GlobalIk(const Chain& chain, const GlobalIkOptions& options = {});

  const Chain& chain() const noexcept { return kin_.chain(); }
  const GlobalIkOptions& options() const noexcept { return options_; }
  /// Replaces the options (no allocation).
  /// @throws Error for invalid options.
  void set_options(const GlobalIkOptions& options);

  /// Sets the joints outside the chain (full qpos, nq entries; default qpos0).
  /// @throws Error for a wrong size or NaN.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Finds q (n) with the chain frame at X_WT, starting from @p q_seed (n; clipped into the
  /// limits). Status: converged (a solution; in distance/manipulability mode the best one found),
  /// timeout (budget spent without a solution: q is the best iterate, with its errors),
  /// not_converged (max_restarts reached without a solution), invalid_input (every iterate was
  /// NaN; q is the clipped seed). The returned q is always within the joint limits.
  /// @throws Error for a non-finite or non-rotation target, or a seed of the wrong size / NaN.
  IkResult solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed);

  /// The same, writing into @p result (allocation-free once result.q has n entries).
  void solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed, IkResult& result);

  /// Position only: finds q (n) with the chain frame's origin at @p p_WT (m, world) and any
  /// orientation, by the same restarts and local methods on the 3 translational rows. The
  /// tolerance's x, y, z bounds apply to the world components of p_WT − p_WE (its rotation
  /// bounds are unused); status as for `solve`; orientation_error is 0; in manipulability mode
  /// the score is √det(J_v J_vᵀ) of the translational Jacobian.
  /// @throws Error for a non-finite target, or a seed of the wrong size / NaN.
  IkResult solve_position(const Eigen::Vector3d& p_WT,
                          const Eigen::Ref<const Eigen::VectorXd>& q_seed);

  /// The same, writing into @p result (allocation-free once result.q has n entries).
  void solve_position(const Eigen::Vector3d& p_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed,
                      IkResult& result);

  /// Diagnostics of the last solve.
  const GlobalIkStats& stats() const noexcept { return stats_; }

 private:
  enum class Outcome { converged, stalled, timeout, invalid };
  using Clock = std::chrono::steady_clock;

  /// The restart loop of both solves, on the target already in X_WT_ / position_only_.
  void search(const Eigen::Ref<const Eigen::VectorXd>& q_seed, IkResult& result);
  /// J_ at kin_'s configuration (rotation rows zero for a position target).
  void update_jacobian() noexcept;
  double evaluate(const Eigen::VectorXd& q, Vector6d& e) noexcept;
  bool converged(const Vector6d& e) const noexcept;
  Outcome run_attempt(bool use_sqp, Clock::time_point deadline, int& iterations) noexcept;
  void random_configuration(Eigen::VectorXd& q) noexcept;
  double uniform() noexcept;
  double manipulability() noexcept;
  /// The closed-form branch closest to q_seed_ within the limits into q_ (e_, E_ evaluated);
  /// true when it meets the tolerance.
  bool solve_analytically();

  GlobalIkOptions options_;
  ChainKinematics kin_;
  qp::DenseQp qp_;
  Random rng_;
  GlobalIkStats stats_;
  std::optional<AnalyticIk> analytic_;  // when the chain has a closed form
  AnalyticIkSolution analytic_solution_;
  Eigen::VectorXd sample_lower_, sample_upper_;  // random-restart box (finite)
  // per-solve state
  Pose X_WT_;
  bool position_only_ = false;  // solve_position: the rotation part of e and J is zero
  Vector6d e_;                  // world-aligned error at q_
  Vector6d e_trial_;
  double E_ = 0.0;   // ½‖e‖² at q_
  double mu_ = 0.1;  // LM damping scale
  // workspace
  Matrix6Xd J_;
  Eigen::MatrixXd H_;
  Eigen::VectorXd q_, q_trial_, dq_, g_, lb_, ub_, q_seed_, q_best_, q_solution_;
};

}  // namespace mjarm
