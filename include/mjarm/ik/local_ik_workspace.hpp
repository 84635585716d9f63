#pragma once
/// @file
/// What the local IK solvers (`PositionIk`, `PoseIk`, `MultiTargetIk`) share around their own
/// task step, so that each of them reads as its algorithm only:
/// - the seed: checked, clipped into the limits, refused when in contact;
/// - the secondary terms: limit bias (centre pull, repulsion) plus posture pull, per iteration;
/// - the limit-aware step: joints a step would carry past a bound are pinned on it and the
///   solver's task step is solved again for the others (one more joint per pass, `saturate_step`),
///   then a trust region caps the largest joint change at max_step;
/// - the backtracking line search: halve the step while it does not improve (the solver says
///   what improving means) or touches a geom watched by the collision guard;
/// - the stall counter.
/// Its settings are those every local solver has (`LocalIkSettings`).

#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <memory>
#include <string_view>
#include <utility>

#include "mjarm/ik/collision_guard.hpp"
#include "mjarm/ik/limit_bias.hpp"
#include "mjarm/ik/local_ik_settings.hpp"
#include "mjarm/ik/posture.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// How a backtracking line search ended.
enum class LineSearchOutcome {
  accepted,   ///< a step was taken: the iterate moved
  blocked,    ///< every shortened step touched a watched geom: the iterate stays
  non_finite  ///< a trial iterate held NaN/inf: the iterate stays
};

/// The iterate, the step and the preallocated workspace a local IK solver keeps between
/// iterations, with the steps every local solver takes the same way. Sized at construction;
/// every method after that allocates nothing (except the error paths of `start`).
class LocalIkWorkspace {
 public:
  /// @param chain the joints the solver moves
  /// @param settings reads limits, posture, collision, null_space_damping, max_step,
  /// secondary_ratio and max_backtracks (checked by the solver's `check`)
  /// @throws Error for an invalid posture or unknown collision geoms.
  LocalIkWorkspace(const Chain& chain, const LocalIkSettings& settings);

  /// Sets the joints outside the chain for the collision guard (full qpos, nq entries); the
  /// solver sets its own kinematics.
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Starts a solve: checks @p q_seed (n), clips it into the limits as the current iterate and
  /// sizes @p result.q (allocation-free when it already has n entries).
  /// @param what names the seed in messages, e.g. "pose IK seed"
  /// @throws Error when q_seed has the wrong size or holds NaN/inf, or is in contact.
  void start(const Eigen::Ref<const Eigen::VectorXd>& q_seed, std::string_view what,
             IkResult& result);

  /// The current iterate (n).
  const Eigen::VectorXd& q() const noexcept { return q_; }
  /// The step from the last `limited_step` (n) [rad or m].
  const Eigen::VectorXd& step() const noexcept { return dq_; }
  /// Remembers the current iterate as the best one.
  void keep_best() noexcept { q_best_ = q_; }
  /// What a solve returns: the current iterate when @p last (a NaN stopped the solve), else the
  /// best one.
  const Eigen::VectorXd& returned(bool last) const noexcept { return last ? q_ : q_best_; }

  /// True when a secondary term is on (a limit-bias gain or the posture gain is positive).
  bool has_secondary() const noexcept { return has_secondary_; }
  /// Computes the secondary step b = limit bias + posture pull at the current iterate (n), a
  /// no-op when `has_secondary()` is false.
  void update_secondary() noexcept;
  /// b from the last `update_secondary` (n) [rad or m per iteration].
  const Eigen::VectorXd& secondary() const noexcept { return bias_; }

  /// The limit-aware step: with no joint pinned, @p solve_free(locked, dq_locked, dq) writes the
  /// full step dq (n) for the free joints (locked[i] = 0) with the pinned ones moving by
  /// dq_locked; joints it would carry past a bound are pinned and it runs again, until none is
  /// (at most n + 1 passes). The step is then shortened (same direction) so that no joint
  /// changes by more than max_step.
  /// @return false when the step holds NaN/inf
  template <class SolveFree>
  bool limited_step(SolveFree&& solve_free) noexcept;

  /// `limited_step` for one task of Rows rows (3 or 6): damped least squares on the free
  /// columns J_f, dq = J_fᵀ(J_fJ_fᵀ + λ²I)⁻¹(target − J·dq_locked), plus the secondary step
  /// projected out of the task, N·b with N = I − J_fᵀ(J_fJ_fᵀ + ε²I)⁻¹J_f, shortened to at
  /// most secondary_ratio × the task step.
  /// @param J task Jacobian (Rows × n) @param target task step wanted (Rows)
  /// @param lambda_sq λ² (units of J squared) @param J_free the solver's Rows × n scratch
  /// @return false when the step holds NaN/inf
  /// Defined in the library for Rows 3 and 6 (the factorizations stay out of this header).
  template <int Rows>
  bool damped_task_step(const Eigen::Matrix<double, Rows, Eigen::Dynamic>& J,
                        const Eigen::Matrix<double, Rows, 1>& target, double lambda_sq,
                        Eigen::Matrix<double, Rows, Eigen::Dynamic>& J_free) noexcept;

  /// Backtracking from the current iterate q along the last step: q + s·dq clipped into the
  /// limits for s = @p first_step, first_step/2, …; a trial touching a watched geom is
  /// halved again (up to the guard's max_halvings), otherwise it is taken when
  /// @p improves(q_try) says so or after max_backtracks halvings. @p improves runs on every
  /// trial that is not in contact, so the solver can keep what it computed on the accepted one.
  template <class Improves>
  LineSearchOutcome line_search(double first_step, Improves&& improves) noexcept;

 private:
  Chain chain_;
  LimitBias limits_;
  double posture_gain_ = 0.0;
  double eps_sq_ = 0.0;
  double max_step_ = 0.0;
  double secondary_ratio_ = 0.0;
  int max_backtracks_ = 0;
  bool has_secondary_ = false;
  std::unique_ptr<CollisionGuard> guard_;
  Eigen::VectorXd q_pref_;
  Eigen::VectorXd q_, q_best_, q_try_, dq_, bias_, projected_, locked_, dq_locked_;
};

/// Counts iterations without progress of a measure that should fall.
class StallCounter {
 public:
  /// @param progress fraction by which the measure must drop to count as progress, in [0, 1)
  /// @param limit iterations without progress that make a stall (≥ 1)
  StallCounter(double progress, int limit) noexcept : progress_(progress), limit_(limit) {}

  /// Records this iteration's @p measure. @return true once @p limit iterations in a row have
  /// not lowered it by the progress fraction below the last measure that did.
  bool stalled(double measure) noexcept {
    if (measure < reference_ * (1.0 - progress_)) {
      reference_ = measure;
      since_ = 0;
      return false;
    }
    return ++since_ >= limit_;
  }

 private:
  double progress_;
  int limit_;
  double reference_ = std::numeric_limits<double>::infinity();
  int since_ = 0;
};

/// @p options once `check(options)` has passed, so that a constructor validates its options
/// before it builds the members that read them.
/// @throws Error from `check`.
template <class Options>
const Options& checked(const Options& options) {
  check(options);
  return options;
}

template <class SolveFree>
bool LocalIkWorkspace::limited_step(SolveFree&& solve_free) noexcept {
  locked_.setZero();
  dq_locked_.setZero();
  for (int pass = 0; pass <= chain_.size(); ++pass) {
    solve_free(std::as_const(locked_), std::as_const(dq_locked_), dq_);
    if (saturate_step(chain_, q_, dq_, locked_, dq_locked_) == 0) break;
  }
  // a trust region against the huge steps next to singularities
  const double largest = dq_.cwiseAbs().maxCoeff();
  if (largest > max_step_) dq_ *= max_step_ / largest;
  return dq_.allFinite();
}

template <class Improves>
LineSearchOutcome LocalIkWorkspace::line_search(double first_step, Improves&& improves) noexcept {
  const int halvings = std::max(max_backtracks_, guard_ ? guard_->spec().max_halvings : 0);
  double s = first_step;
  for (int h = 0; h <= halvings; ++h, s *= 0.5) {
    q_try_ = q_ + s * dq_;
    clamp_to_limits(chain_, q_try_);
    if (!q_try_.allFinite()) return LineSearchOutcome::non_finite;
    if (guard_ && guard_->in_contact(q_try_)) {
      if (h >= guard_->spec().max_halvings) return LineSearchOutcome::blocked;
      continue;
    }
    if (improves(std::as_const(q_try_)) || h >= max_backtracks_) {
      q_ = q_try_;
      return LineSearchOutcome::accepted;
    }
  }
  return LineSearchOutcome::blocked;
}

}  // namespace mjarm
