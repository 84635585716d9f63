#pragma once
/// @file
/// `torque_feasible_duration`: stretches a minimum-jerk joint move until the torques it needs
/// stay within a fraction of the motors' limits.

#include <Eigen/Core>
#include <span>

#include "mjarm/model/actuator_limits.hpp"  // joint_torque_limit
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// The shortest duration T' ≥ @p duration [s] for which the rest-to-rest minimum-jerk joint move
/// q(t) = q_S + (q_T − q_S)·s(t/T') needs, by inverse dynamics, joint torques whose dynamic part
/// |τ − g| stays within @p torque_fraction × limit − |g| on every chain joint (g: gravity and
/// passive forces at rest). The dynamic part scales as 1/T'² (M·q̈ and the velocity-product
/// terms), so T' = T·√(worst ratio) over 64 samples of the move, refined once. Joints without a
/// torque limit (no actuator, or unlimited) are ignored.
/// @param qpos_start full qpos (nq) of the start; joints off the chain keep these values
/// @param q_target chain joint values at the end (chain order)
/// @throws Error on wrong sizes, NaN/inf, a non-positive duration, a fraction outside (0, 1], or
///         when gravity alone needs more than the allowed torque at some point of the move.
double torque_feasible_duration(const Chain& chain, std::span<const double> qpos_start,
                                const Eigen::Ref<const Eigen::VectorXd>& q_target, double duration,
                                double torque_fraction);

}  // namespace mjarm
