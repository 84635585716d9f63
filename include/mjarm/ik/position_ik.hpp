#pragma once
/// @file
/// Position-only inverse kinematics by damped least squares, with the semantics of the classic
/// MuJoCo C-API IK tutorials: a damped step towards the target, a pull to the middle of each
/// joint range, a repulsion from its ends, clipping into the limits and a NaN guard.
///
/// One iteration, with e = p_WT − p_WE (m, world axes) and J = rows 0..2 of J_{E[W]} (3×n):
///   Δq = α·Jᵀ(JJᵀ + λ²I)⁻¹e + N·b,   q ← clip(q + s·Δq),  s ∈ {1, ½, ¼, …},
/// where b = centre pull + limit repulsion + posture pull (per-iteration joint steps) and
/// N = I − Jᵀ(JJᵀ + ε²I)⁻¹J keeps them out of the task (ε = null_space_damping ≪ λ). A
/// null-space step still moves the frame to second order, so N·b is shortened to at most
/// secondary_ratio × ‖task step‖: it fades with the task step, at the target and at the
/// closest point to an unreachable one alike, which keeps convergence to the tolerance (and to
/// the true closest point) intact. Joints a step would carry past a limit are pinned on it and
/// the step is recomputed for the others (`saturate_step`); a step whose largest joint change
/// exceeds max_step is shortened (same direction), which tames the huge DLS steps next to
/// singularities (e.g. a stretched arm). A step that raises the error is halved up to
/// max_backtracks times (the last halving is taken anyway), so an unreachable target ends near
/// the closest reachable point instead of oscillating around it.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/ik/local_ik_settings.hpp"
#include "mjarm/ik/local_ik_workspace.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"

namespace mjarm {

/// Every constant of `PositionIk`: the shared local-IK settings (local_ik_settings.hpp) with
/// this solver's tuning, and its tolerance. Its stall measure is the best error so far.
struct PositionIkOptions : LocalIkSettings {
  double tolerance = 1e-4;  ///< success when ‖p_WT − p_WE‖ ≤ tolerance [m] (finite, > 0)

  /// λ = 0.02 m, α = 0.6, centre gain 0.05 and repulsion 0.2 in the outer 15 % of the ranges,
  /// stall after 60 iterations without progress; the rest as in `LocalIkSettings`.
  PositionIkOptions()
      : LocalIkSettings{
            .damping = 0.02, .step = 0.6, .limits = {0.05, 0.2, 0.15}, .stall_iterations = 60} {}
};

/// The fields of its own (the shared ones are `LocalIkSettings`'s).
constexpr auto declared_fields(const PositionIkOptions*) {
  using S = PositionIkOptions;
  return declare<S>("position IK", field("tolerance", &S::tolerance, "m", Range::positive(),
                                         "success when ‖p_WT − p_WE‖ ≤ tolerance"));
}

/// @throws Error naming the offending option ("position IK: max_step must be positive and
/// finite [rad or m], got 0").
void check(const PositionIkOptions& options);

/// Position IK solver for one chain's frame: construct once, solve many times. After
/// construction, `solve(p_WT, q_seed, result)` with a result of the right size allocates
/// nothing. Never touches any caller's `mjData` (collision checks use an owned scratch one).
class PositionIk {
 public:
  /// @throws Error for invalid options or unknown collision geoms.
  explicit PositionIk(const Chain& chain, const PositionIkOptions& options = {});

  const Chain& chain() const noexcept { return kin_.chain(); }
  const PositionIkOptions& options() const noexcept { return options_; }

  /// Sets the joints outside the chain (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Moves the frame origin to @p p_WT (m, world) starting from @p q_seed (n, clipped into the
  /// limits first). Returns the best iterate: converged, not_converged (iteration limit, stall,
  /// unreachable target, or a step that could not avoid contact) or invalid_input (a NaN
  /// appeared: the last finite iterate). orientation_error is 0.
  /// @throws Error when p_WT or q_seed holds NaN/inf or q_seed has the wrong size, or when the
  /// seed is in contact under the collision spec.
  IkResult solve(const Eigen::Vector3d& p_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed);

  /// The same, writing into @p result (allocation-free once result.q has n entries).
  void solve(const Eigen::Vector3d& p_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed,
             IkResult& result);

 private:
  PositionIkOptions options_;
  ChainKinematics kin_;
  LocalIkWorkspace local_;  // iterate, step, secondary terms, collision guard
  // workspace
  Eigen::Matrix<double, 6, Eigen::Dynamic> J6_;
  Eigen::Matrix<double, 3, Eigen::Dynamic> J_, J_free_;
};

}  // namespace mjarm
