#include "mjarm/kinematics/constraint_summary.hpp"

#include <gtest/gtest.h>

#include "mjarm/model/robot.hpp"

namespace mjarm {
namespace {

// a box resting on the floor (four pyramidal contacts), a pendulum held at its joint limit by
// gravity, and a body welded to the world
constexpr const char* kScene = R"(
<mujoco model="constraints">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="3 3 0.1"/>
    <body name="box" pos="0 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1" mass="1"/>
    </body>
    <body name="pendulum" pos="1 0 1">
      <joint name="hinge" axis="0 1 0" range="-0.1 0.1" limited="true"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="1"/>
    </body>
    <body name="held" pos="-1 0 1">
      <freejoint/>
      <geom type="sphere" size="0.05" mass="2" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <equality><weld body1="held"/></equality>
</mujoco>)";

TEST(ConstraintSummary, CountsEachKindAndTheActiveRows) {
  const Robot robot = Robot::from_string(kScene);
  DataPtr d = robot.make_data();
  for (int i = 0; i < 500; ++i) mj_step(&robot.model(), d.get());
  mj_forward(&robot.model(), d.get());
  const ConstraintSummary s = constraint_summary(*d);
  EXPECT_EQ(s.rows, d->nefc);
  EXPECT_EQ(s.equality + s.friction + s.limit + s.contact, s.rows);
  EXPECT_EQ(s.equality, 6);  // a weld: three translations, three rotations
  EXPECT_EQ(s.limit, 1);     // the pendulum rests on its lower limit
  EXPECT_EQ(s.contacts, 4);  // the box's corners
  EXPECT_EQ(s.contact, 16);  // each a pyramid of four edges (condim 3)
  EXPECT_EQ(s.friction, 0);
  EXPECT_GT(s.active, 6);
  EXPECT_LE(s.active, s.rows);
  EXPECT_GT(s.max_force, 1.0);  // the weld holds 2 kg against gravity
  EXPECT_GT(s.solver_iterations, 0);
}

TEST(ConstraintSummary, NoRowsWithoutConstraints) {
  const Robot robot = Robot::bundled("planar2");
  DataPtr d = robot.make_data();
  mj_forward(&robot.model(), d.get());
  const ConstraintSummary s = constraint_summary(*d);
  EXPECT_EQ(s.rows, 0);
  EXPECT_EQ(s.active, 0);
  EXPECT_EQ(s.max_force, 0.0);
}

}  // namespace
}  // namespace mjarm
