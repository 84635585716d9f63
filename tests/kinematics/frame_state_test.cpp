#include "mjarm/kinematics/frame_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

class FrameStateTest : public ::testing::Test {
 protected:
  /// Puts @p q into the scratch data and runs mj_forward (positions, com, Jacobian inputs).
  void forward(const Chain& chain, const Eigen::VectorXd& q) {
    chain.scatter(q, d_->qpos);
    mj_forward(&robot_.model(), d_.get());
  }

  Robot robot_ = Robot::from_string(test::kTrickyArm);
  DataPtr d_ = robot_.make_data();
};

TEST_F(FrameStateTest, PoseAndJacobianAgreeWithChainKinematics) {
  for (const char* frame : {"tool", "l3"}) {  // a site and a body
    const Chain chain(robot_, frame);
    ChainKinematics kin(chain);
    const JointSampler sampler(chain);
    std::mt19937_64 rng(17);
    Eigen::VectorXd q(chain.size());
    Matrix6Xd J_mj(6, chain.size()), J_kin(6, chain.size());
    for (int trial = 0; trial < 50; ++trial) {
      sampler.sample(rng, q);
      forward(chain, q);
      const Pose X_mj = frame_pose(robot_.model(), *d_, chain.frame());
      mujoco_frame_jacobian(chain, *d_, J_mj);
      const Pose& X_kin = kin.update(q);
      kin.jacobian(J_kin);
      EXPECT_TRUE(X_mj.is_approx(X_kin, 1e-12)) << frame;
      EXPECT_LT((J_mj - J_kin).norm(), 1e-12) << frame;
      EXPECT_TRUE(forward_kinematics(chain, q).is_approx(X_kin, 1e-15));
      // the rotation read from mujoco is orthonormal (row-major read the right way round)
      EXPECT_LT((X_mj.R * X_mj.R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    }
  }
}

TEST_F(FrameStateTest, JacobianKeepsOnlyTheChainDofsInChainOrder) {
  // the free box shifts every arm dof by 6 in qvel; an off-path joint gives a zero column
  const Chain chain(robot_, {"j4", "off_path", "j1"}, "tool");
  Eigen::VectorXd q(3);
  q << 0.3, -0.4, 1.1;
  forward(chain, q);
  Matrix6Xd J(6, 3);
  mujoco_frame_jacobian(chain, *d_, J);
  EXPECT_EQ(J.col(1).norm(), 0.0);
  const Chain full(robot_, "tool");
  Matrix6Xd J_full(6, full.size());
  mujoco_frame_jacobian(full, *d_, J_full);
  EXPECT_EQ(J.col(0), J_full.col(3));  // j4 is the 4th joint on the tool's path
  EXPECT_EQ(J.col(2), J_full.col(0));
  // the angular rows hold the joint axis in world: j1's axis is the base's z axis
  const Eigen::Vector3d z_base =
      frame_pose(robot_.model(), *d_, find_frame(robot_, "base")).R.col(2);
  EXPECT_LT((J.col(2).tail<3>() - z_base).norm(), 1e-12);
}

TEST_F(FrameStateTest, RejectsBadInput) {
  const Chain chain(robot_, "tool");
  EXPECT_THROW(forward_kinematics(chain, Eigen::VectorXd::Zero(4)), Error);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(5);
  q[0] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(forward_kinematics(chain, q), Error);
  Matrix6Xd J(6, 4);
  EXPECT_THROW(mujoco_frame_jacobian(chain, *d_, J), Error);
  FrameRef bad{FrameKind::site, static_cast<int>(robot_.model().nsite), "ghost"};
  EXPECT_THROW(frame_pose(robot_.model(), *d_, bad), Error);
  bad = FrameRef{FrameKind::body, -1, "ghost"};
  EXPECT_THROW(frame_pose(robot_.model(), *d_, bad), Error);
}

}  // namespace
}  // namespace mjarm
