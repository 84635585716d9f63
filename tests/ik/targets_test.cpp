#include "mjarm/ik/targets.hpp"

#include <gtest/gtest.h>

#include <random>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/pose_error.hpp"
#include "support/random_configurations.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

/// Central differences of a target's residual: the task Jacobian must equal −de/dq.
void expect_task_jacobian_matches_differences(const Chain& chain, TargetKind kind,
                                              std::mt19937& rng) {
  ChainKinematics kin(chain);
  const int n = chain.size();
  const int m = task_rows(kind);
  Matrix6Xd scratch(6, n);
  Eigen::MatrixXd J(m, n), unused(m, n), fd(m, n);
  Eigen::VectorXd e(m);
  FiniteDifferenceWorkspace workspace(n, m);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = test::random_q(chain, rng, 0.05);
    // a target near the frame, so the log stays well inside its principal branch
    Pose X_WT = kin.update(test::perturb(chain, q, rng, 0.3));
    kin.update(q);
    evaluate_target(kin, kind, X_WT, e, J, scratch);
    const auto residual = [&](const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> out) {
      kin.update(x);
      evaluate_target(kin, kind, X_WT, out, unused, scratch);
    };
    finite_difference_jacobian(residual, q, fd, workspace);
    for (int i = 0; i < n; ++i) {
      const Eigen::VectorXd de = fd.col(i);
      EXPECT_LT((de + J.col(i)).norm(), 1e-7) << "joint " << i << " kind " << m;
    }
  }
}

TEST(Targets, TaskJacobiansMatchFiniteDifferences) {
  std::mt19937 rng(5);
  const Robot tricky = Robot::from_string(test::kTrickyArm);
  const Robot panda = Robot::bundled("panda");
  for (const Chain& chain : {Chain(tricky, "tool"), Chain(panda, "attachment_site")}) {
    expect_task_jacobian_matches_differences(chain, TargetKind::position, rng);
    expect_task_jacobian_matches_differences(chain, TargetKind::pose, rng);
  }
}

TEST(Targets, PoseResidualIsTheBodyLogError) {
  const Robot robot = Robot::bundled("arm6");
  const Chain chain(robot, "grip");
  ChainKinematics kin(chain);
  std::mt19937 rng(6);
  Matrix6Xd scratch(6, chain.size()), J_local(6, chain.size());
  Eigen::MatrixXd J(6, chain.size());
  Eigen::VectorXd e(6);
  const Pose X_WT = kin.update(test::random_q(chain, rng));
  const Pose& X_WE = kin.update(test::random_q(chain, rng));
  const FrameErrors f = evaluate_target(kin, TargetKind::pose, X_WT, e, J, scratch);
  EXPECT_LT((e - log_error(X_WE, X_WT)).norm(), 1e-14);
  EXPECT_NEAR(f.position, (X_WT.p - X_WE.p).norm(), 1e-14);
  EXPECT_NEAR(f.orientation, e.tail<3>().norm(), 1e-12);
  // Jlog times the local Jacobian, with the local Jacobian from the kinematics itself
  kin.jacobian(J_local, JacobianFrame::local);
  EXPECT_LT((J - log_error_jacobian(log_error(X_WE, X_WT)) * J_local).norm(), 1e-12);
}

TEST(Targets, FrameErrorsOfKnownOffsets) {
  const Pose X_WE = Pose::from_rpy(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.3, -0.2, 1.0));
  Pose X_WT = X_WE;
  X_WT.p += Eigen::Vector3d(0.03, 0.0, -0.04);
  X_WT.R = X_WT.R * Eigen::AngleAxisd(0.25, Eigen::Vector3d(1, 2, 2) / 3.0).toRotationMatrix();
  const FrameErrors f = frame_errors(X_WE, X_WT);
  EXPECT_NEAR(f.position, 0.05, 1e-15);
  EXPECT_NEAR(f.orientation, 0.25, 1e-14);
}

TEST(Targets, ValidationRejectsBadPosesAndWeights) {
  Pose X = Pose::from_rpy(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.3, -0.2, 1.0));
  EXPECT_TRUE(is_valid_pose(X));
  EXPECT_NO_THROW(check_pose_target(X));
  Pose reflected = X;
  reflected.R.col(0) *= -1.0;  // orthonormal but det = −1
  EXPECT_FALSE(is_valid_pose(reflected));
  EXPECT_THROW(check_pose_target(reflected), Error);
  Pose scaled = X;
  scaled.R *= 1.01;
  EXPECT_THROW(check_pose_target(scaled), Error);
  Pose nan = X;
  nan.p.y() = std::numeric_limits<double>::quiet_NaN();
  try {
    check_pose_target(nan, "hand target");
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("hand target"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      check_position_target(Eigen::Vector3d(0, -std::numeric_limits<double>::infinity(), 0)),
      Error);
  FrameTarget t{"hand", TargetKind::pose, X, 1.0, 0.0, 0};
  EXPECT_THROW(check_weights(t), Error);
  t.orientation_weight = 2.0;
  EXPECT_NO_THROW(check_weights(t));
  EXPECT_EQ(task_rows(TargetKind::position), 3);
  EXPECT_EQ(task_rows(TargetKind::pose), 6);
}

}  // namespace
}  // namespace mjarm
