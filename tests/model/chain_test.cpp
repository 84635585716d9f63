#include "mjarm/model/chain.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

class ChainTest : public ::testing::Test {
 protected:
  Robot robot_ = Robot::from_string(test::kTrickyArm);
};

TEST_F(ChainTest, PathToASiteSkipsBranchesAndFreeJoints) {
  const Chain chain(robot_, "tool");
  EXPECT_EQ(chain.joint_names(), (std::vector<std::string>{"j1", "j2", "j3", "j4", "j5"}));
  EXPECT_EQ(chain.frame().kind, FrameKind::site);
  EXPECT_EQ(chain.qpos_address(2), robot_.model().jnt_qposadr[robot_.joint("j3")]);
  EXPECT_FALSE(chain.actuator(0).has_value());
}

TEST_F(ChainTest, BodyFrameAndBounds) {
  const Chain chain(robot_, "l2");
  EXPECT_EQ(chain.frame().kind, FrameKind::body);
  EXPECT_EQ(chain.size(), 3);
  EXPECT_DOUBLE_EQ(chain.lower()[2], -0.1);
  EXPECT_DOUBLE_EQ(chain.center()[2], 0.05);
  Eigen::VectorXd q(3);
  q << 5, 0, 0.3;
  EXPECT_FALSE(chain.within_limits(q));
  EXPECT_TRUE(chain.within_limits(chain.clamp(q)));
}

TEST_F(ChainTest, UnlimitedJointsHaveInfiniteBounds) {
  const Chain chain(robot_, {"off_path"}, "branch");
  EXPECT_TRUE(std::isinf(chain.lower()[0]));
  EXPECT_EQ(chain.center()[0], 0.0);
}

TEST_F(ChainTest, GatherAndScatterRoundTrip) {
  const Chain chain(robot_, "tool");
  std::vector<double> qpos(robot_.nq(), 0.0);
  Eigen::VectorXd q(5);
  q << 0.1, 0.2, 0.03, 0.4, 0.5;
  chain.scatter(q, qpos.data());
  EXPECT_EQ(chain.gather(qpos.data()), q);
}

TEST_F(ChainTest, BadInputIsRejectedWithNames) {
  EXPECT_THROW(Chain(robot_, "no_such_site"), Error);
  EXPECT_THROW(Chain(robot_, {"j1", "j1"}, "tool"), Error);
  EXPECT_THROW(Chain(robot_, {"box_free"}, "tool"), Error);
  EXPECT_THROW(Chain(robot_, std::vector<std::string>{}, "tool"), Error);
  EXPECT_THROW(Chain(robot_, "box"), Error);  // only a free joint above it
  const Chain chain(robot_, "tool");
  EXPECT_THROW(chain.check(Eigen::VectorXd::Zero(4)), Error);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(5);
  q[3] = std::numeric_limits<double>::infinity();
  try {
    chain.check(q, "seed");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("seed value for joint 'j4' is not finite"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace mjarm
