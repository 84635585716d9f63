#include "mjarm/control/gripper_pd.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "control/joint_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/control/gravity_compensation.hpp"
#include "mjarm/error.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

struct Hand {
  Robot robot = Robot::bundled("panda_hand_torque");
  std::vector<std::string> arm_joints{"joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7"};
  Chain arm{robot, arm_joints, "attachment_site"};
  Chain fingers{robot, {"finger_left", "finger_right"}, "tcp"};
};

TEST(GripperPdController, OpenAndCloseFollowTheFraction) {
  Hand hand;
  EXPECT_EQ(hand.fingers.upper(), Eigen::Vector2d(0.04, 0.04));
  DataPtr d = hand.robot.make_data();
  test::go_home(hand.robot, *d);
  GravityHoldController hold(hand.arm);  // keeps the arm up while the fingers move
  GripperPdController gripper(hand.fingers);
  EXPECT_EQ(gripper.open(), hand.fingers.upper());
  EXPECT_EQ(gripper.closed(), hand.fingers.lower());
  for (double fraction : {0.0, 0.5, 1.0, 0.25}) {
    SCOPED_TRACE(fraction);
    test::run_loop(hand.robot, *d, {&hold, &gripper}, 500, [&](double, Reference& r) { r.gripper = fraction; });
    const Eigen::VectorXd expected = Eigen::Vector2d::Constant(0.04 * (1.0 - fraction));
    // at rest the PD's error holds the (small) finger weight: within a fraction of a millimetre
    EXPECT_LT((hand.fingers.gather(d->qpos) - expected).cwiseAbs().maxCoeff(), 2e-4);
    EXPECT_DOUBLE_EQ(gripper.internal_values()[0], fraction);
  }
}

TEST(GripperPdController, ClampsTheForceAndKeepsTheFractionOnNan) {
  Hand hand;
  DataPtr d = hand.robot.make_data();
  test::go_home(hand.robot, *d);
  GripperPdOptions options;
  options.max_force = 3.0;
  options.gravity_compensation = false;
  GripperPdController gripper(hand.fingers, options);
  Reference ref;
  ref.gripper = 1.0;  // fingers open at home: full stroke to close, Kp·0.04 = 40 N > 3 N
  JointCommand command{CommandKind::position, Eigen::VectorXd::Zero(2)};
  const Eigen::VectorXd q = hand.fingers.gather(d->qpos);
  gripper.compute(*d, ref, command);
  EXPECT_EQ(command.kind, CommandKind::torque);
  for (int i = 0; i < 2; ++i) {
    const double unclamped = 1000.0 * (0.0 - q[i]);  // finger speed is zero at home
    EXPECT_DOUBLE_EQ(command.value[i], std::clamp(unclamped, -3.0, 3.0));
  }
  if (q.minCoeff() > 0.003) {
    EXPECT_EQ(gripper.internal_values()[2], 2.0);
  }
  ref.gripper = NAN;
  gripper.compute(*d, ref, command);
  EXPECT_EQ(gripper.internal_values()[0], 1.0);
  ref.gripper = 7.0;  // out of range: clamped
  gripper.compute(*d, ref, command);
  EXPECT_EQ(gripper.internal_values()[0], 1.0);
  gripper.reset();
  ref.gripper = NAN;
  gripper.compute(*d, ref, command);
  EXPECT_EQ(gripper.internal_values()[0], 0.0);
}

TEST(GripperPdController, ExplicitStrokeAndValidation) {
  Hand hand;
  GripperPdOptions options;
  options.open = Eigen::Vector2d(0.03, 0.035);
  options.closed = Eigen::Vector2d(0.01, 0.005);
  GripperPdController gripper(hand.fingers, options);
  EXPECT_EQ(gripper.open(), options.open);
  EXPECT_EQ(gripper.closed(), options.closed);

  GripperPdOptions bad = options;
  bad.max_force = 0.0;
  EXPECT_THROW(GripperPdController(hand.fingers, bad), Error);
  bad = options;
  bad.open = Eigen::Vector3d::Zero();
  try {
    GripperPdController g(hand.fingers, bad);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("open"), std::string::npos) << e.what();
  }
  bad = options;
  bad.gains.kp = Eigen::Vector3d::Ones();
  EXPECT_THROW(GripperPdController(hand.fingers, bad), Error);
  // a hinge without range needs an explicit stroke
  const Robot tricky = Robot::from_string(test::kTrickyArm);
  const Chain unlimited(tricky, {"off_path"}, "tool");
  EXPECT_THROW(GripperPdController{unlimited}, Error);
  GripperPdOptions hinge;
  hinge.open = Eigen::VectorXd::Constant(1, 0.5);
  hinge.closed = Eigen::VectorXd::Constant(1, -0.2);
  EXPECT_NO_THROW(GripperPdController(unlimited, hinge));
}

TEST(GripperPdController, ComputeAllocatesNothing) {
  Hand hand;
  DataPtr d = hand.robot.make_data();
  test::go_home(hand.robot, *d);
  GripperPdController gripper(hand.fingers);
  Reference ref;
  ref.gripper = 0.7;
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(2)};
  const std::uint64_t calls = test::malloc_calls();
  for (int k = 0; k < 5; ++k) gripper.compute(*d, ref, command);
  EXPECT_EQ(test::malloc_calls() - calls, 0u);
  EXPECT_EQ(gripper.name(), "gripper-pd");
}

}  // namespace
}  // namespace mjarm
