#include "mjarm/tasks/shelf_pick/controllers.hpp"

#include <cmath>

#include "mjarm/control/acceleration_control.hpp"
#include "mjarm/control/computed_torque.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/control/task_pd.hpp"
#include "mjarm/error.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

namespace {

Vector6d gains(double linear, double angular) {
  return (Vector6d() << linear, linear, linear, angular, angular, angular).finished();
}

std::unique_ptr<Controller> make_osc(const Chain& chain, const ShelfPickRobot& robot, double s) {
  OperationalSpaceOptions o;
  o.mode = robot.position_only ? TaskMode::position : TaskMode::pose;
  // per unit of desired inertia: ω_n = √K, critically damped
  o.stiffness = s * gains(2500.0, 2500.0);
  o.damping = Vector6d::Constant(-1.0);  // critical for any stiffness
  o.nullspace_damping = 2.0;
  o.nullspace_stiffness = robot.position_only ? 0.0 : 20.0;  // the IK'd posture
  return std::make_unique<OperationalSpaceController>(chain, o);
}

std::unique_ptr<Controller> make_task_pd(const Chain& chain, const ShelfPickRobot& robot,
                                         double s) {
  TaskPdOptions o;
  o.mode = robot.position_only ? TaskMode::position : TaskMode::pose;
  // no model feed-forward: only stiff gains keep the lag behind a 0.2–0.3 s move small
  if (robot.position_only) {
    o.stiffness = gains(7000.0, 0.0);
    o.damping = gains(130.0, 0.0);
  } else {
    o.stiffness = gains(60000.0, 2000.0);
    o.damping = gains(1200.0, 40.0);
    o.joint_damping = 1.0;
  }
  o.stiffness *= s;
  o.damping *= std::sqrt(s);
  return std::make_unique<TaskPdController>(chain, o);
}

std::unique_ptr<Controller> make_ct(const Chain& chain, const ShelfPickRobot&, double s) {
  ComputedTorqueOptions o;
  o.gains = JointPdGains::critically_damped(50.0 * std::sqrt(s));  // K = ω², D = 2ω
  return std::make_unique<ComputedTorqueController>(chain, o);
}

std::unique_ptr<Controller> make_accel(const Chain& chain, const ShelfPickRobot& robot, double s) {
  AccelerationControlOptions o;
  o.mode = robot.position_only ? TaskMode::position : TaskMode::pose;
  o.stiffness = Vector6d::Constant(2500.0 * s);
  o.damping = Vector6d::Constant(100.0 * std::sqrt(s));
  if (robot.position_only) {
    // the planar arm's y row of J is zero, so w = 0 always: keep the damping negligible
    o.max_damping = 1e-3;
  }
  o.nullspace_damping = 10.0;
  o.nullspace_stiffness = robot.position_only ? 0.0 : 25.0;
  return std::make_unique<AccelerationController>(chain, o);
}

}  // namespace

std::unique_ptr<Controller> make_shelf_pick_controller(std::string_view name, const Chain& chain,
                                                       const ShelfPickRobot& robot,
                                                       double gain_scale) {
  check_shelf_pick_controller(name);
  check_value(gain_scale, "shelf pick", "gain_scale", "", Range::positive());
  if (name == "ct") return make_ct(chain, robot, gain_scale);
  if (name == "osc") return make_osc(chain, robot, gain_scale);
  if (name == "task-pd") return make_task_pd(chain, robot, gain_scale);
  if (name == "accel") return make_accel(chain, robot, gain_scale);
  throw Error("shelf pick: no builder for controller '" + std::string(name) + "'");
}

}  // namespace mjarm
