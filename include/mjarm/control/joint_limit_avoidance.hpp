#pragma once
/// @file
/// `JointLimitAvoidance`: the repulsive joint-limit term the task-space torque controllers (OSC,
/// CIC, SE(3) impedance) add near the joints' limits: the negative gradient of a spring
/// potential plus damping on the velocity towards the limit, split between the task's null space
/// (far from the limit, where the task allows) and the full joint space (near it, where the task
/// would otherwise push the joint through).

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

class TaskSpaceDynamics;

/// Settings of the joint-limit term. Off by default: the controllers then behave exactly as
/// without it.
struct JointLimitOptions {
  bool enabled = false;  ///< add the term
  /// Width of the zone inside each limit where the term acts [rad or m] (> 0, and less than
  /// half of every limited joint's range).
  double margin = 0.2;
  /// k: the stiffness of the repulsive spring [N·m/rad or N/m] (> 0): k·margin at the limit.
  double gain = 100.0;
  /// b: damping on the velocity towards the limit, at the limit [N·m·s/rad or N·s/m] (> 0).
  double damping = 10.0;
};

constexpr auto declared_fields(const JointLimitOptions*) {
  using S = JointLimitOptions;
  return declare<S>("joint limits",
                    field("enabled", &S::enabled, "add the repulsive joint-limit term"),
                    field("margin", &S::margin, "rad or m", Range::positive(),
                          "zone inside each limit where the term acts"),
                    field("gain", &S::gain, "N·m/rad or N/m", Range::positive(),
                          "stiffness of the repulsive spring"),
                    field("damping", &S::damping, "N·m·s/rad or N·s/m", Range::positive(),
                          "damping on the velocity towards the limit"));
}

/// The joint-limit term. For each limited joint, with d its distance to the nearer limit
/// (negative past it) and m = margin, inside the zone d < m:
///
///     U(d)  = (k/2)·(m − d)²                       (C¹: U = U′ = 0 at d = m)
///     τ_U   = −∂U/∂q = ±k·(m − d)                  (away from the limit)
///     s(d)  = smoothstep(1 − d/m)                   (0 at the zone's edge, 1 at the limit)
///     τ_b   = −b·s·q̇  while q̇ points towards the limit, 0 otherwise
///     τ_lim = τ_U + τ_b
///
/// The potential is a spring of bounded stiffness k, not a barrier that grows without bound: a
/// barrier's stiffness near the limit rang at the 2 ms step of a light wrist joint (panda joint7,
/// docs/control.md); k·m is the push at the limit, and it keeps growing past it. A controller
/// with a null space adds Nᵀ·((1 − s)⊙τ_lim) + s⊙τ_lim: at the zone's edge the term only uses the
/// redundancy, at the limit it acts in full, whatever the task asks. Joints with an infinite
/// range are skipped. Nothing is allocated after construction.
class JointLimitAvoidance {
 public:
  /// @throws Error when margin, gain or damping is not positive and finite, or (when enabled)
  ///         the margin is not less than half a limited joint's range (naming the joint).
  JointLimitAvoidance(const Chain& chain, const JointLimitOptions& options);

  const JointLimitOptions& options() const noexcept { return options_; }
  bool enabled() const noexcept { return options_.enabled; }

  /// U(q) [J]: the sum of the joints' barrier potentials.
  double potential(const Eigen::Ref<const Eigen::VectorXd>& q) const noexcept;

  /// Computes τ_lim and s for the state (@p q, @p qd), both n.
  void update(const Eigen::Ref<const Eigen::VectorXd>& q,
              const Eigen::Ref<const Eigen::VectorXd>& qd) noexcept;

  /// Adds the term of the last `update` to @p tau (n): Nᵀ·((1 − s)⊙τ_lim) + s⊙τ_lim with N the
  /// null-space projector of @p task_space, or τ_lim in full when @p task_space is null.
  void add_to(const TaskSpaceDynamics* task_space, Eigen::Ref<Eigen::VectorXd> tau) noexcept;

  /// τ_lim of the last `update` (n) [N·m].
  const Eigen::VectorXd& torque() const noexcept { return torque_; }
  /// s of the last `update` (n), 0 outside the zone, 1 at the limit.
  const Eigen::VectorXd& full_weight() const noexcept { return weight_; }
  /// The torque `add_to` last added (n) [N·m].
  const Eigen::VectorXd& applied() const noexcept { return applied_; }
  /// The smallest distance to a limit at the last `update` over the limited joints [rad or m]
  /// (+inf when no joint is limited).
  double min_distance() const noexcept { return min_distance_; }

 private:
  JointLimitOptions options_;
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
  // workspace
  Eigen::VectorXd torque_;   // n
  Eigen::VectorXd weight_;   // n
  Eigen::VectorXd share_;    // n: (1 − s)⊙τ_lim
  Eigen::VectorXd applied_;  // n
  double min_distance_ = 0.0;
};

}  // namespace mjarm
