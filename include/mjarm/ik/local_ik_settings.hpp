#pragma once
/// @file
/// The settings every local IK solver shares. `PositionIkOptions`, `PoseIkOptions` and
/// `MultiTargetIkOptions` derive from `LocalIkSettings`, add what only their solver has (its
/// tolerances, row weights, mode) and set their own tuning of the shared fields in their
/// constructors; everything else is defaulted here, once:
///
/// | field            | PositionIk        | PoseIk | MultiTargetIk |
/// |------------------|-------------------|--------|---------------|
/// | damping          | 0.02 m            | 1e-3   | 1e-3          |
/// | step             | 0.6               | 1      | 1             |
/// | limits           | {0.05, 0.2, 0.15} | off    | off           |
/// | max_iterations   | 300               | 200    | 300           |
/// | stall_iterations | 60                | 30     | 30            |
///
/// `LocalIkWorkspace` reads the step, trust-region, line-search and secondary-term fields; each
/// solver reads the damping, step and stopping rules in its own loop.

#include <string_view>

#include "mjarm/ik/collision_guard.hpp"
#include "mjarm/ik/iteration_callback.hpp"
#include "mjarm/ik/limit_bias.hpp"
#include "mjarm/ik/posture.hpp"

namespace mjarm {

/// What `PositionIk`, `PoseIk` and `MultiTargetIk` share: the damped step, its trust region and
/// line search, the secondary terms, the stopping rules, the collision hook and the observer.
struct LocalIkSettings {
  // (class members get `{}` so that the options' designated initializers may leave them out
  // under -Wmissing-field-initializers)

  /// λ₀ > 0, the constant part of the damping of each damped least-squares step, in the units of
  /// the (weighted) task error: position IK's λ [m]; pose and multi-target IK add an
  /// error-proportional part (their `error_damping`).
  double damping = 1e-3;
  /// Fraction of the task step taken per iteration, in (0, 1]: position IK scales its step by
  /// it (α); pose and multi-target IK try it first in the line search.
  double step = 1.0;
  /// Halvings of a step that does not improve the result (≥ 0); the last one is taken anyway.
  int max_backtracks = 4;
  /// ε of the null-space projector(s), finite and ≥ 0 (≪ damping).
  double null_space_damping = 1e-5;
  /// Largest joint change per iteration [rad or m] (finite, > 0); a longer step is shortened in
  /// the same direction.
  double max_step = 0.5;
  /// The secondary step is at most this × the task step (finite, ≥ 0).
  double secondary_ratio = 1.0;
  /// Centre pull and limit repulsion in the null space of the task(s) (off by default).
  LimitBias limits{};
  /// Optional pull towards a preferred configuration, in the null space of the task(s).
  Posture posture{};
  /// Iteration limit (≥ 1).
  int max_iterations = 300;
  /// Stop after this many iterations without progress (≥ 1).
  int stall_iterations = 30;
  /// Progress = the solver's error measure drops by this fraction, in [0, 1).
  double stall_progress = 1e-4;
  /// Optional: geoms that must not touch (off when empty).
  CollisionSpec collision{};
  /// Optional observer of every iterate (iteration_callback.hpp).
  IkIterationCallback on_iteration{};
};

/// Checks every field, nested ones by path: "<solver> option limits.centre_gain must be finite
/// and >= 0, got -1". The posture's q_pref and the collision geoms' names need the chain; the
/// solver's constructor checks them.
/// @param solver names the solver in messages, e.g. "pose IK"
/// @throws Error naming the first offending field.
void check(const LocalIkSettings& settings, std::string_view solver);

}  // namespace mjarm
