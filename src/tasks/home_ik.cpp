#include "mjarm/tasks/home_ik.hpp"

#include "mjarm/ik/pose_ik.hpp"

namespace mjarm {

IkResult home_pose_ik(const Robot& robot, const Chain& chain, const Pose& X_WE) {
  const Eigen::VectorXd q_home = chain.gather(robot.keyframe_qpos("home").data());
  PoseIkOptions options;
  options.posture.q_pref = q_home;
  options.posture.gain = 0.2;
  PoseIk ik(chain, options);
  return ik.solve(X_WE, q_home);
}

}  // namespace mjarm
