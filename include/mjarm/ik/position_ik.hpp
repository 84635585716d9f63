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

#include "mjarm/ik/collision_guard.hpp"
#include "mjarm/ik/iteration_callback.hpp"
#include "mjarm/ik/limit_bias.hpp"
#include "mjarm/ik/local_ik_workspace.hpp"
#include "mjarm/ik/posture.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"

namespace mjarm {

/// Every constant of `PositionIk`.
struct PositionIkOptions {
  double damping = 0.02;              ///< λ of the damped least-squares step [m]
  double step = 0.6;                  ///< α, fraction of the DLS step taken per iteration (0, 1]
  double null_space_damping = 1e-5;   ///< ε of the null-space projector [m], ≥ 0
  int max_backtracks = 4;             ///< halvings of a step that raises the error (≥ 0)
  double max_step = 0.5;              ///< largest joint change of the task step [rad or m] (> 0)
  double secondary_ratio = 1.0;       ///< secondary step ≤ this × the task step (≥ 0)
  LimitBias limits{0.05, 0.2, 0.15};  ///< centre gain 0.05, repulsion in the outer 15% of ranges
  Posture posture;                    ///< optional pull towards a preferred configuration
  double tolerance = 1e-4;            ///< success when ‖p_WT − p_WE‖ ≤ tolerance [m]
  int max_iterations = 300;           ///< iteration limit (≥ 1)
  int stall_iterations = 60;          ///< stop after this many iterations without progress (≥ 1)
  double stall_progress = 1e-4;  ///< progress = the best error drops by this fraction, in [0, 1)
  CollisionSpec collision;       ///< optional: geoms that must not touch (off when empty)
  IkIterationCallback
      on_iteration;  ///< optional observer of every iterate (iteration_callback.hpp)
};

/// @throws Error naming the offending option.
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
