#include "mjarm/ik/posture.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

TEST(Posture, ResolvesToTheCentreOrTheGivenConfiguration) {
  const Robot robot = Robot::from_string(test::kTrickyArm);
  const Chain chain(robot, "tool");
  EXPECT_EQ(resolve_posture(chain, Posture{}), chain.center());
  const Eigen::VectorXd q_pref = Eigen::VectorXd::LinSpaced(5, -0.5, 0.5);
  EXPECT_EQ(resolve_posture(chain, Posture{q_pref, 0.3}), q_pref);
  EXPECT_THROW(resolve_posture(chain, Posture{Eigen::VectorXd::Zero(4), 0.3}), Error);
  Eigen::VectorXd nan = q_pref;
  nan[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(resolve_posture(chain, Posture{nan, 0.3}), Error);
  EXPECT_THROW(resolve_posture(chain, Posture{q_pref, 1.5}), Error);
  EXPECT_THROW(resolve_posture(chain, Posture{q_pref, -0.1}), Error);
}

TEST(Posture, PullIsAFractionOfTheDistance) {
  const Eigen::Vector3d q_pref(1.0, 2.0, 3.0), q(0.0, 2.0, 4.0);
  Eigen::VectorXd step = Eigen::Vector3d(0.1, 0.1, 0.1);
  add_posture_pull(q_pref, 0.5, q, step);
  EXPECT_TRUE(step.isApprox(Eigen::Vector3d(0.6, 0.1, -0.4)));
  add_posture_pull(q_pref, 0.0, q, step);  // disabled
  EXPECT_TRUE(step.isApprox(Eigen::Vector3d(0.6, 0.1, -0.4)));
}

TEST(Posture, SecondaryScaleLimitsTheSecondaryStep) {
  EXPECT_DOUBLE_EQ(secondary_scale(1.0, 0.5, 1.0), 1.0);  // already shorter than the task step
  EXPECT_DOUBLE_EQ(secondary_scale(0.1, 0.5, 1.0), 0.2);  // shortened to the task step
  EXPECT_DOUBLE_EQ(secondary_scale(0.1, 0.5, 2.0), 0.4);
  EXPECT_DOUBLE_EQ(secondary_scale(0.0, 0.5, 1.0), 0.0);  // converged: no secondary motion
  EXPECT_DOUBLE_EQ(secondary_scale(0.0, 0.0, 1.0), 1.0);
}

}  // namespace
}  // namespace mjarm
