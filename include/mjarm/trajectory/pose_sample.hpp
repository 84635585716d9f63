#pragma once
/// @file
/// `PoseSample`: what every pose profile of the trajectory room gives at a time t — the pose of
/// a frame E, its twist and twist rate — and `PoseProfile`, the concept such a profile meets
/// (duration(), at(t)): the SE(3) counterpart of trajectory_sample.hpp.

#include <concepts>

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Pose, twist and twist rate of a frame E at one instant, in world axes W, linear first (as
/// `TaskReference` wants them).
struct PoseSample {
  Pose X_WE;                         ///< pose of E in W
  Vector6d V_WE = Vector6d::Zero();  ///< [ṗ; ω] [m/s; rad/s]
  Vector6d A_WE = Vector6d::Zero();  ///< [p̈; ω̇] [m/s²; rad/s²]
};

/// A pose profile over [0, T]: `duration()` T [s] and `at(t)`, the `PoseSample` at t [s]
/// (clamped to [0, T]; allocation-free).
template <class P>
concept PoseProfile = requires(const P& profile, double t) {
  { profile.duration() } -> std::convertible_to<double>;
  { profile.at(t) } -> std::same_as<PoseSample>;
};

}  // namespace mjarm
