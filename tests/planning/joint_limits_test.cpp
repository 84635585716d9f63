#include "mjarm/planning/joint_limits.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/error.hpp"
#include "planning/planning_support.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using planning_test::home_q;
using test::error_of;

TEST(JointLimits, TorquesFromMotorCtrlRangesAndForceRanges) {
  const Robot torque = Robot::bundled("panda_torque");  // motors: ctrlrange is the torque
  const Robot servo = Robot::bundled("panda");          // position servos with forcerange
  for (const Robot* robot : {&torque, &servo}) {
    const Chain chain(*robot, "attachment_site");
    const JointLimits limits = joint_limits_from_model(chain, home_q(*robot));
    for (int i = 0; i < 7; ++i) EXPECT_EQ(limits.max_torque[i], i < 4 ? 87.0 : 12.0) << i;
    EXPECT_NO_THROW(check(limits, 7));
  }
}

TEST(JointLimits, AccelerationIsTheTorqueFractionOverTheInertia) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  ModelLimitOptions options;
  options.torque_fraction = 0.25;
  options.velocity = 0.7;
  const JointLimits limits = joint_limits_from_model(chain, home_q(robot), options);
  DataPtr data = robot.make_data();
  chain.scatter(home_q(robot), data->qpos);
  mj_forward(&robot.model(), data.get());
  ChainDynamics dynamics(chain);
  dynamics.update(*data);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(limits.max_acceleration[i],
                0.25 * limits.max_torque[i] / dynamics.mass_matrix()(i, i), 1e-12);
    EXPECT_EQ(limits.max_velocity[i], 0.7);
  }
}

TEST(JointLimits, WithoutActuatorsTheTorqueIsUncheckedAndTheAccelerationTheDefault) {
  const Robot robot = Robot::from_string(R"(<mujoco><compiler autolimits="true"/><worldbody><body>
      <joint name="a" type="hinge" axis="0 0 1" range="-1 1"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/><site name="tip" pos="0.3 0 0"/>
    </body></worldbody></mujoco>)");
  const Chain chain(robot, "tip");
  ModelLimitOptions options;
  options.acceleration = 3.0;
  const JointLimits limits = joint_limits_from_model(chain, Eigen::VectorXd::Zero(1), options);
  EXPECT_TRUE(std::isinf(limits.max_torque[0]));
  EXPECT_EQ(limits.max_acceleration[0], 3.0);
}

TEST(JointLimits, BadLimitsAreNamed) {
  JointLimits limits{Eigen::VectorXd::Ones(2), Eigen::VectorXd::Ones(3), Eigen::VectorXd::Ones(3)};
  EXPECT_NE(error_of([&] { check(limits, 3); }).find("max_velocity has 2 entries, expected 3"),
            std::string::npos);
  limits.max_velocity = Eigen::VectorXd::Ones(3);
  limits.max_acceleration[1] = -1.0;
  EXPECT_NE(error_of([&] { check(limits, 3); }).find("max_acceleration of joint 1"),
            std::string::npos);
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  ModelLimitOptions options;
  options.torque_fraction = 0.0;
  EXPECT_THROW(joint_limits_from_model(chain, home_q(robot), options), Error);
  EXPECT_THROW(joint_limits_from_model(chain, Eigen::VectorXd::Zero(3)), Error);
}

}  // namespace
}  // namespace mjarm
