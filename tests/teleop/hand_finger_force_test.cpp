// HandFingerForce: the bimanual session's adapter of FingerForceController — each hand its own
// closing command in the same tick, "the object" everything outside the gripper, bad options.
#include "mjarm/teleop/hand_finger_force.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mjarm/model/chain.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

TEST(HandFingerForce, EachHandTakesItsOwnCommandInTheSameTick) {
  const Robot robot = Robot::bundled("dual_arm_box_torque");
  const Chain left(robot, {"left_finger_left", "left_finger_right"}, "left_tcp");
  const Chain right(robot, {"right_finger_left", "right_finger_right"}, "right_tcp");
  HandFingerForce l(left), r(right);
  l.set_command(0.0);  // open: the PD pushes the fingers towards their upper limit
  r.set_command(1.0);  // closed: towards the lower limit
  const DataPtr d = robot.make_data();
  for (const Chain* c : {&left, &right})
    for (int i = 0; i < 2; ++i) d->qpos[c->qpos_address(i)] = 0.02;  // fingers half open, at rest
  mj_forward(&robot.model(), d.get());
  Reference shared;
  shared.gripper = 0.5;  // ignored: every hand reads its own command
  JointCommand cl, cr;
  cl.value.setZero(2);
  cr.value.setZero(2);
  l.compute(*d, shared, cl);
  r.compute(*d, shared, cr);
  EXPECT_DOUBLE_EQ(l.command(), 0.0);
  EXPECT_DOUBLE_EQ(r.command(), 1.0);
  for (int i = 0; i < 2; ++i) {
    // f = K_free·(q_d − q) at rest, 0.02 m from either end
    EXPECT_NEAR(r.controller().force(i), 1000.0 * (right.lower()[i] - 0.02), 1e-9);
    EXPECT_NEAR(l.controller().force(i), 1000.0 * (left.upper()[i] - 0.02), 1e-9);
    EXPECT_LT(r.controller().force(i), -10.0);
    EXPECT_GT(l.controller().force(i), 10.0);
  }
  // NaN keeps the command, values are clamped
  r.set_command(std::nan(""));
  EXPECT_DOUBLE_EQ(r.command(), 1.0);
  r.set_command(7.0);
  EXPECT_DOUBLE_EQ(r.command(), 1.0);
  // the object is every geom outside the gripper: the bar, the table, the other arm
  const FingerForceOptions& o = l.controller().options();
  const int bar = mj_name2id(&robot.model(), mjOBJ_BODY, "bar");
  ASSERT_GE(bar, 0);
  bool bar_listed = false;
  for (const int g : o.object_geoms) {
    bar_listed = bar_listed || robot.model().geom_bodyid[g] == bar;
    for (const auto& finger : o.finger_geoms)
      EXPECT_EQ(std::count(finger.begin(), finger.end(), g), 0) << "a finger geom is an object";
  }
  EXPECT_TRUE(bar_listed);
  ASSERT_EQ(o.finger_geoms.size(), 2u);
  EXPECT_FALSE(o.finger_geoms[0].empty());
  EXPECT_FALSE(o.finger_geoms[1].empty());
}

TEST(HandFingerForce, RefusesOptionsItFillsItselfOrCannotUse) {
  const Robot robot = Robot::bundled("dual_arm_box_torque");
  const Chain left(robot, {"left_finger_left", "left_finger_right"}, "left_tcp");
  FingerForceOptions position = hand_finger_force_defaults();
  position.command = CommandKind::position;
  EXPECT_NE(test::error_of([&] { HandFingerForce f(left, position); }).find("must be torque"),
            std::string::npos);
  FingerForceOptions geoms = hand_finger_force_defaults();
  geoms.object_geoms = {0};
  EXPECT_NE(test::error_of([&] { HandFingerForce f(left, geoms); }).find("leave"),
            std::string::npos);
  FingerForceOptions weak = hand_finger_force_defaults();
  weak.max_force = 1.0;  // below the grasp force: FingerForceController's own check
  EXPECT_NE(test::error_of([&] { HandFingerForce f(left, weak); }).find("max_force"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
