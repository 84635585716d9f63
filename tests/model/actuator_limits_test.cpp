#include "mjarm/model/actuator_limits.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/model/robot.hpp"

namespace mjarm {
namespace {

TEST(ActuatorLimits, TorqueRangeOfTheBundledMotors) {
  const Robot iiwa = Robot::bundled("iiwa14_torque");
  const Chain chain(iiwa, "attachment_site");
  const double expected[7] = {320, 320, 176, 176, 110, 40, 40};  // KUKA datasheet
  for (int i = 0; i < 7; ++i) {
    const TorqueRange r = joint_torque_range(chain, i);
    EXPECT_EQ(r.lower, -expected[i]);
    EXPECT_EQ(r.upper, expected[i]);
    EXPECT_EQ(joint_torque_limit(chain, i), expected[i]);
  }
}

TEST(ActuatorLimits, GainGearForceRangeAndMissingActuators) {
  // joint a: motor gain 2, gear −3, ctrl [−1, 4] → torque [−24, 6]; forcerange [−5, 5] → [−15, 15]
  // → intersection [−15, 6]. joint b: no actuator. joint c: a position servo, force-limited.
  const Robot robot = Robot::from_string(R"(
    <mujoco>
      <worldbody>
        <body name="l1">
          <joint name="a" type="hinge" axis="0 0 1"/>
          <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" mass="1"/>
          <body name="l2" pos="0.2 0 0">
            <joint name="b" type="hinge" axis="0 0 1"/>
            <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" mass="1"/>
            <body name="l3" pos="0.2 0 0">
              <joint name="c" type="hinge" axis="0 0 1"/>
              <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" mass="1"/>
              <site name="tip" pos="0.2 0 0"/>
            </body>
          </body>
        </body>
      </worldbody>
      <actuator>
        <general joint="a" gear="-3" gainprm="2" ctrllimited="true" ctrlrange="-1 4"
                 forcelimited="true" forcerange="-5 5"/>
        <position joint="c" kp="50" ctrllimited="true" ctrlrange="-1 1" forcelimited="true"
                  forcerange="-7 9"/>
      </actuator>
    </mujoco>)");
  const Chain chain(robot, "tip");
  const TorqueRange a = joint_torque_range(chain, 0);
  EXPECT_DOUBLE_EQ(a.lower, -15.0);
  EXPECT_DOUBLE_EQ(a.upper, 6.0);
  const TorqueRange b = joint_torque_range(chain, 1);
  EXPECT_TRUE(std::isinf(b.lower) && b.lower < 0.0);
  EXPECT_TRUE(std::isinf(b.upper) && b.upper > 0.0);
  EXPECT_TRUE(std::isinf(joint_torque_limit(chain, 1)));
  // the servo's ctrlrange is a position: only its forcerange bounds the torque
  const TorqueRange c = joint_torque_range(chain, 2);
  EXPECT_DOUBLE_EQ(c.lower, -7.0);
  EXPECT_DOUBLE_EQ(c.upper, 9.0);
}

}  // namespace
}  // namespace mjarm
