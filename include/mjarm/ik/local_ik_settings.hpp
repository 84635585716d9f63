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

#include "mjarm/fields.hpp"
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

/// The declared fields (mjarm/fields.hpp), checked by each solver's `check` under its name with
/// nested ones by path ("pose IK: limits.centre_gain must be finite and ≥ 0, got -1"), or by
/// `check_fields<LocalIkSettings>(settings, "my IK")`. The posture's q_pref size and the collision
/// geoms' names need the chain: the solvers' constructors check them. `on_iteration` is not
/// declared (a callback has no range; the Python binding wraps it for the GIL).
constexpr auto declared_fields(const LocalIkSettings*) {
  using S = LocalIkSettings;
  return declare<S>(
      "local IK",
      field("damping", &S::damping, "", Range::positive(),
            "λ₀ of each damped least-squares step (position IK: λ [m])"),
      field("step", &S::step, "", Range::open_closed(0.0, 1.0),
            "fraction of the task step taken per iteration"),
      field("max_backtracks", &S::max_backtracks, "", Range::at_least(0),
            "halvings of a step that does not improve; the last one is taken anyway"),
      field("null_space_damping", &S::null_space_damping, "", Range::non_negative(),
            "ε of the null-space projector(s), ≪ damping"),
      field("max_step", &S::max_step, "rad or m", Range::positive(),
            "largest joint change per iteration"),
      field("secondary_ratio", &S::secondary_ratio, "", Range::non_negative(),
            "the secondary step is at most this × the task step"),
      field("limits", &S::limits, "centre pull and limit repulsion in the null space"),
      field("posture", &S::posture, "pull towards a preferred configuration in the null space"),
      field("max_iterations", &S::max_iterations, "", Range::at_least(1), "iteration limit"),
      field("stall_iterations", &S::stall_iterations, "", Range::at_least(1),
            "stop after this many iterations without progress"),
      field("stall_progress", &S::stall_progress, "", Range{0.0, 1.0, false, true},
            "progress = the solver's error measure drops by this fraction"),
      field("collision", &S::collision, "geoms that must not touch (off when empty)"));
}

}  // namespace mjarm
