#include "mjarm/planning/configuration_check.hpp"

#include <gtest/gtest.h>

#include "ik/malloc_counter.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/error.hpp"
#include "planning/planning_support.hpp"

namespace mjarm {
namespace {

using planning_test::home_q;
using planning_test::panda_with_box;

struct PandaChecks : ::testing::Test {
  Robot robot = Robot::bundled("panda_torque");
  Chain chain{robot, "attachment_site"};
  JointLimits limits = joint_limits_from_model(chain, home_q(robot));
};

TEST_F(PandaChecks, HomePassesAndReportsItsFigures) {
  ConfigurationChecker checker(chain, limits);
  const ConfigurationCheck& c = checker.check(home_q(robot));
  EXPECT_TRUE(c.ok()) << checker.describe(c);
  EXPECT_NEAR(c.sigma_min, 0.2244, 1e-3);
  EXPECT_GT(c.torque_ratio, 0.0);  // gravity
  EXPECT_LT(c.torque_ratio, 1.0);
  EXPECT_EQ(checker.describe(c), "ok");
}

TEST_F(PandaChecks, AJointOutsideItsRangeIsNamed) {
  ConfigurationChecker checker(chain, limits);
  Eigen::VectorXd q = home_q(robot);
  q[3] = 0.1;  // joint4's range is [-3.0718, -0.0698]
  const ConfigurationCheck& c = checker.check(q);
  EXPECT_EQ(c.failure, CheckFailure::joint_limits);
  EXPECT_EQ(c.limit_joint, 3);
  EXPECT_NE(checker.describe(c).find("joint 'joint4'"), std::string::npos);
}

TEST_F(PandaChecks, TheStretchedArmIsFlaggedNearSingular) {
  CheckOptions options;
  options.min_singular_value = 0.05;
  ConfigurationChecker checker(chain, limits, options);
  Eigen::VectorXd up(7);
  up << 0, 0, 0, -0.0698, 0, 1.571, 0;  // elbow at its straightest, pointing up
  const ConfigurationCheck& c = checker.check(up);
  EXPECT_EQ(c.failure, CheckFailure::singular);
  EXPECT_LT(c.sigma_min, 0.05);
  EXPECT_NE(checker.describe(c).find("singular value"), std::string::npos);
  EXPECT_TRUE(checker.check(home_q(robot)).ok());
}

TEST_F(PandaChecks, TorqueIsInverseDynamicsAgainstTheLimits) {
  ConfigurationChecker checker(chain, limits);
  const Eigen::VectorXd q = home_q(robot);
  const Eigen::VectorXd qd = Eigen::VectorXd::Constant(7, 0.3);
  Eigen::VectorXd qdd = Eigen::VectorXd::Zero(7);
  qdd[5] = 400.0;  // joint6: far beyond 12 N·m
  const ConfigurationCheck c = checker.check(q, qd, qdd);
  EXPECT_EQ(c.failure, CheckFailure::torque);
  EXPECT_EQ(c.torque_joint, 5);
  // the same τ from an independent mj_forward + ChainDynamics
  DataPtr data = robot.make_data();
  chain.scatter(q, data->qpos);
  for (int i = 0; i < 7; ++i) data->qvel[chain.dof_address(i)] = qd[i];
  mj_forward(&robot.model(), data.get());
  ChainDynamics dynamics(chain);
  Eigen::VectorXd tau(7);
  dynamics.inverse_dynamics(*data, qdd, tau);
  EXPECT_NEAR(c.torque_ratio, std::abs(tau[5]) / 12.0, 1e-9);
  EXPECT_NE(checker.describe(c).find("joint 'joint6' needs"), std::string::npos);
}

TEST_F(PandaChecks, CheckingAllocatesNothing) {
  ConfigurationChecker checker(chain, limits);
  const Eigen::VectorXd q = home_q(robot);
  const Eigen::VectorXd qd = Eigen::VectorXd::Constant(7, 0.2);
  const Eigen::VectorXd qdd = Eigen::VectorXd::Constant(7, 1.0);
  checker.check(q, qd, qdd);  // warm
  const std::uint64_t before = test::malloc_calls();
  int failures = 0;
  for (int j = 0; j < 20; ++j) failures += !checker.check(q, qd, qdd).ok();
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_EQ(failures, 0);
}

TEST_F(PandaChecks, NanIsInvalidNotACrash) {
  ConfigurationChecker checker(chain, limits);
  Eigen::VectorXd q = home_q(robot);
  q[2] = std::nan("");
  EXPECT_EQ(checker.check(q).failure, CheckFailure::invalid);
}

TEST(ConfigurationCheck, ContactWithAnObstacleIsACollisionNamingTheGeoms) {
  // the box around the home tool position (0.307, 0, 0.590)
  const Robot robot = panda_with_box({0.31, 0.0, 0.56}, 0.05);
  const Chain chain(robot, "attachment_site");
  ConfigurationChecker checker(chain, joint_limits_from_model(chain, home_q(robot)));
  const ConfigurationCheck& c = checker.check(home_q(robot));
  EXPECT_EQ(c.failure, CheckFailure::collision);
  EXPECT_LT(c.distance, 0.0);
  const std::string text = checker.describe(c);
  EXPECT_NE(text.find("touches geom 'obstacle'"), std::string::npos) << text;
  // the base on the floor is not a collision: at home in the bundled scene nothing counts
  const Robot plain = Robot::bundled("panda_torque");
  const Chain plain_chain(plain, "attachment_site");
  ConfigurationChecker plain_checker(plain_chain,
                                     joint_limits_from_model(plain_chain, home_q(plain)));
  EXPECT_TRUE(plain_checker.check(home_q(plain)).ok());
}

TEST(ConfigurationCheck, NeverTouchesACallersData) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  DataPtr mine = robot.make_data();
  const double before = mine->qpos[0];
  ConfigurationChecker checker(chain, joint_limits_from_model(chain, home_q(robot)));
  Eigen::VectorXd q = home_q(robot);
  q[0] = 1.0;
  checker.check(q);
  EXPECT_EQ(mine->qpos[0], before);
}

TEST(ConfigurationCheck, BadOptionsThrow) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  const JointLimits limits = joint_limits_from_model(chain, home_q(robot));
  CheckOptions options;
  options.min_singular_value = -1.0;
  EXPECT_THROW(ConfigurationChecker(chain, limits, options), Error);
  JointLimits wrong = limits;
  wrong.max_torque.resize(3);
  EXPECT_THROW(ConfigurationChecker(chain, wrong), Error);
}

}  // namespace
}  // namespace mjarm
