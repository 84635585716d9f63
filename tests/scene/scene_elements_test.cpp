// Scene::add: any element from its MJCF tag and attributes, checked when added; the book's
// two-link planar arm built element by element; defaults; the scene unchanged by a failed add.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/scene/scene.hpp"

namespace mjarm {
namespace {

// the two-link planar arm of the textbooks: 0.3 m links turning about z, motors, a tip site and
// joint sensors, all from code
Scene planar_arm() {
  Scene scene("planar");
  scene.add({"body", "link1", "", "", {}});
  scene.add({"joint", "shoulder", "link1", "", {{"type", "hinge"}, {"axis", "0 0 1"}}});
  scene.add({"geom",
             "upper",
             "link1",
             "",
             {{"type", "capsule"}, {"fromto", "0 0 0 0.3 0 0"}, {"size", "0.02"}}});
  scene.add({"body", "link2", "link1", "", {{"pos", "0.3 0 0"}}});
  scene.add({"joint", "elbow", "link2", "", {{"type", "hinge"}, {"axis", "0 0 1"}}});
  scene.add({"geom",
             "fore",
             "link2",
             "",
             {{"type", "capsule"}, {"fromto", "0 0 0 0.3 0 0"}, {"size", "0.02"}}});
  scene.add({"site", "tip", "link2", "", {{"pos", "0.3 0 0"}}});
  scene.add({"motor",
             "shoulder_motor",
             "",
             "",
             {{"joint", "shoulder"}, {"gear", "2"}, {"ctrlrange", "-1 1"}}});
  scene.add({"position", "elbow_servo", "", "", {{"joint", "elbow"}, {"kp", "50"}, {"kv", "3"}}});
  scene.add({"jointpos", "elbow_angle", "", "", {{"joint", "elbow"}}});
  scene.add({"framepos", "tip_position", "", "", {{"objtype", "site"}, {"objname", "tip"}}});
  return scene;
}

TEST(SceneElements, TheBooksTwoLinkArmBuiltFromCodePutsItsTipWhereTheBookSays) {
  const Robot robot = planar_arm().compile();
  const mjModel& m = robot.model();
  ASSERT_EQ(m.nq, 2);
  DataPtr d = robot.make_data();
  d->qpos[0] = 0.0;
  d->qpos[1] = std::numbers::pi / 4;
  mj_forward(&m, d.get());
  const double* tip = d->site_xpos + 3 * robot.site("tip");
  EXPECT_NEAR(tip[0], 0.512132, 5e-7);
  EXPECT_NEAR(tip[1], 0.212132, 5e-7);
  EXPECT_NEAR(tip[2], 0.0, 1e-12);
  // the sensors read what they were added for
  EXPECT_DOUBLE_EQ(d->sensordata[0], std::numbers::pi / 4);
  EXPECT_NEAR(d->sensordata[1], 0.512132, 5e-7);
  // the actuators are what their tags say: a motor with its gear, a position servo
  EXPECT_EQ(m.actuator_trntype[0], mjTRN_JOINT);
  EXPECT_DOUBLE_EQ(m.actuator_gear[0], 2.0);
  EXPECT_EQ(m.actuator_biastype[0], mjBIAS_NONE);
  EXPECT_EQ(m.actuator_ctrllimited[0], 1);
  EXPECT_DOUBLE_EQ(m.actuator_gainprm[mjNGAIN * 1], 50.0);
  EXPECT_DOUBLE_EQ(m.actuator_biasprm[mjNBIAS * 1 + 1], -50.0);
  EXPECT_DOUBLE_EQ(m.actuator_biasprm[mjNBIAS * 1 + 2], -3.0);
}

TEST(SceneElements, TheXmlOfTheSceneHoldsTheElementsAndLoadsIntoTheSameArm) {
  const Scene scene = planar_arm();
  const std::string xml = scene.xml();
  EXPECT_NE(xml.find("name=\"elbow_servo\""), std::string::npos);
  const Robot again = Robot::from_string(xml);
  EXPECT_EQ(again.model().nu, 2);
  EXPECT_EQ(again.model().nsensor, 2);
}

TEST(SceneElements, ADefaultClassGivesItsValuesToTheElementsMadeFromIt) {
  Scene scene("defaults");
  scene.add({"default", "heavy", "", "", {{"geom.mass", "2"}, {"joint.damping", "0.5"}}});
  scene.add({"default", "heavier", "heavy", "", {{"geom.mass", "3"}}});
  scene.add({"body", "block", "", "", {}});
  scene.add({"joint", "slide", "block", "heavy", {{"type", "slide"}}});
  scene.add({"geom", "cube", "block", "heavier", {{"type", "box"}, {"size", "0.1 0.1 0.1"}}});
  EXPECT_TRUE(scene.has("default", "heavier"));
  const Robot robot = scene.compile();
  EXPECT_DOUBLE_EQ(robot.model().body_mass[1], 3.0) << "the child class's mass";
  EXPECT_DOUBLE_EQ(robot.model().dof_damping[0], 0.5) << "the parent class's damping, inherited";
}

TEST(SceneElements, BadElementsAreRefusedWithTheClosestNamesAndLeaveTheSceneUnchanged) {
  Scene scene = planar_arm();
  const std::string before = scene.xml();
  auto message = [&](const ElementSpec& e) -> std::string {
    try {
      scene.add(e);
    } catch (const Error& error) {
      if (std::getenv("SHOW")) std::printf("%s\n", error.what());
      return error.what();
    }
    return "no error";
  };
  EXPECT_NE(message({"gemo", "x", "", "", {}}).find("unknown tag 'gemo'; closest: geom"),
            std::string::npos);
  EXPECT_NE(message({"geom", "tip2", "link3", "", {}}).find("closest: link1, link2"),
            std::string::npos);
  EXPECT_NE(message({"geom", "upper", "link1", "", {}}).find("name clash"), std::string::npos);
  EXPECT_NE(message({"geom", "g", "link1", "", {{"szie", "0.1"}}}).find("size"), std::string::npos);
  EXPECT_NE(message({"geom", "g", "link1", "", {{"size", "0.1 nan"}}}).find("finite"),
            std::string::npos);
  EXPECT_NE(message({"geom", "g", "link1", "", {{"type", "cube"}}}).find("box"), std::string::npos);
  EXPECT_NE(message({"joint", "j", "link1", "stiff", {}}).find("no default class 'stiff'"),
            std::string::npos);
  EXPECT_NE(message({"position", "p", "", "", {{"kp", "x"}}}).find("kp must be a finite number"),
            std::string::npos);
  EXPECT_NE(message({"framepos", "f", "", "", {{"objtype", "planet"}}}).find("object type"),
            std::string::npos);
  EXPECT_NE(message({"default", "d", "", "", {{"mass", "1"}}}).find("<element>.<attribute>"),
            std::string::npos);
  EXPECT_NE(message({"default", "d", "", "", {{"wheel.mass", "1"}}}).find("geom"),
            std::string::npos);
  EXPECT_NE(message({"site", "", "link1", "", {}}).find("needs a name"), std::string::npos);
  EXPECT_EQ(scene.xml(), before) << "every refused add left the scene as it was";
  EXPECT_FALSE(scene.has("geom", "g"));
}

}  // namespace
}  // namespace mjarm
