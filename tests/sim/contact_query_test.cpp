#include "mjarm/sim/contact_query.hpp"

#include <gtest/gtest.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/contacts.hpp"
#include "mjarm/sim/simulation.hpp"
#include "sim/sim_test_support.hpp"

namespace mjarm {
namespace {

// a 1 kg box resting on the floor (it starts 1 mm above and settles)
constexpr const char* kBoxOnFloor = R"(
<mujoco model="box">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="box" pos="0 0 0.051">
      <freejoint name="box_free"/>
      <geom name="box_geom" type="box" size="0.05 0.05 0.05" mass="1"/>
    </body>
  </worldbody>
</mujoco>)";

// two slide fingers squeezing a free box, no gravity; each finger pushes with a motor
constexpr const char* kSqueeze = R"(
<mujoco model="squeeze">
  <option timestep="0.002" gravity="0 0 0"/>
  <worldbody>
    <body name="left" pos="0 0.1 0">
      <joint name="left_slide" type="slide" axis="0 -1 0" damping="20"/>
      <geom name="left_pad" type="box" size="0.02 0.01 0.02" mass="0.1"/>
      <site name="left_site"/>
    </body>
    <body name="right" pos="0 -0.1 0">
      <joint name="right_slide" type="slide" axis="0 1 0" damping="20"/>
      <geom name="right_pad" type="box" size="0.02 0.01 0.02" mass="0.1"/>
    </body>
    <body name="object">
      <freejoint/>
      <geom name="object_geom" type="box" size="0.03 0.03 0.03" mass="0.5"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="left_motor" joint="left_slide"/>
    <motor name="right_motor" joint="right_slide"/>
  </actuator>
</mujoco>)";

TEST(ContactQuery, BoxOnTheFloorWeighsMg) {
  const Robot robot = Robot::from_string(kBoxOnFloor);
  Simulation sim(robot);
  const int watch = sim.watch_contacts(GeomSet::of_bodies(robot, {"world"}, false),
                                       GeomSet::of_bodies(robot, {"box"}));
  EXPECT_EQ(sim.contacts(watch).contacts, 0);  // 1 mm above the floor
  ConstantReferenceSource nothing{Reference{}};
  ASSERT_TRUE(sim.run(nothing, 1.0).ok());
  const ContactSummary& floor_on_box = sim.contacts(watch);
  const double mg = 1.0 * -robot.model().opt.gravity[2];
  EXPECT_GE(floor_on_box.contacts, 1);
  EXPECT_LE(floor_on_box.min_distance, 0.0);
  EXPECT_NEAR(floor_on_box.force_W.z(), mg, 1e-3 * mg);
  EXPECT_NEAR(floor_on_box.force_W.head<2>().norm(), 0.0, 1e-6);
  EXPECT_NEAR(floor_on_box.normal_force, mg, 1e-3 * mg);
  // the same data through kinematics/contacts.hpp
  const std::vector<ContactForce> all = contact_forces(robot.model(), sim.data());
  const Eigen::Vector3d on_box = contact_force_on_body(all, robot.body("box"));
  EXPECT_LT((on_box - floor_on_box.force_W).norm(), 1e-12);
  // the other way round: the box pushes the floor down
  const ContactSummary box_on_floor = contact_between(robot.model(), sim.data(),
                                                     GeomSet::of_geoms(robot, {"box_geom"}),
                                                     GeomSet::of_geoms(robot, {"floor"}));
  EXPECT_LT((box_on_floor.force_W + floor_on_box.force_W).norm(), 1e-12);
}

TEST(ContactQuery, FingerOnObjectNormalForce) {
  const Robot robot = Robot::from_string(kSqueeze);
  Simulation sim(robot);
  const Chain fingers(robot, {"left_slide", "right_slide"}, "left_site");
  test::FixedTorque squeeze(fingers, Eigen::Vector2d(5.0, 5.0));  // 5 N inwards each
  sim.add_controller(squeeze);
  const int left = sim.watch_contacts(GeomSet::of_bodies(robot, {"left"}), GeomSet::of_bodies(robot, {"object"}));
  const int right = sim.watch_contacts(GeomSet::of_bodies(robot, {"right"}), GeomSet::of_bodies(robot, {"object"}));
  ConstantReferenceSource nothing{Reference{}};
  ASSERT_TRUE(sim.run(nothing, 1.5).ok());
  const ContactSummary& l = sim.contacts(left);
  const ContactSummary& r = sim.contacts(right);
  ASSERT_GE(l.contacts, 1);
  ASSERT_GE(r.contacts, 1);
  EXPECT_NEAR(l.normal_force, 5.0, 5e-3);
  EXPECT_NEAR(r.normal_force, 5.0, 5e-3);
  EXPECT_NEAR(l.force_W.y(), -5.0, 5e-3);  // the left finger (at +y) pushes the object towards −y
  EXPECT_NEAR(r.force_W.y(), 5.0, 5e-3);
  EXPECT_EQ(robot.model().geom_bodyid[l.first_geom_a], robot.body("left"));
  EXPECT_EQ(l.first_geom_b, robot.geom("object_geom"));
}

// The robot falls onto its table when its motors go limp.
TEST(ContactQuery, RobotTableContact) {
  const Robot robot = Robot::bundled("arm6_torque");
  Simulation sim(robot);
  sim.reset("home");
  const GeomSet arm = GeomSet::of_bodies(robot, {"link1"});
  const int watch = sim.watch_contacts(arm, GeomSet::of_bodies(robot, {"table"}, false));
  EXPECT_EQ(sim.contacts(watch).contacts, 0);
  ConstantReferenceSource nothing{Reference{}};
  ASSERT_TRUE(sim.run(nothing, 1.5).ok());
  EXPECT_GE(sim.contacts(watch).contacts, 1);
  EXPECT_GT(sim.contacts(watch).normal_force, 0.0);
  EXPECT_LT(sim.contacts(watch).force_W.z(), 0.0);  // the arm pushes the table down
  // "anything but the arm" includes the table
  EXPECT_GE(contact_between(robot.model(), sim.data(), arm, GeomSet{}).contacts,
            sim.contacts(watch).contacts);
}

TEST(ContactQuery, GeomSets) {
  const Robot robot = Robot::bundled("arm6");
  const GeomSet table = GeomSet::of_bodies(robot, {"table"}, false);
  EXPECT_EQ(table.size(), 5);  // top and four legs
  EXPECT_TRUE(table.contains(robot.geom("table_top")));
  EXPECT_FALSE(table.contains(robot.geom("palm")));
  const GeomSet table_and_below = GeomSet::of_bodies(robot, {"table"});
  EXPECT_GT(table_and_below.size(), table.size());  // the arm is mounted below the table body
  EXPECT_TRUE(table_and_below.contains(robot.geom("palm")));
  const GeomSet rest = table.complement(robot);
  EXPECT_EQ(rest.size() + table.size(), robot.model().ngeom);
  GeomSet fingers = GeomSet::of_geoms(robot, {"finger_left"});
  fingers.add(GeomSet::of_geoms(robot, {"finger_right"}));
  EXPECT_EQ(fingers.size(), 2);
  EXPECT_TRUE(GeomSet{}.empty());
  EXPECT_THROW(GeomSet::of_bodies(robot, {"tabel"}), Error);
  EXPECT_THROW(GeomSet::of_geoms(robot, {"palmm"}), Error);
}

}  // namespace
}  // namespace mjarm
