#pragma once
/// @file
/// The posture term of local IK: a pull towards a preferred configuration that acts in the null
/// space of the primary task(s), so it picks among the solutions without moving the targets.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// A preferred configuration and how hard to pull towards it. Disabled while gain is 0.
struct Posture {
  /// Preferred joint values (chain order, n) [rad or m]; empty = the middle of each range
  /// (0 for unlimited joints).
  Eigen::VectorXd q_pref;
  /// Per-iteration pull as a fraction of (q_pref − q), in [0, 1].
  double gain = 0.0;
};

constexpr auto declared_fields(const Posture*) {
  using S = Posture;
  return declare<S>("posture",
                    field("q_pref", &S::q_pref, "rad or m", Range::finite(),
                          "preferred joints (n,); empty = the middle of each range"),
                    field("gain", &S::gain, "", Range::closed(0.0, 1.0),
                          "per-iteration pull, a fraction of (q_pref - q)"));
}

/// The preferred configuration to use with @p chain: `posture.q_pref`, or the chain's centre
/// when it is empty.
/// @throws Error when the gain is outside [0, 1] or q_pref has the wrong size or a non-finite
/// value.
Eigen::VectorXd resolve_posture(const Chain& chain, const Posture& posture);

/// Adds gain·(q_pref − q) to @p step (n). Allocates nothing.
/// @param q_pref the resolved preference (from `resolve_posture`)
void add_posture_pull(const Eigen::Ref<const Eigen::VectorXd>& q_pref, double gain,
                      const Eigen::Ref<const Eigen::VectorXd>& q,
                      Eigen::Ref<Eigen::VectorXd> step) noexcept;

/// Factor that shortens a null-space secondary step of length @p secondary_norm to at most
/// @p ratio × @p task_norm (the length of the task step it rides on): min(1, ratio·task/secondary),
/// 0 for a zero task step, 1 for a zero secondary step. The secondary terms thereby fade out as
/// the solver converges, so their second-order drift can never hold it off the target.
double secondary_scale(double task_norm, double secondary_norm, double ratio) noexcept;

}  // namespace mjarm
