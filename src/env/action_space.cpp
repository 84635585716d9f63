#include "mjarm/env/action_space.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

void require_positive_option(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0.0))
    throw Error(std::string("action options: ") + name + " must be positive and finite, got " +
                number_text(value));
}

}  // namespace

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
  require_positive_option(max_joint_delta, "max_joint_delta");
  require_positive_option(max_translation, "max_translation");
  require_positive_option(max_rotation, "max_rotation");
  require_positive_option(max_linear_speed, "max_linear_speed");
  require_positive_option(max_angular_speed, "max_angular_speed");
  require_positive_option(joint_bandwidth, "joint_bandwidth");
  require_positive_option(max_joint_speed, "max_joint_speed");
  if (osc.mode != TaskMode::pose)
    throw Error(
        "action options: the end-effector action spaces command a pose; osc.mode must be "
        "pose");
}

}  // namespace mjarm
