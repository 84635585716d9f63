#include "mjarm/model/named_data.hpp"

#include <gtest/gtest.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {
namespace {

// one of each joint type, a mocap body, a site, a sensor, a stateful and a stateless actuator
constexpr const char* kMixed = R"(
<mujoco model="mixed">
  <worldbody>
    <body name="ball_body" pos="0 0 1">
      <joint name="ball" type="ball"/>
      <geom name="ball_geom" type="sphere" size="0.05" mass="1"/>
      <body name="arm" pos="0 0 -0.3">
        <joint name="hinge" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" mass="0.5"/>
        <site name="tip" pos="0.2 0 0"/>
      </body>
    </body>
    <body name="puck" pos="1 0 0.5">
      <freejoint name="free"/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.2"/>
    </body>
    <body name="target" mocap="true" pos="0.5 0.5 0.5"/>
  </worldbody>
  <actuator>
    <motor name="motor" joint="hinge"/>
    <general name="filtered" joint="hinge" dyntype="filter" dynprm="0.1"/>
  </actuator>
  <sensor>
    <framepos name="tip_pos" objtype="site" objname="tip"/>
    <jointpos name="hinge_pos" joint="hinge"/>
  </sensor>
</mujoco>)";

struct NamedDataTest : ::testing::Test {
  Robot robot = Robot::from_string(kMixed);
  DataPtr data = robot.make_data();
  NamedData named{robot.model(), *data};
};

TEST_F(NamedDataTest, EachJointCoversItsOwnNumberOfValues) {
  EXPECT_EQ(named("qpos", "ball").size(), 4);
  EXPECT_EQ(named("qvel", "ball").size(), 3);
  EXPECT_EQ(named("qpos", "hinge").size(), 1);
  EXPECT_EQ(named("qpos", "free").size(), 7);
  EXPECT_EQ(named("qvel", "free").size(), 6);
  // the views sit where the model's addresses say
  const mjModel& m = robot.model();
  const int free = mj_name2id(&m, mjOBJ_JOINT, "free");
  EXPECT_EQ(named("qpos", "free").data(), data->qpos + m.jnt_qposadr[free]);
  EXPECT_EQ(named("qvel", "free").data(), data->qvel + m.jnt_dofadr[free]);
  // the free joint starts at the body's position
  EXPECT_DOUBLE_EQ(named("qpos", "free")[0], 1.0);
  EXPECT_DOUBLE_EQ(named("qpos", "free")[2], 0.5);
}

TEST_F(NamedDataTest, WritesGoIntoTheDataAndForwardSeesThem) {
  named("qpos", "hinge")[0] = 0.7;
  named("ctrl", "motor")[0] = 1.5;
  mj_forward(&robot.model(), data.get());
  const mjModel& m = robot.model();
  EXPECT_DOUBLE_EQ(data->qpos[m.jnt_qposadr[mj_name2id(&m, mjOBJ_JOINT, "hinge")]], 0.7);
  EXPECT_DOUBLE_EQ(data->ctrl[0], 1.5);
  // the site, the sensor and the body frames read what mj_forward computed
  const Eigen::Vector3d tip = named("site_xpos", "tip");
  EXPECT_TRUE(
      tip.isApprox(Eigen::Map<const Eigen::Vector3d>(named("sensordata", "tip_pos").data())));
  EXPECT_DOUBLE_EQ(named("sensordata", "hinge_pos")[0], 0.7);
  EXPECT_EQ(named("xmat", "arm").size(), 9);
  EXPECT_EQ(named("site_xmat", "tip").size(), 9);
  EXPECT_EQ(named("xquat", "arm").size(), 4);
  EXPECT_EQ(named("cvel", "arm").size(), 6);
  EXPECT_EQ(named("xfrc_applied", "arm").size(), 6);
}

TEST_F(NamedDataTest, ActuatorsWithoutActivationHaveNone) {
  EXPECT_EQ(named("act", "motor").size(), 0);
  EXPECT_EQ(named("act", "filtered").size(), 1);
  EXPECT_EQ(named("ctrl", "filtered").data(), data->ctrl + 1);
}

TEST_F(NamedDataTest, MocapPosesByBodyName) {
  EXPECT_EQ(named("mocap_pos", "target").data(), data->mocap_pos);
  EXPECT_DOUBLE_EQ(named("mocap_pos", "target")[1], 0.5);
  EXPECT_EQ(named("mocap_quat", "target").size(), 4);
  try {
    named("mocap_pos", "puck");
    FAIL() << "a body that is not a mocap body";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'puck' is not a mocap body"), std::string::npos)
        << e.what();
  }
}

TEST_F(NamedDataTest, UnknownNamesGetTheClosest) {
  try {
    named("qpso", "hinge");
    FAIL() << "an unknown quantity";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("closest: qpos"), std::string::npos) << e.what();
  }
  try {
    named("qpos", "hinj");
    FAIL() << "an unknown joint";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'hinj'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hinge"), std::string::npos) << e.what();
  }
  EXPECT_THROW(named("qpos", 3), Error);  // three joints: 0, 1, 2
  EXPECT_THROW(named("qpos", -1), Error);
}

TEST_F(NamedDataTest, EveryQuantityTilesItsArray) {
  // the elements' slices cover each array once, in order, without overlap
  const mjModel& m = robot.model();
  for (const NamedQuantity& q : named_quantities()) {
    if (q.name.starts_with("mocap_")) continue;  // indexed by bodies, only some of them mocap
    const std::span<mjtNum> array = named_array(m, *data, q);
    int next = 0;
    for (int id = 0; id < named_count(m, q); ++id) {
      const NamedSlice slice = named_slice(m, q, id);
      if (slice.size == 0) continue;
      EXPECT_EQ(slice.offset, next) << q.name << " element " << id;
      next = slice.offset + slice.size;
    }
    EXPECT_EQ(static_cast<std::size_t>(next), array.size()) << q.name;
  }
}

}  // namespace
}  // namespace mjarm
