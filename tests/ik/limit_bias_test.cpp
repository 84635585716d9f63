#include "mjarm/ik/limit_bias.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

class LimitBiasTest : public ::testing::Test {
 protected:
  Robot robot_ = Robot::from_string(test::kTrickyArm);
  // j1 in [-3, 3], the unlimited off-path hinge, j3 (slide) in [-0.1, 0.2]
  Chain chain_{robot_, {"j1", "off_path", "j3"}, "tool"};
};

TEST_F(LimitBiasTest, CentrePullActsOnLimitedJointsOnly) {
  const LimitBias bias{0.05, 0.0, 0.15};
  const Eigen::Vector3d q(1.0, 2.0, 0.0);
  Eigen::VectorXd step = Eigen::VectorXd::Zero(3);
  add_limit_bias(chain_, bias, q, step);
  EXPECT_DOUBLE_EQ(step[0], 0.05 * (0.0 - 1.0));
  EXPECT_DOUBLE_EQ(step[1], 0.0);
  EXPECT_DOUBLE_EQ(step[2], 0.05 * (0.05 - 0.0));
}

TEST_F(LimitBiasTest, RepulsionGrowsQuadraticallyInTheOuterZone) {
  const LimitBias bias{0.0, 0.2, 0.15};
  const double zone = 0.15 * 6.0;  // j1's range is 6 rad
  const auto push = [&](double q1) {
    Eigen::VectorXd step = Eigen::VectorXd::Zero(3);
    add_limit_bias(chain_, bias, Eigen::Vector3d(q1, 0.0, 0.05), step);
    return step[0];
  };
  EXPECT_EQ(push(0.0), 0.0);
  EXPECT_EQ(push(3.0 - zone - 1e-9), 0.0);     // just outside the zone
  EXPECT_NEAR(push(3.0), -0.2 * zone, 1e-15);  // full push at the bound, inwards
  EXPECT_NEAR(push(3.0 - 0.5 * zone), -0.2 * zone * 0.25,
              1e-15);  // quadratic: half depth, quarter push
  EXPECT_NEAR(push(-3.0), 0.2 * zone, 1e-15);
  EXPECT_NEAR(push(-3.0 + 0.75 * zone), 0.2 * zone / 16.0, 1e-15);  // a quarter deep
}

TEST_F(LimitBiasTest, SaturationPinsJointsOnTheirBounds) {
  const Eigen::Vector3d q(2.9, 0.0, 0.1);
  Eigen::VectorXd locked = Eigen::VectorXd::Zero(3), dq_locked = Eigen::VectorXd::Zero(3);
  // j1 would overshoot its upper bound by 0.2, the unlimited joint never saturates, j3 stays inside
  EXPECT_EQ(saturate_step(chain_, q, Eigen::Vector3d(0.3, 100.0, 0.05), locked, dq_locked), 1);
  EXPECT_EQ(locked, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_NEAR(dq_locked[0], 0.1, 1e-15);
  // a second pass only adds new joints
  EXPECT_EQ(saturate_step(chain_, q, Eigen::Vector3d(0.5, 0.0, -0.3), locked, dq_locked), 1);
  EXPECT_EQ(locked, Eigen::Vector3d(1.0, 0.0, 1.0));
  EXPECT_NEAR(dq_locked[0], 0.1, 1e-15);
  EXPECT_NEAR(dq_locked[2], -0.2, 1e-15);
}

TEST_F(LimitBiasTest, ClampAndValidation) {
  Eigen::VectorXd q = Eigen::Vector3d(5.0, -50.0, -1.0);
  clamp_to_limits(chain_, q);
  EXPECT_EQ(q, Eigen::Vector3d(3.0, -50.0, -0.1));
  EXPECT_THROW(check(LimitBias{-0.1, 0.0, 0.15}), Error);
  EXPECT_THROW(check(LimitBias{0.0, std::numeric_limits<double>::infinity(), 0.15}), Error);
  EXPECT_THROW(check(LimitBias{0.0, 0.0, 0.6}), Error);
  EXPECT_NO_THROW(check(LimitBias{0.05, 0.2, 0.15}));
}

}  // namespace
}  // namespace mjarm
