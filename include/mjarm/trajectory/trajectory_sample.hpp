#pragma once
/// @file
/// `TrajectorySample`: what every profile of the trajectory room gives at a time t for its n
/// coordinates (joints, axes, or the one coordinate of a scalar profile), and
/// `TrajectoryProfile`, the concept every such profile meets — duration(), dofs() and
/// at(t, sample) — so that code that samples "a profile" is written once (pose_sample.hpp is the
/// SE(3) counterpart).

#include <Eigen/Core>
#include <concepts>

namespace mjarm {

/// Position, velocity, acceleration and jerk of n coordinates at one instant. Units are the
/// profile's: a position in u (m, rad), then u/s, u/s², u/s³.
struct TrajectorySample {
  Eigen::VectorXd position;      ///< q [u] (n)
  Eigen::VectorXd velocity;      ///< q̇ [u/s] (n)
  Eigen::VectorXd acceleration;  ///< q̈ [u/s²] (n)
  /// q⃛ [u/s³] (n): 0 outside [0, T] and inside a profile's phases of constant acceleration;
  /// where the acceleration steps (a trapezoid's switches) the jerk is unbounded, and 0 here.
  Eigen::VectorXd jerk;

  TrajectorySample() = default;
  /// @p n coordinates, all zero (allocates here, so that at(t, sample) does not).
  explicit TrajectorySample(Eigen::Index n);

  /// The number of coordinates n.
  Eigen::Index size() const noexcept { return position.size(); }
  /// Gives every vector @p n entries (allocates only when the size changes).
  void resize(Eigen::Index n);
};

/// A profile of n coordinates over [0, T]: `duration()` T [s], `dofs()` n, and
/// `at(t, sample)`, which writes the state at t [s] into @p sample (resized to n when it is not;
/// no allocation once it is). Time is clamped as the profile documents (most: to [0, T]).
template <class P>
concept TrajectoryProfile = requires(const P& profile, double t, TrajectorySample& sample) {
  { profile.duration() } -> std::convertible_to<double>;
  { profile.dofs() } -> std::convertible_to<Eigen::Index>;
  profile.at(t, sample);
};

/// @p profile at @p t [s] in a new sample (allocates; in a loop, keep one sample and call
/// `profile.at(t, sample)`).
template <TrajectoryProfile P>
TrajectorySample sample_at(const P& profile, double t) {
  TrajectorySample sample(static_cast<Eigen::Index>(profile.dofs()));
  profile.at(t, sample);
  return sample;
}

}  // namespace mjarm
