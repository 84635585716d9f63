#pragma once
// What the teleoperation sessions (single-arm viewer session, bimanual session) share besides their
// mode switch (mode_rigs.hpp): a model's other actuator flavour, the gripper joints below an arm,
// the body the robot stands on, the initial keyframe, a rig's simulation and frame reads.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/teleop/detail/mode_rigs.hpp"

namespace mjarm::detail {

/// The model file of the other flavour beside @p robot's file: `<name>_torque.xml` for torque
/// motors, `<name>.xml` for position servos; @p robot itself when it already is that flavour;
/// nullopt when there is no such file (or the model came from a string).
std::optional<Robot> model_variant(const Robot& robot, bool torque);

/// "torque mode needs the model's torque-motor variant '…' beside '…'" (or the position one).
std::string model_variant_missing(const Robot& robot, bool torque);

/// Limited hinge/slide joints below @p arm's last joint that the arm does not move (the fingers).
std::vector<std::string> gripper_joints(const Chain& arm);

/// The initial keyframe of a session: @p keyframe when given (checked: an unknown name throws
/// `Error`, naming close ones), else "home" when @p robot has it, else "" (qpos0).
std::string initial_keyframe(const Robot& robot, const std::string& keyframe);

/// The pose of @p frame in @p d, read directly (the chain that holds the frame checked its id).
Pose read_frame(const mjData& d, const FrameRef& frame) noexcept;

/// The simulation of a session's rig in @p mode: kinematic mode steps @p kinematic_period [s]
/// rounded to whole timesteps (≥ 1) per tick, with @p contact_check (empty: none) rolled back;
/// the others tick at @p control_period (0: one physics step). @p period receives the rig's tick.
std::unique_ptr<Simulation> rig_simulation(const Robot& robot, SimulationMode mode,
                                           double kinematic_period, double control_period,
                                           const GeomSet& contact_check, double& period);

/// Resets @p sim to keyframe @p keyframe when its model has one by that name, else to qpos0.
void reset_simulation(Simulation& sim, const std::string& keyframe);

/// The top-level body holding the joint @p joint ("" when unnamed).
std::string root_body(const mjModel& m, int joint);

}  // namespace mjarm::detail
