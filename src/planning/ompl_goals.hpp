#pragma once
// The goal of an OMPL plan as configurations: a joint goal as given, a pose or a pose region
// through several seeded global-IK solves, each solution checked by the collision checker.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mjarm/ik/global_ik.hpp"
#include "mjarm/planning/collision_checker.hpp"
#include "mjarm/planning/ompl_planner.hpp"

namespace mjarm::ompl_detail {

/// Collision-free goal configurations, or why there are none.
struct GoalConfigurations {
  OmplStatus status = OmplStatus::success;  ///< success when `states` is not empty
  std::string message;
  std::vector<Eigen::VectorXd> states;
};

/// @throws Error for a goal of the wrong size, a non-finite or non-rotation pose, a
///         non-positive tolerance, or a region whose lower corner is above its upper one.
GoalConfigurations goal_configurations(const OmplGoal& goal, const Eigen::VectorXd& q_start,
                                       const OmplOptions& options, CollisionChecker& checker,
                                       GlobalIk& ik);

}  // namespace mjarm::ompl_detail
