// MJCF parts attached with mjs_attach keep their own units, euler sequence, default classes,
// asset folders and global options (src/scene/scene.cpp), checked through the public Scene.

#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <random>

#include "mjarm/model/names.hpp"
#include "mjarm/scene/scene.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

// degrees, a zyx euler sequence, joint ranges from default classes (one serving a slide joint,
// whose range is a length and must not be converted), ref and springref, axis-angle and euler
// orientations on bodies, geoms and sites, a ball joint
constexpr const char* kDegreeArm = R"(
<mujoco model="deg">
  <compiler angle="degree" eulerseq="zyx" autolimits="true"/>
  <default>
    <joint range="-90 90" damping="0.1"/>
    <default class="wrist">
      <joint range="-45 120"/>
    </default>
  </default>
  <worldbody>
    <body name="base" euler="30 0 0">
      <joint name="j1" axis="0 0 1" ref="10"/>
      <geom type="capsule" fromto="0 0 0 0 0 0.3" size="0.03"/>
      <body name="link" pos="0 0 0.3" euler="0 45 20">
        <joint name="j2" axis="0 1 0" class="wrist" springref="5"/>
        <joint name="s" type="slide" axis="1 0 0"/>
        <geom type="box" size="0.02 0.02 0.1" pos="0 0 0.1" axisangle="1 0 0 30"/>
        <site name="tip" pos="0 0 0.2" euler="10 20 30"/>
        <body name="ball_link" pos="0 0 0.2" axisangle="0 1 1 -40">
          <joint name="b" type="ball" range="0 60"/>
          <geom size="0.02"/>
          <site name="end" pos="0.1 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
)";

std::filesystem::path write_part(const std::string& name, const std::string& text) {
  const auto file = test::scratch() / name;
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
  return file;
}

TEST(AttachedPart, DegreePartMergedIntoARadianSceneKeepsItsKinematics) {
  const auto file = write_part("deg/deg.xml", kDegreeArm);
  const Robot alone = Robot::from_file(file);
  Scene scene;
  scene.add_robot({"deg", file.string(), {}, {1, 0, 0, 0}, false});
  const Robot merged = scene.compile();
  const mjModel& a = alone.model();
  const mjModel& m = merged.model();
  ASSERT_EQ(m.nq, a.nq);
  for (int j = 0; j < a.njnt; ++j) {
    const int id = merged.joint("deg/" + std::string(mj_id2name(&a, mjOBJ_JOINT, j)));
    EXPECT_NEAR(m.jnt_range[2 * id], a.jnt_range[2 * j], 1e-12) << j;
    EXPECT_NEAR(m.jnt_range[2 * id + 1], a.jnt_range[2 * j + 1], 1e-12) << j;
    EXPECT_NEAR(m.qpos_spring[m.jnt_qposadr[id]], a.qpos_spring[a.jnt_qposadr[j]], 1e-12) << j;
  }
  // the slide joint's range is a length: untouched
  EXPECT_EQ(m.jnt_range[2 * merged.joint("deg/s") + 1], 90.0);
  for (int i = 0; i < a.nq; ++i) EXPECT_NEAR(m.qpos0[i], a.qpos0[i], 1e-12) << i;

  DataPtr da = alone.make_data();
  DataPtr dm = merged.make_data();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    for (int i = 0; i < a.nq; ++i) da->qpos[i] = dm->qpos[i] = u(rng);
    mj_normalizeQuat(&a, da->qpos);
    mj_normalizeQuat(&m, dm->qpos);
    mj_kinematics(&a, da.get());
    mj_kinematics(&m, dm.get());
    for (const char* body : {"base", "link", "ball_link"}) {
      const int ia = alone.body(body);
      const int im = merged.body(std::string("deg/") + body);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(dm->xpos[3 * im + k], da->xpos[3 * ia + k], 1e-12);
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(dm->xquat[4 * im + k], da->xquat[4 * ia + k], 1e-12);
    }
    for (const char* site : {"tip", "end"}) {
      const int ia = alone.site(site);
      const int im = merged.site(std::string("deg/") + site);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(dm->site_xpos[3 * im + k], da->site_xpos[3 * ia + k], 1e-12);
      for (int k = 0; k < 9; ++k)
        EXPECT_NEAR(dm->site_xmat[9 * im + k], da->site_xmat[9 * ia + k], 1e-12);
    }
    for (int g = 0; g < a.ngeom; ++g)
      for (int k = 0; k < 9; ++k)
        EXPECT_NEAR(dm->geom_xmat[9 * g + k], da->geom_xmat[9 * g + k], 1e-12);
  }
}

TEST(AttachedPart, EditsOfADegreePartAreInDegrees) {
  const auto file = write_part("deg/deg.xml", kDegreeArm);
  Scene scene;
  scene.add_robot({"deg", file.string(), {}, {1, 0, 0, 0}, false});
  const std::vector<double> range{-30.0, 60.0};
  scene.set_attribute("joint", "deg/j2", "range", range);
  EXPECT_EQ(scene.attribute("joint", "deg/j2", "range"), "-30 60");
  // the body's euler, as written in the part (degrees, zyx)
  EXPECT_EQ(scene.attribute("body", "deg/link", "euler"), "0 45 20");
  EXPECT_EQ(scene.attribute("body", "deg/link", "quat"), std::nullopt);
  const Robot robot = scene.compile();
  const int j = robot.joint("deg/j2");
  EXPECT_NEAR(robot.model().jnt_range[2 * j], -std::numbers::pi / 6.0, 1e-15);
  EXPECT_NEAR(robot.model().jnt_range[2 * j + 1], std::numbers::pi / 3.0, 1e-15);
}

TEST(AttachedPart, AGripperSitsAtASitePosedInDegreesAndByADefaultClass) {
  // the site's position comes from the part's default class, its orientation from a zyx euler
  // in degrees
  const auto file = write_part("flange/flange.xml", R"(
<mujoco model="flange">
  <compiler angle="degree" eulerseq="zyx"/>
  <default><site pos="0.02 0 0.1"/></default>
  <worldbody>
    <body name="link">
      <joint name="j" axis="0 0 1"/>
      <geom size="0.05"/>
      <site name="tilted" euler="30 0 20"/>
    </body>
  </worldbody>
</mujoco>)");
  Scene scene;
  scene.add_robot({"r", file.string(), {0.1, 0.2, 0.3}, {1, 0, 0, 0}, false});
  scene.attach_gripper({"r", "franka_hand", "tilted", "hand"});
  const Robot robot = scene.compile();
  const mjModel& m = robot.model();
  DataPtr d = robot.make_data();
  d->qpos[m.jnt_qposadr[robot.joint("r/j")]] = 0.7;
  mj_kinematics(&m, d.get());
  const int mount = robot.body("r/hand");
  const int site = robot.site("r/tilted");
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(d->xpos[3 * mount + k], d->site_xpos[3 * site + k], 1e-12);
  for (int k = 0; k < 9; ++k)
    EXPECT_NEAR(d->xmat[9 * mount + k], d->site_xmat[9 * site + k], 1e-12);
  EXPECT_NEAR(d->site_xpos[3 * site + 2], 0.4, 1e-12);
}

TEST(AttachedPart, TwoCopiesOfOnePartKeepTheirOwnClassesAndMeshes) {
  // a mesh named after its file, found through the part's own meshdir
  write_part("meshy/meshes/tetra.obj",
             "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0\nv 0 0 0.04\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const auto file = write_part("meshy/meshy.xml", R"(
<mujoco model="meshy">
  <compiler meshdir="meshes" autolimits="true"/>
  <default>
    <default class="heavy"><geom density="5000" rgba="0 0 1 1"/></default>
  </default>
  <asset><mesh file="tetra.obj"/></asset>
  <worldbody>
    <body name="b" childclass="heavy">
      <joint name="j" axis="0 0 1"/>
      <geom name="g" type="mesh" mesh="tetra"/>
    </body>
  </worldbody>
  <actuator><motor name="m" joint="j"/></actuator>
</mujoco>)");
  Scene scene;
  scene.add_robot({"a", file.string(), {}, {1, 0, 0, 0}, false});
  scene.add_robot({"b", file.string(), {1, 0, 0}, {1, 0, 0, 0}, false});
  scene.add_robot({"c", "arm6", {0, 1, 0}, {1, 0, 0, 0}, false});
  scene.add_robot({"d", "arm6", {0, -1, 0}, {1, 0, 0, 0}, false});
  const Robot robot = scene.compile();
  EXPECT_EQ(robot.nq(), 1 + 1 + 8 + 8);
  EXPECT_EQ(robot.model().nmesh, 2);
  EXPECT_GE(try_find_object(robot.model(), mjOBJ_MESH, "a/tetra"), 0);
  EXPECT_GE(try_find_object(robot.model(), mjOBJ_MESH, "b/tetra"), 0);
  const Robot alone = Robot::from_file(file);
  EXPECT_NEAR(robot.model().body_mass[robot.body("b/b")], alone.model().body_mass[alone.body("b")],
              1e-12);
  EXPECT_EQ(robot.model().actuator_trnid[2 * robot.actuator("b/m")], robot.joint("b/j"));
  EXPECT_TRUE(scene.has("default", "a/heavy"));
  EXPECT_TRUE(scene.has("default", "d/arm6_finger"));
}

TEST(AttachedPart, ItsOptionsAreTakenAndConflictsRefusedWithMuJoCosWord) {
  // no compiler element (degrees, autolimits), implicitfast, a position actuator with kv
  const auto file = write_part("v4/v4.xml", R"(
<mujoco model="v4">
  <option integrator="implicitfast"/>
  <worldbody>
    <body name="b"><joint name="j" axis="0 0 1" range="-1 1"/><geom size="0.05"/></body>
  </worldbody>
  <actuator><position name="p" joint="j" kp="50" kv="2"/></actuator>
</mujoco>)");
  Scene scene;
  scene.add_robot({"v4", file.string(), {}, {1, 0, 0, 0}, false});
  // the scene had no integrator of its own: it takes the part's, and says so
  ASSERT_FALSE(scene.warnings().empty());
  EXPECT_NE(scene.warnings().front().find("robot 'v4'"), std::string::npos);
  EXPECT_NE(scene.warnings().front().find("integrator"), std::string::npos)
      << scene.warnings().front();
  const Robot robot = scene.compile();
  // and the compiled robot's load report holds it (issue 29: it was only printed)
  ASSERT_FALSE(robot.load_warnings().empty());
  EXPECT_EQ(robot.load_warnings().front(), scene.warnings().front());
  const mjModel& m = robot.model();
  EXPECT_EQ(m.opt.integrator, mjINT_IMPLICITFAST);
  const int j = robot.joint("v4/j");
  EXPECT_TRUE(m.jnt_limited[j]);
  // degrees, as MuJoCo reads the file alone
  const Robot alone = Robot::from_file(file);
  EXPECT_NEAR(m.jnt_range[2 * j + 1], alone.model().jnt_range[1], 1e-15);
  EXPECT_NEAR(m.jnt_range[2 * j + 1], std::numbers::pi / 180.0, 1e-15);
  EXPECT_EQ(m.actuator_biasprm[robot.actuator("v4/p") * mjNBIAS + 2], -2.0);

  // a second part that wants another integrator is refused, naming it; the scene is unchanged
  const auto other = write_part("v4/rk4.xml", R"(
<mujoco model="rk4">
  <option integrator="RK4"/>
  <worldbody><body name="b"><joint name="j"/><geom size="0.05"/></body></worldbody>
</mujoco>)");
  const std::string message = test::error_of([&] {
    scene.add_robot({"rk4", other.string(), {1, 0, 0}, {1, 0, 0, 0}, false});
  });
  EXPECT_NE(message.find("robot 'rk4'"), std::string::npos) << message;
  EXPECT_NE(message.find("integrator"), std::string::npos) << message;
  EXPECT_FALSE(scene.has("body", "rk4"));
  EXPECT_FALSE(scene.has("joint", "rk4/j"));
  EXPECT_EQ(scene.compile().nq(), 1);

  // what the scene sets itself wins over its parts, before or after they come
  Scene own;
  own.set_option("integrator", "RK4");
  own.add_robot({"v4", file.string(), {}, {1, 0, 0, 0}, false});
  own.add_robot({"rk4", other.string(), {1, 0, 0}, {1, 0, 0, 0}, false});
  EXPECT_EQ(own.compile().model().opt.integrator, mjINT_RK4);
}

}  // namespace
}  // namespace mjarm
