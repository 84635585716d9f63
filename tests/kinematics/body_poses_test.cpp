#include "mjarm/kinematics/body_poses.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"

namespace mjarm {
namespace {

TEST(BodyPoses, EveryBodyAsMujocoPlacesIt) {
  const Robot robot = Robot::bundled("panda");
  const mjModel& m = robot.model();
  BodyPoses poses(robot);
  Eigen::VectorXd qpos = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
  qpos.head(7) << 0.3, -0.5, 0.2, -2.0, 0.1, 1.6, 0.7;
  poses.update(qpos);
  DataPtr d = robot.make_data();
  Eigen::Map<Eigen::VectorXd>(d->qpos, m.nq) = qpos;
  mj_forward(&m, d.get());
  ASSERT_EQ(poses.size(), m.nbody);
  for (int b = 0; b < m.nbody; ++b) {
    EXPECT_EQ(poses.pose(b).p, Eigen::Map<const Eigen::Vector3d>(d->xpos + 3 * b)) << b;
    const Eigen::Matrix3d R =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->xmat + 9 * b);
    EXPECT_EQ(poses.pose(b).R, R) << b;
  }
  EXPECT_EQ(poses.names().front(), "world");
  EXPECT_EQ(&poses.pose("link7"), &poses.pose(robot.body("link7")));
}

TEST(BodyPoses, TheEndBodyAgreesWithTheChainsOwnKinematics) {
  // two methods: MuJoCo's mj_kinematics for every body, mjarm's chain recursion for the site
  const Robot robot = Robot::bundled("panda");
  const mjModel& m = robot.model();
  const Chain chain(robot, "attachment_site");
  ChainKinematics kinematics(chain);
  BodyPoses poses(robot);
  const Eigen::VectorXd q =
      (Eigen::VectorXd(7) << -0.4, 0.6, -0.3, -1.5, 0.8, 2.1, -0.2).finished();
  poses.update(chain, q);
  const Pose& X_WE = kinematics.update(q);
  const int site = robot.site("attachment_site");
  const Pose& X_WB = poses.pose(m.site_bodyid[site]);
  const Eigen::Vector3d p_BS = Eigen::Map<const Eigen::Vector3d>(m.site_pos + 3 * site);
  EXPECT_LT((X_WB.p + X_WB.R * p_BS - X_WE.p).norm(), 1e-12);
}

TEST(BodyPoses, RefusesBadInput) {
  const Robot robot = Robot::bundled("panda");
  BodyPoses poses(robot);
  EXPECT_THROW(poses.update(Eigen::VectorXd::Zero(3)), Error);
  Eigen::VectorXd qpos = Eigen::VectorXd::Zero(robot.nq());
  qpos[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(poses.update(qpos), Error);
  EXPECT_THROW(poses.pose("lnik7"), Error);
  const Robot ur5e = Robot::bundled("ur5e");
  const Chain other(ur5e, "attachment_site");
  EXPECT_THROW(poses.update(other, Eigen::VectorXd::Zero(6)), Error);
}

}  // namespace
}  // namespace mjarm
