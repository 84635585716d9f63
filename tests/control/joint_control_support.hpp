#pragma once
// Shared pieces of the joint-space controller tests: a closed loop that runs a controller on
// torque motors the way users run it (mj_step1 → compute → ctrl = τ / gear → mj_step2).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::test {

/// The torque-driven Panda arm up to its attachment site.
inline Chain panda() { return Chain(Robot::bundled("panda_torque"), "attachment_site"); }

/// Writes a torque command to the chain's motors: ctrl = τ / gear (MuJoCo clips to ctrlrange).
inline void apply_torque(const Chain& chain, const JointCommand& command, mjData& d) {
  const mjModel& m = chain.robot().model();
  for (int i = 0; i < chain.size(); ++i) {
    const int actuator = *chain.actuator(i);
    d.ctrl[actuator] = command.value[i] / m.actuator_gear[6 * actuator];
  }
}

/// Writes a position command to the chain's servos: ctrl = gear · q_target.
inline void apply_position(const Chain& chain, const JointCommand& command, mjData& d) {
  const mjModel& m = chain.robot().model();
  for (int i = 0; i < chain.size(); ++i) {
    const int actuator = *chain.actuator(i);
    d.ctrl[actuator] = command.value[i] * m.actuator_gear[6 * actuator];
  }
}

/// Runs @p controllers (each on its own chain, torque or position) for @p steps physics steps,
/// calling @p reference(time, ref) before each tick and @p observe(d) after each step.
inline void run_loop(const Robot& robot, mjData& d, const std::vector<Controller*>& controllers,
                     int steps, const std::function<void(double, Reference&)>& reference,
                     const std::function<void(const mjData&)>& observe = {}) {
  const mjModel& m = robot.model();
  Reference ref;
  std::vector<JointCommand> commands(controllers.size());
  for (std::size_t k = 0; k < controllers.size(); ++k) {
    commands[k].value = Eigen::VectorXd::Zero(controllers[k]->chain().size());
  }
  for (int s = 0; s < steps; ++s) {
    mj_step1(&m, &d);
    if (reference) reference(d.time, ref);
    for (std::size_t k = 0; k < controllers.size(); ++k) {
      controllers[k]->compute(d, ref, commands[k]);
      if (commands[k].kind == CommandKind::torque) {
        apply_torque(controllers[k]->chain(), commands[k], d);
      } else {
        apply_position(controllers[k]->chain(), commands[k], d);
      }
    }
    mj_step2(&m, &d);
    if (observe) observe(d);
  }
}

/// Puts the model's 'home' keyframe into @p d (qpos, qvel = 0, ctrl) and runs mj_forward.
inline void go_home(const Robot& robot, mjData& d) {
  mj_resetDataKeyframe(&robot.model(), &d, robot.keyframe("home"));
  mj_forward(&robot.model(), &d);
}

}  // namespace mjarm::test
