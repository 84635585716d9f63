#pragma once
/// @file
/// `SmoothRampTrajectory`: n axes moved from a start to a goal together along one smoothstep or
/// smootherstep ramp, q(t) = q₀ + s(t)·(q₁ − q₀) — the rest-to-rest ramps of smoothstep.hpp as a
/// joint-space profile.

#include <Eigen/Core>

#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

/// q(t) = q₀ + s(t)·d with d = q₁ − q₀ and s the ramp of `kind` over the duration T, so that
/// q̇ = ṡ·d, q̈ = s̈·d, q⃛ = s⃛·d. Every axis reaches its peaks at the same instant: |q̇_i| peaks
/// at `SmoothRamp::peak_slope`·|d_i|/T, |q̈_i| at peak_curvature·|d_i|/T², |q⃛_i| at
/// peak_jerk·|d_i|/T³. A `TrajectoryProfile`; sampling allocates nothing.
class SmoothRampTrajectory {
 public:
  /// From @p start to @p goal (n entries each, any units u per axis) in @p duration [s]; a zero
  /// duration only when nothing moves.
  /// @throws Error when the sizes differ or are 0, a position is not finite, or the duration is
  ///         negative, not finite, or zero for a move.
  SmoothRampTrajectory(SmoothRamp::Kind kind, const Eigen::VectorXd& start,
                       const Eigen::VectorXd& goal, double duration);

  /// The shortest ramp within per-axis limits: T = max over the axes of
  /// `SmoothRamp::duration_for`(kind, |d_i|, v_max,i, a_max,i) (0 when nothing moves); the axis
  /// that sets it is `limiting_axis()`.
  /// @param max_velocity [u/s], @param max_acceleration [u/s²]: n entries each, positive
  /// @throws Error as the constructor, or when a limit is not positive and finite (the axis is
  ///         named).
  static SmoothRampTrajectory within_limits(SmoothRamp::Kind kind, const Eigen::VectorXd& start,
                                            const Eigen::VectorXd& goal,
                                            const Eigen::VectorXd& max_velocity,
                                            const Eigen::VectorXd& max_acceleration);

  /// The ramp's kind.
  SmoothRamp::Kind kind() const noexcept { return kind_; }
  /// The duration T [s] (0: nothing moves).
  double duration() const noexcept { return duration_; }
  /// The number of axes n.
  Eigen::Index dofs() const noexcept { return start_.size(); }
  /// The axis whose limits set the duration (`within_limits`), −1 when the duration was given or
  /// nothing moves.
  Eigen::Index limiting_axis() const noexcept { return limiting_axis_; }

  /// q, q̇, q̈, q⃛ at @p t [s] (clamped to [0, T]) into @p sample (resized to n when it is not).
  void at(double t, TrajectorySample& sample) const;

  /// The peak |q̇_i| [u/s] of every axis (0 when nothing moves).
  Eigen::VectorXd peak_velocity() const;
  /// The peak |q̈_i| [u/s²] of every axis.
  Eigen::VectorXd peak_acceleration() const;
  /// The peak |q⃛_i| [u/s³] of every axis (at the ends, where the jerk steps for smootherstep;
  /// throughout for smoothstep).
  Eigen::VectorXd peak_jerk() const;

 private:
  SmoothRamp::Kind kind_;
  Eigen::VectorXd start_;
  Eigen::VectorXd delta_;  // d = q₁ − q₀
  double duration_;
  Eigen::Index limiting_axis_ = -1;
};

}  // namespace mjarm
