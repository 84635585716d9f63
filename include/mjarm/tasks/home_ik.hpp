#pragma once
/// @file
/// The start of a task run with its tool at a pose: pose IK from the robot's `home` keyframe,
/// pulled towards it, so the arm keeps the posture of home (the docking and the wiping start so).

#include "mjarm/ik/result.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// Pose IK of @p chain's frame to @p X_WE from the `home` keyframe of @p robot, with a posture
/// pull (gain 0.2) towards it.
/// @throws Error when the robot has no `home` keyframe.
IkResult home_pose_ik(const Robot& robot, const Chain& chain, const Pose& X_WE);

}  // namespace mjarm
