#pragma once
/// @file
/// `CartesianTrapezoid`: a rest-to-rest straight-line move of a frame with trapezoidal velocity,
/// its turn about one fixed axis timed by a second trapezoid that starts and ends with it.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/trajectory/pose_sample.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {

/// Limits of a `CartesianTrapezoid`.
struct CartesianLimits {
  double max_velocity = 0.07;             ///< along the line [m/s] (> 0)
  double max_acceleration = 0.9;          ///< [m/s²] (> 0)
  double max_angular_velocity = 0.5;      ///< about the turn axis [rad/s] (> 0)
  double max_angular_acceleration = 3.0;  ///< [rad/s²] (> 0)
};

constexpr auto declared_fields(const CartesianLimits*) {
  using S = CartesianLimits;
  return declare<S>(
      "Cartesian trapezoid",
      field("max_velocity", &S::max_velocity, "m/s", Range::positive(), "along the line"),
      field("max_acceleration", &S::max_acceleration, "m/s²", Range::positive(), "along the line"),
      field("max_angular_velocity", &S::max_angular_velocity, "rad/s", Range::positive(),
            "about the turn axis"),
      field("max_angular_acceleration", &S::max_angular_acceleration, "rad/s²", Range::positive(),
            "about the turn axis"));
}

/// From X_start to X_goal at rest, in world axes: with d = ‖p₁ − p₀‖, u = (p₁ − p₀)/d and the
/// turn R₁·R₀ᵀ = Exp(θ·k) (world axis k, angle θ ∈ [0, π]), the two axes (d under the linear
/// limits, θ under the angular ones) are a `SyncedTrapezoid`: the slower sets the duration T and
/// the other is stretched to finish with it. Then, exactly,
///
///     p(t) = p₀ + s_d(t)·u,   ṗ = ṡ_d·u,   p̈ = s̈_d·u
///     R(t) = Exp(s_θ(t)·k)·R₀,   ω = ṡ_θ·k,   ω̇ = s̈_θ·k
///
/// — the straight line of the classic teaching code's `trap_profile` segments, with the
/// orientation along for the ride. Twists are linear first ([ṗ; ω], world axes), as
/// `TaskReference` wants them.
class CartesianTrapezoid {
 public:
  /// Pose, twist and twist rate at one instant (a `PoseProfile`'s sample).
  using Sample = PoseSample;

  /// @throws Error when a pose is not finite or its rotation not orthonormal (to 1e-6), or a
  ///         limit is not positive and finite.
  CartesianTrapezoid(const Pose& X_start, const Pose& X_goal, const CartesianLimits& limits = {});

  double duration() const noexcept { return profile_.duration(); }  ///< T [s] (0: no motion)
  double distance() const noexcept { return distance_; }            ///< d [m]
  double angle() const noexcept { return angle_; }                  ///< θ [rad]
  const Pose& start() const noexcept { return X_start_; }
  const Pose& goal() const noexcept { return X_goal_; }
  /// The pose, twist and rate at @p t [s] (clamped to [0, T]); allocates nothing.
  Sample at(double t) const noexcept;

 private:
  Pose X_start_, X_goal_;
  Eigen::Vector3d direction_ = Eigen::Vector3d::Zero();  // u
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();      // k
  double distance_ = 0.0;
  double angle_ = 0.0;
  SyncedTrapezoid profile_;
};

}  // namespace mjarm
