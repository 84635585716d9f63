#pragma once
/// @file
/// Joint-limit terms of local IK: a pull towards the middle of each joint's range and a
/// repulsion from its ends, both applied as per-iteration joint steps in the null space of the
/// task, plus clipping into the range.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// Gains of the joint-limit terms. Only joints with a finite range take part.
struct LimitBias {
  /// Per-iteration pull towards the middle of the range, as a fraction of (centre − q) (≥ 0).
  double centre_gain = 0.0;
  /// Per-iteration push away from a bound, reached at the bound, as a fraction of the zone width
  /// (≥ 0). Inside the zone it grows quadratically with the depth: gain·zone·(depth/zone)².
  double repulsion_gain = 0.0;
  /// Width of the zone at each end of the range where repulsion acts, as a fraction of the
  /// range (in [0, 0.5]).
  double repulsion_zone = 0.15;
};

constexpr auto declared_fields(const LimitBias*) {
  using S = LimitBias;
  return declare<S>(
      "limit bias",
      field("centre_gain", &S::centre_gain, "", Range::non_negative(),
            "per-iteration pull towards the middle of the range, a fraction of (centre - q)"),
      field("repulsion_gain", &S::repulsion_gain, "", Range::non_negative(),
            "per-iteration push away from a bound, reached at the bound, a fraction of the zone"),
      field("repulsion_zone", &S::repulsion_zone, "", Range::closed(0.0, 0.5),
            "width of the zone at each end where repulsion acts, a fraction of the range"));
}

/// @throws Error naming the field when a gain is negative or not finite or the zone is outside
/// [0, 0.5] ("limit bias: centre_gain must be finite and ≥ 0, got -1").
void check(const LimitBias& bias);

/// Adds the limit-bias step at @p q to @p step (both n = chain size) [rad or m per iteration].
/// Allocates nothing.
void add_limit_bias(const Chain& chain, const LimitBias& bias,
                    const Eigen::Ref<const Eigen::VectorXd>& q,
                    Eigen::Ref<Eigen::VectorXd> step) noexcept;

/// Saturation of a step in the joint limits: every joint not yet in @p locked that @p dq would
/// carry past a bound from @p q is marked (locked[i] = 1) and given the motion that lands it
/// exactly on the bound (dq_locked[i]). Solvers then recompute the step for the remaining
/// joints with the locked motions as given, so that clipping never breaks the task (the
/// joints that hit a limit are taken out of the problem, the others make up for them).
/// @param q joint values inside the limits (n) @param dq proposed step (n)
/// @param locked 0/1 per joint (n), updated @param dq_locked motion of locked joints (n), updated
/// @return the number of joints newly locked
int saturate_step(const Chain& chain, const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& dq, Eigen::Ref<Eigen::VectorXd> locked,
                  Eigen::Ref<Eigen::VectorXd> dq_locked) noexcept;

/// Clips @p q into the chain's bounds in place (unlimited joints untouched). Allocates nothing.
void clamp_to_limits(const Chain& chain, Eigen::Ref<Eigen::VectorXd> q) noexcept;

}  // namespace mjarm
