#pragma once
/// @file
/// Full-pose inverse kinematics (closed-loop IK on SE(3)) by damped least squares with
/// Levenberg–Marquardt style adaptive damping.
///
/// The error is the body log error e = log(X_WE⁻¹·X_WT) = [v; ω] (m; rad, frame E). For a body
/// twist V_E = J_E·q̇ it moves as ė = −Jlog(e)·V_E with Jlog = dexp⁻¹(e), so the Newton step
/// solves (Jlog·J_E)·Δq = e. With row weights W = diag(w_p·I₃, w_o·I₃) one iteration is
///   J = W·Jlog(e)·J_E,   λ² = damping² + error_damping·½‖W·e‖²,
///   Δq = Jᵀ(JJᵀ + λ²I)⁻¹·W·e + N·b,   q ← clip(q + s·Δq),
/// where b is the optional centre pull / limit repulsion / posture (null space N, at most
/// secondary_ratio × the task step, as in `PositionIk`) and s ∈ {step, step/2, …} is the first
/// step length that lowers ‖W·e‖ (the last one is taken anyway after `max_backtracks`
/// halvings) and touches no watched geom. The error-proportional damping is large far from the
/// target (short, safe steps) and vanishes near it (quadratic convergence). Joint limits: joints
/// a step would carry past a bound are pinned on it and the step is recomputed for the others;
/// no step changes a joint by more than max_step.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/ik/local_ik_settings.hpp"
#include "mjarm/ik/local_ik_workspace.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/pose.hpp"

namespace mjarm {

/// Every constant of `PoseIk`: the shared local-IK settings (local_ik_settings.hpp) with this
/// solver's tuning, its error-proportional damping, row weights and tolerances. Its stall
/// measure is the best max(position error / tolerance, angle / tolerance) so far.
struct PoseIkOptions : LocalIkSettings {
  double error_damping = 0.5;        ///< adds this × ½‖W·e‖² to λ² (≥ 0; 0 = plain DLS)
  double position_weight = 1.0;      ///< w_p, row weight of the position error [1/m] (> 0)
  double orientation_weight = 0.5;   ///< w_o, row weight of the orientation error [1/rad] (> 0)
  double position_tolerance = 1e-5;  ///< success when ‖p_WT − p_WE‖ ≤ this [m] (> 0)
  double orientation_tolerance = 1e-5;  ///< ... and the rotation angle to the target ≤ this [rad]

  /// At most 200 iterations; the rest as in `LocalIkSettings` (λ₀ = 1e-3, first step 1, no
  /// limit bias).
  PoseIkOptions() : LocalIkSettings{.max_iterations = 200} {}
};

/// The fields of its own (the shared ones are `LocalIkSettings`'s).
constexpr auto declared_fields(const PoseIkOptions*) {
  using S = PoseIkOptions;
  return declare<S>("pose IK",
                    field("error_damping", &S::error_damping, "", Range::non_negative(),
                          "adds this × ½‖W·e‖² to λ²; 0 = plain DLS"),
                    field("position_weight", &S::position_weight, "1/m", Range::positive(),
                          "row weight of the position error"),
                    field("orientation_weight", &S::orientation_weight, "1/rad", Range::positive(),
                          "row weight of the orientation error"),
                    field("position_tolerance", &S::position_tolerance, "m", Range::positive(),
                          "success when ‖p_WT − p_WE‖ ≤ this"),
                    field("orientation_tolerance", &S::orientation_tolerance, "rad",
                          Range::positive(), "... and the rotation angle to the target ≤ this"));
}

/// @throws Error naming the offending option ("pose IK: posture.gain must be in [0, 1], got
/// 2").
void check(const PoseIkOptions& options);

/// Pose IK solver for one chain's frame: construct once, solve many times. After construction,
/// `solve(X_WT, q_seed, result)` with a result of the right size allocates nothing. Never
/// touches any caller's `mjData`.
class PoseIk {
 public:
  /// @throws Error for invalid options or unknown collision geoms.
  explicit PoseIk(const Chain& chain, const PoseIkOptions& options = {});

  const Chain& chain() const noexcept { return kin_.chain(); }
  const PoseIkOptions& options() const noexcept { return options_; }

  /// Sets the joints outside the chain (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Moves the frame to the pose @p X_WT (world) starting from @p q_seed (n, clipped into the
  /// limits first). Returns the best iterate (smallest max(position error / position
  /// tolerance, orientation error / orientation tolerance)) with status converged,
  /// not_converged or invalid_input (a NaN appeared: the last finite iterate).
  /// @throws Error when X_WT is not finite or not a rotation, q_seed has the wrong size or
  /// holds NaN/inf, or the seed is in contact under the collision spec.
  IkResult solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed);

  /// The same, writing into @p result (allocation-free once result.q has n entries).
  void solve(const Pose& X_WT, const Eigen::Ref<const Eigen::VectorXd>& q_seed, IkResult& result);

 private:
  PoseIkOptions options_;
  ChainKinematics kin_;
  LocalIkWorkspace local_;  // iterate, step, secondary terms, collision guard
  // workspace
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_world_;  // world-aligned frame Jacobian
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_, J_free_;
};

}  // namespace mjarm
