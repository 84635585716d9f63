#include "mjarm/planning/waypoint_path_plan.hpp"

#include "mjarm/kinematics/chain_kinematics.hpp"

namespace mjarm {

WaypointPathPlan plan_waypoint_path(const Chain& chain, const Eigen::VectorXd& start_qpos,
                                    const WaypointPath& path, const PlanOptions& options) {
  WaypointPlanner planner(chain, options);
  planner.set_fixed_qpos(start_qpos);
  ChainKinematics kin(chain);
  kin.set_fixed_qpos(start_qpos);
  const Eigen::VectorXd q = chain.gather(start_qpos.data());
  WaypointPathPlan plan;
  plan.poses = path.poses(kin.update(q).R);
  plan.result = planner.plan(q, plan.poses);
  return plan;
}

}  // namespace mjarm
