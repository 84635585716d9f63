// The pick-and-place scene: names, the table top (a box, with exact contacts for the object
// resting on it), the object's friction, the classic edits, bad input.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <string>
#include <string_view>

#include "mjarm/error.hpp"
#include "mjarm/scene/free_pose.hpp"
#include "mjarm/tasks/pick_place/scene.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;

PickPlaceSceneOptions options_for(const std::string& robot, SimulationMode mode) {
  PickPlaceSceneOptions o;
  o.robot = robot;
  o.mode = mode;
  const PickPlaceRobot& r = pick_place_robot(robot);
  const double radius = 0.5 * (r.min_radius + r.max_radius);
  o.object.position = {r.mount[0] + radius, r.mount[1] + 0.05};
  o.target = {r.mount[0] + radius, r.mount[1] - 0.1};
  return o;
}

TEST(PickPlaceScene, BothRobotsInBothModesWithEveryName) {
  for (const PickPlaceRobot& robot : pick_place_robots()) {
    for (const SimulationMode mode : {SimulationMode::position, SimulationMode::torque}) {
      SCOPED_TRACE(robot.name + " " + to_string(mode));
      const PickPlaceScene s = build_pick_place_scene(options_for(robot.name, mode));
      const Robot& m = s.model;
      EXPECT_GE(m.site(s.tool), 0);
      EXPECT_GE(m.body(s.hand), 0);
      EXPECT_GE(m.body(s.table), 0);
      EXPECT_GE(m.body(s.robot_root), 0);
      EXPECT_GE(m.site(s.target), 0);
      for (const std::string& finger : s.fingers) {
        EXPECT_GE(m.joint(finger), 0);
        EXPECT_GE(m.geom(finger), 0);
      }
      EXPECT_EQ(s.cameras.size(), 3u);
      for (const std::string& camera : s.cameras) EXPECT_GE(m.camera(camera), 0);
      EXPECT_EQ(s.arm_joints.size(), robot.name == "arm6" ? 6u : 7u);
      // the free object adds 7 coordinates; the weld is there, switched off
      EXPECT_EQ(m.model().neq, 1);
      EXPECT_EQ(m.model().eq_active0[0], 0);
      EXPECT_EQ(m.model().eq_obj1id[0], m.body(s.hand));
      EXPECT_EQ(m.model().eq_obj2id[0], m.body(s.object));
      // motors in torque mode, servos in position mode
      const ActuatorKind kind = m.actuators().front().kind;
      EXPECT_EQ(kind,
                mode == SimulationMode::torque ? ActuatorKind::motor : ActuatorKind::position);
      // the object rests on the table top, a box whose upper face is at the table's height
      const int top = m.geom(robot.own_table ? robot.name + "/table_top" : "arena/table_top");
      EXPECT_EQ(m.model().geom_type[top], mjGEOM_BOX);
      DataPtr d = m.make_data();
      const std::vector<double> home = m.keyframe_qpos("home");
      std::copy(home.begin(), home.end(), d->qpos);
      mj_forward(&m.model(), d.get());
      EXPECT_NEAR(d->geom_xpos[3 * top + 2] + m.model().geom_size[3 * top + 2], robot.table_height,
                  1e-12);
      const FreePose p = free_pose(m, *d, s.object);
      EXPECT_NEAR(p.p_WB[2], robot.table_height + 0.015, 1e-12);
      // the object's friction wins over the fingers' (priority)
      EXPECT_GT(m.model().geom_priority[m.geom(s.object + "/geom")],
                m.model().geom_priority[m.geom(s.fingers[0])]);
    }
  }
}

TEST(PickPlaceScene, ClassicEdits) {
  PickPlaceSceneOptions o = options_for("panda_hand", SimulationMode::position);
  o.finger_travel = {0.0, 0.012};
  o.finger_servo_gain = 3200.0;
  const PickPlaceScene s = build_pick_place_scene(o);
  const mjModel& m = s.model.model();
  for (const std::string& finger : s.fingers) {
    const int j = s.model.joint(finger), a = s.model.actuator(finger);
    EXPECT_EQ(m.jnt_range[2 * j + 1], 0.012);
    EXPECT_EQ(m.actuator_ctrlrange[2 * a + 1], 0.012);
    EXPECT_EQ(m.actuator_gainprm[a * mjNGAIN], 3200.0);
    EXPECT_EQ(m.actuator_biasprm[a * mjNBIAS + 1], -3200.0);
    EXPECT_EQ(m.actuator_biasprm[a * mjNBIAS + 2], -4.0);  // the model's damping kept
  }
  // torque mode: the travel applies to the joints, the gain does not (motors)
  o.mode = SimulationMode::torque;
  const PickPlaceScene t = build_pick_place_scene(o);
  EXPECT_EQ(t.model.model().jnt_range[2 * t.model.joint(t.fingers[0]) + 1], 0.012);
  EXPECT_EQ(t.model.actuators()[7].kind, ActuatorKind::motor);
}

// The table top is a box: MuJoCo's box-box collider gives exact face-on-face contacts for a small
// box resting on it (MuJoCo 2.2.2's gave contacts half a metre deep for some poses, which shot
// the object away at the first step): none deeper than a micrometre over poses all around
TEST(PickPlaceScene, AnObjectRestingOnTheTableTopTouchesItExactly) {
  PickPlaceSceneOptions o = options_for("arm6", SimulationMode::position);
  o.object.size = {0.017229543605401777, 0.017229543605401777, 0.017229543605401777};
  const PickPlaceScene s = build_pick_place_scene(o);
  const mjModel& m = s.model.model();
  int box_tops = 0;
  for (int g = 0; g < m.ngeom; ++g) {
    const char* name = mj_id2name(&m, mjOBJ_GEOM, g);
    if (name != nullptr && std::string_view(name).ends_with("table_top"))
      box_tops += m.geom_type[g] == mjGEOM_BOX;
  }
  EXPECT_EQ(box_tops, 1);
  DataPtr e = s.model.make_data();
  const std::vector<double> home = s.model.keyframe_qpos("home");
  int poses = 0;
  for (int yaw = 0; yaw < 90; yaw += 3) {
    for (double x = 0.2; x < 0.4; x += 0.02) {
      std::copy(home.begin(), home.end(), e->qpos);
      const double a = yaw * M_PI / 180.0;
      set_free_pose(
          s.model, *e, s.object,
          {{x, -0.1, 0.75 + o.object.size[2]}, {std::cos(a / 2), 0.0, 0.0, std::sin(a / 2)}});
      mj_forward(&s.model.model(), e.get());
      for (int c = 0; c < e->ncon; ++c) EXPECT_GT(e->contact[c].dist, -1e-6) << yaw << " " << x;
      ++poses;
    }
  }
  EXPECT_EQ(poses, 300);
}

TEST(PickPlaceScene, BadInput) {
  PickPlaceSceneOptions o = options_for("arm6", SimulationMode::position);
  o.robot = "panda";
  EXPECT_NE(error_of([&] {
              build_pick_place_scene(o);
            }).find("unknown robot 'panda' for the pick and place; choices: arm6, panda_hand"),
            std::string::npos);
  o = options_for("arm6", SimulationMode::position);
  o.object.shape = "torus";
  EXPECT_NE(error_of([&] { build_pick_place_scene(o); }).find("choices: box, cylinder"),
            std::string::npos);
  o = options_for("arm6", SimulationMode::position);
  o.object.size = {0.01, 0.01};
  EXPECT_NE(error_of([&] { build_pick_place_scene(o); }).find("3 half extents"), std::string::npos);
  o = options_for("arm6", SimulationMode::position);
  o.object.mass = -1.0;
  EXPECT_NE(error_of([&] { build_pick_place_scene(o); }).find("mass"), std::string::npos);
  o = options_for("arm6", SimulationMode::position);
  o.finger_travel = {0.02, 0.01};
  EXPECT_NE(error_of([&] { build_pick_place_scene(o); }).find("finger_travel"), std::string::npos);
  o = options_for("arm6", SimulationMode::position);
  o.mode = SimulationMode::kinematic;
  EXPECT_NE(error_of([&] { build_pick_place_scene(o); }).find("position or torque"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
