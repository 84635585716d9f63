#include "mjarm/tasks/pick_place/scene.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

const std::vector<PickPlaceRobot>& pick_place_robots() {
  static const std::vector<PickPlaceRobot> robots = [] {
    std::vector<PickPlaceRobot> list;
    PickPlaceRobot arm6;
    arm6.name = "arm6";
    arm6.position_model = "arm6";
    arm6.torque_model = "arm6_torque";
    arm6.tool = "grip";
    arm6.hand = "link6";
    arm6.fingers = {"finger_left", "finger_right"};
    arm6.own_table = true;  // top at z = 0.75, the base at the world origin on it
    arm6.table_height = 0.75;
    // with the tool pointing down the wrist stays 0.14 m above it: the shoulder (0.12 m above
    // the table) reaches the tool at 0.15–0.36 m from the base axis
    arm6.min_radius = 0.20;
    arm6.max_radius = 0.32;
    arm6.max_bearing = 1.0;
    list.push_back(arm6);

    PickPlaceRobot panda;
    panda.name = "panda_hand";
    panda.position_model = "panda_hand";
    panda.torque_model = "panda_hand_torque";
    panda.tool = "tcp";
    panda.hand = "hand";
    panda.fingers = {"finger_left", "finger_right"};
    panda.mount = {0.12, 0.0, 0.4};  // on the arena's table, near its back edge
    panda.own_table = false;
    panda.table_height = 0.4;
    panda.min_radius = 0.35;
    panda.max_radius = 0.60;
    panda.max_bearing = 0.9;
    list.push_back(panda);
    return list;
  }();
  return robots;
}

const PickPlaceRobot& pick_place_robot(std::string_view name) {
  std::string names;
  for (const auto& robot : pick_place_robots()) {
    if (robot.name == name) return robot;
    names += (names.empty() ? "" : ", ") + robot.name;
  }
  throw Error("unknown robot '" + std::string(name) +
              "' for the pick and place; choices: " + names);
}

double object_half_height(const PickPlaceObject& object) {
  if (object.shape == "box") {
    if (object.size.size() != 3)
      throw Error("pick and place: a box object needs 3 half extents [m], got " +
                  std::to_string(object.size.size()) + " values");
    return object.size[2];
  }
  if (object.shape == "cylinder") {
    if (object.size.size() != 2)
      throw Error("pick and place: a cylinder object needs a radius and a half height [m], got " +
                  std::to_string(object.size.size()) + " values");
    return object.size[1];
  }
  throw Error("unknown object shape '" + object.shape +
              "' for the pick and place; choices: box, cylinder");
}

namespace {

// the names of the scene, before it is compiled
struct Names {
  std::string tool, hand, table, robot_root;
  std::array<std::string, 2> fingers;
  std::string object = "object", target = "target", weld = "grasp";
  std::vector<std::string> cameras;
};

std::array<double, 6> camera_axes(double tilt, bool side) {
  const double s = std::sin(tilt), c = std::cos(tilt);
  if (side) return {1, 0, 0, 0, s, c};  // from −y, looking at +y
  return {0, 1, 0, -s, 0, c};           // from +x, looking at −x
}

}  // namespace

PickPlaceScene build_pick_place_scene(const PickPlaceSceneOptions& options) {
  const PickPlaceRobot& robot = pick_place_robot(options.robot);
  const double half_height = object_half_height(options.object);
  if (options.mode == SimulationMode::kinematic)
    throw Error("pick and place: the mode must be position or torque, not kinematic");
  const std::string prefix = robot.name;
  Names out;
  out.tool = prefix + "/" + robot.tool;
  out.hand = prefix + "/" + robot.hand;
  for (int i = 0; i < 2; ++i) out.fingers[i] = prefix + "/" + robot.fingers[i];
  out.table = robot.own_table ? prefix + "/table" : "arena/table";

  Scene scene("pick_place_" + robot.name);
  ArenaSpec arena;
  if (!robot.own_table) {
    arena.table = true;
    arena.table_center = {robot.mount[0] + 0.38, robot.mount[1]};
    arena.table_half_size = {0.45, 0.65};
    arena.table_height = robot.table_height;
  }
  scene.add_arena(arena);
  const std::string& file =
      options.mode == SimulationMode::torque ? robot.torque_model : robot.position_model;
  scene.add_robot({prefix, file, robot.mount, {1, 0, 0, 0}, false});
  out.robot_root = prefix + "/" + (robot.own_table ? "base" : "link0");

  ObjectSpec object;
  object.name = out.object;
  object.shape = object_shape(options.object.shape);
  object.size = options.object.size;
  object.mass = options.object.mass;
  object.friction = {options.object.friction, 0.005, 0.0001};
  object.pos = {options.object.position[0], options.object.position[1],
                robot.table_height + half_height};
  object.quat = {std::cos(0.5 * options.object.yaw), 0.0, 0.0, std::sin(0.5 * options.object.yaw)};
  scene.add_object(object);
  // the object's friction is the one the trial draws: it wins over the fingers' and the table's
  scene.set_attribute("geom", out.object + "/geom", "priority", "1");

  SiteSpec target;
  target.name = out.target;
  target.pos = {options.target[0], options.target[1], robot.table_height + half_height};
  target.size = 0.004;
  target.rgba = {0.1, 0.8, 0.2, 0.6};
  scene.add_site(target);
  scene.add_weld({out.weld, out.hand, out.object, false, {0.002, 1.0}});

  // three views of the workspace, from the front, the side and above
  const double cx = robot.mount[0] + 0.5 * (robot.min_radius + robot.max_radius);
  const double cy = robot.mount[1], cz = robot.table_height;
  const double d = 1.3 * robot.max_radius + 0.25;
  const double tilt = 0.6;
  SceneCameraSpec front;
  front.name = "front";
  front.pos = {cx + d * std::cos(tilt), cy, cz + d * std::sin(tilt)};
  front.xyaxes = camera_axes(tilt, false);
  SceneCameraSpec side;
  side.name = "side";
  side.pos = {cx, cy - d * std::cos(tilt), cz + d * std::sin(tilt)};
  side.xyaxes = camera_axes(tilt, true);
  SceneCameraSpec top;
  top.name = "top";
  top.pos = {cx, cy, cz + 1.1 * d};
  top.xyaxes = {0, 1, 0, -1, 0, 0};  // image right = +y, up = +x (the robot at the bottom)
  for (const SceneCameraSpec* c : {&front, &side, &top}) {
    scene.add_camera(*c);
    out.cameras.push_back(c->name);
  }

  // the classic edits: finger travel and finger servo gain
  if (!options.finger_travel.empty()) {
    const std::vector<double>& t = options.finger_travel;
    if (t.size() != 2 || !(std::isfinite(t[0]) && std::isfinite(t[1])) || !(t[0] < t[1]) ||
        t[0] < 0.0 || t[1] > 0.04)
      throw Error(
          "pick and place: finger_travel needs two increasing values within [0, 0.04] m "
          "(closed, open), got " +
          std::to_string(t.size()) + " values");
    for (const std::string& finger : out.fingers) {
      scene.set_attribute("joint", finger, "range", t);
      if (options.mode == SimulationMode::position)
        scene.set_attribute("actuator", finger, "ctrlrange", t);
    }
  }
  if (options.finger_servo_gain != 0.0 && options.mode == SimulationMode::position) {
    const double kp = options.finger_servo_gain;
    if (!(std::isfinite(kp) && kp > 0.0))
      throw Error("pick and place: finger_servo_gain must be positive [N/m], got " +
                  number_text(kp));
    for (const std::string& finger : out.fingers) {
      const std::optional<std::string> bias = scene.attribute("actuator", finger, "biasprm");
      double kv = 0.0;
      if (bias) {
        // "0 -kp -kv": keep the damping
        double a = 0.0, b = 0.0;
        std::sscanf(bias->c_str(), "%lf %lf %lf", &a, &b, &kv);
      }
      const double gain[1] = {kp};
      const double biasprm[3] = {0.0, -kp, kv == 0.0 ? 0.0 : kv};
      scene.set_attribute("actuator", finger, "gainprm", gain);
      scene.set_attribute("actuator", finger, "biasprm", biasprm);
    }
  }
  if (options.noslip_iterations < 0 || options.noslip_iterations > 1000)
    throw Error("pick and place: noslip_iterations must be in [0, 1000], got " +
                std::to_string(options.noslip_iterations));
  if (!(std::isfinite(options.impratio) && options.impratio >= 1.0))
    throw Error("pick and place: impratio must be ≥ 1, got " + number_text(options.impratio));
  scene.set_option("noslip_iterations", std::to_string(options.noslip_iterations));
  scene.set_option("impratio", number_text(options.impratio));

  Robot model = scene.compile();
  std::vector<std::string> arm_joints;
  const mjModel& m = model.model();
  for (int j = 0; j < m.njnt; ++j) {
    const char* name = mj_id2name(&m, mjOBJ_JOINT, j);
    if (name == nullptr || m.jnt_type[j] != mjJNT_HINGE) continue;
    if (std::string(name).rfind(prefix + "/", 0) == 0) arm_joints.push_back(name);
  }
  return PickPlaceScene{.model = std::move(model),
                        .robot = &robot,
                        .tool = out.tool,
                        .hand = out.hand,
                        .fingers = out.fingers,
                        .arm_joints = std::move(arm_joints),
                        .table = out.table,
                        .robot_root = out.robot_root,
                        .object = out.object,
                        .target = out.target,
                        .weld = out.weld,
                        .cameras = out.cameras,
                        .table_height = robot.table_height};
}

}  // namespace mjarm
