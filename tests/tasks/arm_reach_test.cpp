#include "mjarm/tasks/arm_reach.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

TEST(ArmReach, Planar2MatchesTheClosedForm) {
  const Robot robot = Robot::bundled("planar2_torque");
  const ArmReach reach = arm_reach(Chain(robot, "tip"));
  EXPECT_TRUE(reach.p_WS.isApprox(Eigen::Vector3d(0, 0, 1), 1e-15));
  // |p| = √(l1² + l2² + 2·l1·l2·cos q2): largest at q2 = 0, smallest at the limit q2 = −2.5
  const double l1 = 0.4, l2 = 0.35;
  const double closest = std::sqrt(l1 * l1 + l2 * l2 + 2 * l1 * l2 * std::cos(2.5));
  EXPECT_LE(reach.max_distance, l1 + l2 + 1e-12);
  EXPECT_GT(reach.max_distance, l1 + l2 - 1e-3);
  EXPECT_GE(reach.min_distance, closest - 1e-12);
  EXPECT_LT(reach.min_distance, closest + 3e-3);
  EXPECT_EQ(reach.samples, 20000);
}

TEST(ArmReach, PandaShoulderAndReach) {
  const Robot robot = Robot::bundled("panda_torque");
  const ArmReach reach = arm_reach(Chain(robot, "attachment_site"));
  EXPECT_TRUE(reach.p_WS.isApprox(Eigen::Vector3d(0, 0, 0.333), 1e-12));
  // Franka quotes 855 mm of reach; the flange is never farther than the sum of the distances
  // between successive joint anchors (DH: 0.316, 0.0825, √(0.0825² + 0.384²), 0.088, 0.107)
  EXPECT_GT(reach.max_distance, 0.85);
  EXPECT_LT(reach.max_distance, 0.316 + 0.0825 + std::hypot(0.0825, 0.384) + 0.088 + 0.107);
  // the same seed gives the same shell
  const ArmReach again = arm_reach(Chain(robot, "attachment_site"));
  EXPECT_EQ(again.min_distance, reach.min_distance);
  EXPECT_EQ(again.max_distance, reach.max_distance);
  EXPECT_THROW(arm_reach(Chain(robot, "attachment_site"), 0), Error);
}

}  // namespace
}  // namespace mjarm
