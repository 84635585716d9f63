#pragma once
/// @file
/// Inverse kinematics for several frames at once (e.g. both hands and the lift of a bimanual
/// robot), all moved by ONE shared list of joints, in two modes:
/// - stacked: every target's weighted rows in one damped least-squares problem, a compromise
///   when targets conflict;
/// - prioritized: strict task priorities. Levels (targets of equal `priority`, stacked) are
///   solved in order, each in the null space of all levels before it, by the recursion
///     Δq₀ = motion of pinned joints (none at first), N₀ = diag(free joints),
///     J̃ₖ = Jₖ·Nₖ₋₁,   Δqₖ = Δqₖ₋₁ + J̃ₖᵀ(J̃ₖJ̃ₖᵀ + λₖ²I)⁻¹·(Wₖeₖ − JₖΔqₖ₋₁),
///     Nₖ = Nₖ₋₁ − J̃ₖᵀ(J̃ₖJ̃ₖᵀ + ε²I)⁻¹J̃ₖ,
///   with damped pseudo-inverses (λₖ² = damping² + error_damping·½‖Wₖeₖ‖², ε ≪ λ for the
///   projectors), so a lower level can never pull a higher one off its target.
/// Each target's residual and Jacobian are those of targets.hpp (world position error, or the
/// body log error with Jlog·J_E). Posture and limit terms act in the null space of all levels.
/// Joints a step would carry past a limit are pinned on it and the recursion reruns without
/// them; steps are halved while they make the result worse (lexicographically by level in
/// prioritized mode) or touch a watched geom.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/ik/damped_least_squares.hpp"
#include "mjarm/ik/local_ik_settings.hpp"
#include "mjarm/ik/local_ik_workspace.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"

namespace mjarm {

/// How several targets are combined.
enum class MultiTargetMode {
  stacked,     ///< one weighted damped least-squares problem (priorities ignored)
  prioritized  ///< strict priorities by recursive null-space projection
};

constexpr auto declared_names(const MultiTargetMode*) {
  using M = MultiTargetMode;
  return std::array{
      EnumName{M::stacked, "stacked", "one weighted damped least-squares problem"},
      EnumName{M::prioritized, "prioritized", "strict priorities by null-space projection"}};
}

/// Every constant of `MultiTargetIk`: the shared local-IK settings (local_ik_settings.hpp, all
/// at their defaults), the mode, the error-proportional damping and the per-target tolerances.
/// Row weights and priorities belong to each `FrameTarget`. Its stall measure is the sum over
/// the targets of max(position error / tolerance, angle / tolerance) at the current iterate.
struct MultiTargetIkOptions : LocalIkSettings {
  MultiTargetMode mode = MultiTargetMode::prioritized;  ///< how targets are combined
  double error_damping = 0.5;        ///< adds this × ½‖Wₖeₖ‖² to λₖ² (finite, ≥ 0)
  double position_tolerance = 1e-5;  ///< per target: ‖p_WT − p_WE‖ ≤ this [m] (> 0)
  double orientation_tolerance = 1e-5;  ///< per pose target: rotation angle ≤ this [rad] (> 0)
};

/// The fields of its own (the shared ones are `LocalIkSettings`'s).
constexpr auto declared_fields(const MultiTargetIkOptions*) {
  using S = MultiTargetIkOptions;
  return declare<S>("multi-target IK", field("mode", &S::mode, "how targets are combined"),
                    field("error_damping", &S::error_damping, "", Range::non_negative(),
                          "adds this × ½‖Wₖeₖ‖² to λₖ²"),
                    field("position_tolerance", &S::position_tolerance, "m", Range::positive(),
                          "per target: ‖p_WT − p_WE‖ ≤ this"),
                    field("orientation_tolerance", &S::orientation_tolerance, "rad",
                          Range::positive(), "per pose target: rotation angle ≤ this"));
}

/// @throws Error naming the offending option ("multi-target IK: step must be in (0, 1], got
/// 0").
void check(const MultiTargetIkOptions& options);

/// Multi-target IK solver: construct once, move targets with `set_target`, solve many times.
/// After construction, `solve(q_seed, result)` with a result of the right size allocates
/// nothing. Never touches any caller's `mjData`.
class MultiTargetIk {
 public:
  /// @param robot the model
  /// @param joints the joints every target shares (chain order = order of q)
  /// @param targets one or more targets; each frame must be moved by at least one joint
  /// @throws Error for unknown joints or frames, a frame no joint moves, invalid target poses
  /// or weights, negative priorities, invalid options or unknown collision geoms.
  MultiTargetIk(const Robot& robot, const std::vector<std::string>& joints,
                const std::vector<FrameTarget>& targets, const MultiTargetIkOptions& options = {});

  /// The shared joints (with the first target's frame).
  const Chain& chain() const noexcept { return targets_.front().kin.chain(); }
  const MultiTargetIkOptions& options() const noexcept { return options_; }
  int target_count() const noexcept { return static_cast<int>(targets_.size()); }
  /// Target @p i as given (pose updated by `set_target`).
  const FrameTarget& target(int i) const { return targets_.at(i).target; }

  /// Moves target @p i (position targets use X_WT.p only). Allocates nothing.
  /// @throws Error for an index out of range or a non-finite pose / non-rotation.
  void set_target(int i, const Pose& X_WT);

  /// Sets the joints outside the shared list (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Solves from @p q_seed (n, clipped into the limits first). The result holds the worst
  /// position and orientation errors over all targets; `target_errors(i)` has each one.
  /// @throws Error when q_seed has the wrong size or holds NaN/inf, or is in contact.
  IkResult solve(const Eigen::Ref<const Eigen::VectorXd>& q_seed);

  /// The same, writing into @p result (allocation-free once result.q has n entries).
  void solve(const Eigen::Ref<const Eigen::VectorXd>& q_seed, IkResult& result);

  /// Errors of target @p i at the configuration returned by the last solve.
  const FrameErrors& target_errors(int i) const { return targets_.at(i).result_errors; }

 private:
  struct TargetSlot {
    FrameTarget target;
    ChainKinematics kin;
    int level = 0;
    int row = 0;                // first row in its level
    FrameErrors errors;         // at the current iterate
    FrameErrors trial_errors;   // at the trial iterate
    FrameErrors best_errors;    // at the best iterate
    FrameErrors result_errors;  // at the returned configuration
  };
  struct Level {
    int rows = 0;
    Eigen::MatrixXd J;        // weighted task Jacobian (rows × n)
    Eigen::VectorXd e;        // weighted residual (rows)
    Eigen::MatrixXd J_tilde;  // J·N of the levels above
    Eigen::VectorXd r, dq;
    DampedLeastSquares step, null;
  };
  /// Per-level (converged, objective) of the current or trial evaluation, for comparisons.
  struct Score {
    std::vector<char> converged;
    std::vector<double> objective;
    double total = 0.0;  // Σ over targets of max(position/tol, orientation/tol)
    double worst = 0.0;  // the largest of these
  };

  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& q, bool trial, Score& score) noexcept;
  bool better(const Score& a, const Score& b) const noexcept;
  bool all_converged(const Score& s) const noexcept;
  /// Calls options_.on_iteration with the worst errors of the current iterate.
  void report_iteration(int iteration) const;
  /// The limit-aware prioritized step into the workspace; false when it is not finite.
  bool compute_step() noexcept;

  MultiTargetIkOptions options_;
  std::vector<TargetSlot> targets_;
  std::vector<Level> levels_;
  // iterate, step, secondary terms, collision guard: built once the targets are validated (the
  // constructor reports a bad target before a wrong-sized q_pref or an unknown collision geom)
  std::optional<LocalIkWorkspace> local_;
  // workspace
  Matrix6Xd J_scratch_;
  Eigen::MatrixXd N_, P_;
  Eigen::VectorXd projected_bias_;
  Score current_, trial_, best_;
};

}  // namespace mjarm
