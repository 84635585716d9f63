#pragma once
/// @file
/// The per-joint limits a plan respects: velocity and acceleration (they set the segment
/// durations) and torque (checked by inverse dynamics), from the model's actuators or the user.

#include <Eigen/Core>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// Limits of each chain joint (n entries each, chain order).
struct JointLimits {
  Eigen::VectorXd max_velocity;      ///< |q̇_i| ≤ this [rad/s or m/s] (> 0)
  Eigen::VectorXd max_acceleration;  ///< |q̈_i| ≤ this [rad/s² or m/s²] (> 0)
  /// |τ_i| ≤ this [N·m or N] (> 0; +infinity: the joint's torque is not checked)
  Eigen::VectorXd max_torque;
};

/// How `joint_limits_from_model` fills what the model does not say.
struct ModelLimitOptions {
  /// MJCF has no joint velocity limit: this one is used for every joint [rad/s or m/s]
  /// (> 0). Override per joint with the user's limits (`mjarm plan --velocity-limit`).
  double velocity = 1.0;
  /// a_max,i = torque_fraction · τ_max,i / M_ii(q) at the configuration given, in (0, 1]: the
  /// rest of the torque is left for gravity, coupling and feedback.
  double torque_fraction = 0.5;
  /// Acceleration used for a joint without a torque limit [rad/s² or m/s²] (> 0).
  double acceleration = 5.0;
};

constexpr auto declared_fields(const ModelLimitOptions*) {
  using S = ModelLimitOptions;
  return declare<S>(
      "model limits",
      field("velocity", &S::velocity, "rad/s or m/s", Range::positive(),
            "velocity limit of every joint (MJCF has none)"),
      field("torque_fraction", &S::torque_fraction, "", Range::open_closed(0.0, 1.0),
            "share of the torque limit that sets the acceleration limit"),
      field("acceleration", &S::acceleration, "rad/s² or m/s²", Range::positive(),
            "acceleration limit of a joint without a torque limit"));
}

/// Limits read from the model at chain configuration @p q (n): torque limits from the actuator
/// driving each joint (|gear|·min(|forcerange|) when force-limited, else |gear|·min(|ctrlrange|)
/// for a ctrl-limited motor, else +infinity), accelerations from those torques and the diagonal
/// of the mass matrix at @p q (`ModelLimitOptions::torque_fraction`), velocities from the options.
/// @throws Error when @p q does not fit the chain or an option is out of range.
JointLimits joint_limits_from_model(const Chain& chain, const Eigen::VectorXd& q,
                                    const ModelLimitOptions& options = {});

/// @throws Error naming the vector and the joint when a vector does not have @p n entries or an
///         entry is not positive (velocity and acceleration also finite).
void check(const JointLimits& limits, int n);

/// One line per kind for people: "max velocity [rad/s]: 1, 1, …".
std::string describe(const JointLimits& limits);

}  // namespace mjarm
