#include "mjarm/env/action_space.hpp"

#include "mjarm/error.hpp"

namespace mjarm {
const std::vector<ActionSpace>& action_spaces() {
  static const std::vector<ActionSpace> all{
      ActionSpace::joint_torques, ActionSpace::joint_positions, ActionSpace::joint_deltas,
      ActionSpace::ee_pose_deltas, ActionSpace::ee_velocities};
  return all;
}

ActionSpace action_space(std::string_view name) {
  return parse_enum<ActionSpace>(name, "action space");
}

OperationalSpaceOptions environment_osc_options() {
  OperationalSpaceOptions o;
  o.mode = TaskMode::pose;
  o.stiffness = Vector6d::Constant(400.0);
  o.damping = Vector6d::Constant(-1.0);
  o.nullspace_stiffness = 10.0;
  o.nullspace_damping = 2.0;
  return o;
}

void ActionOptions::check() const {
  check_fields(*this);
  if (osc.mode != TaskMode::pose)
    throw Error(
        "action options: the end-effector action spaces command a pose; osc.mode must be "
        "pose");
}

}  // namespace mjarm
