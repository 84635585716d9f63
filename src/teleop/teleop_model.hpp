#pragma once
// What the teleoperation sessions (single-arm viewer session, bimanual session) read off a model:
// its other actuator flavour, the gripper joints below an arm and the body the robot stands on.

#include <optional>
#include <string>
#include <vector>

#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm::detail {

/// The model file of the other flavour beside @p robot's file: `<name>_torque.xml` for torque
/// motors, `<name>.xml` for position servos; @p robot itself when it already is that flavour;
/// nullopt when there is no such file (or the model came from a string).
std::optional<Robot> model_variant(const Robot& robot, bool torque);

/// "torque mode needs the model's torque-motor variant '…' beside '…'" (or the position one).
std::string model_variant_missing(const Robot& robot, bool torque);

/// Limited hinge/slide joints below @p arm's last joint that the arm does not move (the fingers).
std::vector<std::string> gripper_joints(const Chain& arm);

/// Resets @p sim to keyframe @p keyframe when its model has one by that name, else to qpos0.
void reset_simulation(Simulation& sim, const std::string& keyframe);

/// A mode switch: @p to takes @p from's state (qpos, qvel, time) when the models have the same
/// sizes (else it is reset), and its controllers are reset.
void carry_state(const Simulation& from, Simulation& to);

/// The top-level body holding the joint @p joint ("" when unnamed).
std::string root_body(const mjModel& m, int joint);

}  // namespace mjarm::detail
