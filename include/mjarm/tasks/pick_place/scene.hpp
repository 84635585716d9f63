#pragma once
/// @file
/// The scene of a pick and place: a robot on a table, a free object, a target marker, a weld for
/// the weld grasp and cameras — composed with the scene room (`Scene`) for one trial.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/model/robot.hpp"
#include "mjarm/scene/scene.hpp"
#include "mjarm/sim/simulation_options.hpp"

namespace mjarm {

/// A robot the pick and place knows: its models, tool, gripper and table. Names are the robot's
/// own (unprefixed); positions are world coordinates [m].
struct PickPlaceRobot {
  std::string name;            ///< what the user types ("arm6")
  std::string position_model;  ///< bundled model with position servos ("arm6")
  std::string torque_model;    ///< bundled model with torque motors ("arm6_torque")
  std::string tool;            ///< tool site between the fingertips ("grip")
  std::string hand;            ///< body carrying the fingers ("link6")
  std::array<std::string, 2>
      fingers;  ///< finger joints; each finger's body and geom share its name
  std::array<double, 3> mount{0.0, 0.0, 0.0};  ///< where the robot stands
  bool own_table = false;     ///< the model brings its table (body "table"); else the arena's
  double table_height = 0.0;  ///< top surface of the table
  /// The part of the table trials draw from: points at a horizontal distance in [min_radius,
  /// max_radius] from the robot's base axis, at a bearing within ±max_bearing [rad] of +x.
  double min_radius = 0.0;
  double max_radius = 0.0;
  double max_bearing = 0.0;
};

/// The robots, in a fixed order: arm6, panda_hand.
const std::vector<PickPlaceRobot>& pick_place_robots();
/// The robot called @p name.
/// @throws Error "unknown robot 'x' for the pick and place; choices: arm6, panda_hand".
const PickPlaceRobot& pick_place_robot(std::string_view name);

/// The object to pick: a box (or cylinder) resting upright on the table.
struct PickPlaceObject {
  std::string shape = "box";  ///< "box" or "cylinder" (upright)
  /// box: half extents x y z; cylinder: radius, half height [m].
  std::vector<double> size{0.015, 0.015, 0.015};
  double mass = 0.05;     ///< [kg]
  double friction = 1.0;  ///< sliding friction; wins over the fingers' and the table's
  std::array<double, 2> position{0.0, 0.0};  ///< centre on the table, x y [m]
  double yaw = 0.0;                          ///< about the vertical [rad]
};

/// What the scene of one trial is made of.
struct PickPlaceSceneOptions {
  std::string robot = "arm6";
  SimulationMode mode = SimulationMode::position;  ///< position: servo model; torque: motors
  PickPlaceObject object;
  std::array<double, 2> target{0.0, 0.0};  ///< where the object should end, x y [m]
  /// The classic scene edits (position and torque models alike, where they apply): finger
  /// travel [lower, upper] per finger [m] (joint range and, for servos, ctrlrange); finger servo
  /// gain kp [N/m] (position mode; the damping stays as the model has it). Empty / 0: the
  /// model's own.
  std::vector<double> finger_travel;
  double finger_servo_gain = 0.0;
  /// Solver option `noslip_iterations` of the scene (0: MuJoCo's default, none).
  int noslip_iterations = 0;
  double impratio = 1.0;  ///< MuJoCo's frictional-to-normal impedance ratio (≥ 1)
};

/// A composed pick-and-place scene and the names a run needs (all prefixed as in the model).
struct PickPlaceScene {
  Robot model;
  const PickPlaceRobot* robot = nullptr;
  std::string tool;                     ///< "arm6/grip"
  std::string hand;                     ///< "arm6/link6"
  std::array<std::string, 2> fingers;   ///< finger joints = bodies = geoms ("arm6/finger_left")
  std::vector<std::string> arm_joints;  ///< the arm's hinge joints, base to flange
  std::string table;                    ///< table body ("arm6/table", "arena/table")
  std::string robot_root;               ///< body whose subtree is the robot ("arm6/base", "panda")
  std::string object = "object";        ///< the free body (geom "object/geom")
  std::string target = "target";        ///< world site at the target (object centre at rest)
  std::string weld = "grasp";           ///< weld hand → object, inactive
  std::vector<std::string> cameras;     ///< "front", "side", "top"
  double table_height = 0.0;            ///< top surface [m]
};

/// Composes the scene: arena (with a table unless the robot brings one), the robot (its servo or
/// motor model), the object resting on the table at its pose, the target site at the object's
/// resting height, the weld, three cameras, the classic edits.
/// @throws Error for an unknown robot, a bad object (shape, size, mass, friction), a finger travel
///         that is not two increasing values within the joint's reach, or a value MuJoCo refuses.
PickPlaceScene build_pick_place_scene(const PickPlaceSceneOptions& options);

/// Height of the object's centre above its base when upright [m] (box: z half extent; cylinder:
/// half height).
/// @throws Error for a shape or size that is not one of the above.
double object_half_height(const PickPlaceObject& object);

}  // namespace mjarm
