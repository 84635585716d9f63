#pragma once
/// @file
/// A waypoint file planned from a start state: the poses it asks for (each waypoint's own
/// orientation, else the file's, else the tool's at the start) and the planner's result.

#include <Eigen/Core>
#include <vector>

#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/planning/waypoint_file.hpp"
#include "mjarm/planning/waypoint_planner.hpp"

namespace mjarm {

struct WaypointPathPlan {
  std::vector<Pose> poses;  ///< the tool poses planned through
  PlanResult result;
};

/// Plans @p path for @p chain from @p start_qpos (every joint of the model: the chain's are its
/// start, the others stay there) with @p options.
/// @throws Error as `WaypointPlanner` (options, a start of the wrong size)
WaypointPathPlan plan_waypoint_path(const Chain& chain, const Eigen::VectorXd& start_qpos,
                                    const WaypointPath& path, const PlanOptions& options);

}  // namespace mjarm
