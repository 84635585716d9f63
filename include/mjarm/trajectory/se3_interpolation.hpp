#pragma once
/// @file
/// `Se3Interpolation`: a pose trajectory that starts in motion (any twist and twist rate) and
/// ends at rest at a goal pose — position by a quintic per axis, orientation by a quintic in the
/// rotation vector relative to the start, mapped to angular velocity through the exact SO(3)
/// dexp (docs/trajectory.md).

#include <Eigen/Core>
#include <array>

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/trajectory/pose_sample.hpp"
#include "mjarm/trajectory/quintic.hpp"

namespace mjarm {

/// From X_WE(0) = X_start with twist V_start and twist rate A_start to X_WE(T) = X_goal at rest.
/// Twists are those of `TaskReference`: V = [ṗ; ω] and A = [p̈; ω̇], all in world axes W.
///
/// - position: p(t) is a quintic per axis from (p₀, v₀, a₀) to (p₁, 0, 0);
/// - orientation: R(t) = R₀·Exp(θ(t)) with θ a quintic per component from θ(0) = 0,
///   θ̇(0) = R₀ᵀω₀, θ̈(0) = R₀ᵀω̇₀ to θ(T) = Log(R₀ᵀR₁), θ̇(T) = θ̈(T) = 0. Then, exactly,
///   ω(t) = R₀·Jl(θ)·θ̇ (= R(t)·Jr(θ)·θ̇, Jl/Jr the SO(3) left/right Jacobians of lie/) and
///   ω̇(t) = R₀·(J̇l(θ, θ̇)·θ̇ + Jl(θ)·θ̈). At t = 0 Jl = I and J̇l(0, θ̇)·θ̇ = ½ θ̇ × θ̇ = 0, so
///   ω(0) = ω₀ and ω̇(0) = ω̇₀ exactly. (The shortcut ω ≈ R·θ̇ is exact only when θ ∥ θ̇.)
///
/// The rotation goes the short way (‖θ(T)‖ ≤ π); a fast start may carry θ(t) beyond π on the
/// way, which the exponential map handles (no inverse Jacobian is used).
class Se3Interpolation {
 public:
  /// Pose, twist and twist rate at one instant (world axes, linear first: a `PoseProfile`'s
  /// sample).
  using Sample = PoseSample;

  /// The interpolation from @p X_start (moving with @p V_start, @p A_start) to @p X_goal at rest
  /// in @p duration [s].
  /// @throws Error when a pose, twist or rate is not finite, a rotation is not orthonormal
  ///         (to 1e-6), or the duration is not positive and finite.
  Se3Interpolation(const Pose& X_start, const Vector6d& V_start, const Vector6d& A_start,
                   const Pose& X_goal, double duration);

  /// The duration T [s].
  double duration() const noexcept { return duration_; }
  /// The rotation vector θ(T) = Log(R₀ᵀR₁) [rad] (in the start frame).
  const Eigen::Vector3d& rotation() const noexcept { return theta_goal_; }

  /// Pose, twist and twist rate at @p t [s] (clamped to [0, T]; from T on exactly the goal
  /// position with rotation R₀·Exp(θ(T)) and a zero twist and rate); allocates nothing.
  Sample at(double t) const noexcept;

  /// The rotation vector θ(t) and its first two time derivatives (start frame) at @p t [s].
  void rotation_vector(double t, Eigen::Vector3d& theta, Eigen::Vector3d& theta_dot,
                       Eigen::Vector3d& theta_ddot) const noexcept;

 private:
  Pose X_start_;
  Pose X_end_;  // p_goal, R₀·Exp(θ(T))
  Eigen::Vector3d theta_goal_;
  std::array<Quintic, 3> position_;
  std::array<Quintic, 3> angle_;
  double duration_;
};

}  // namespace mjarm
