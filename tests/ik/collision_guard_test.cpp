#include "mjarm/ik/collision_guard.hpp"

#include <gtest/gtest.h>

#include <random>

#include "ik/local_ik_support.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/multi_target_ik.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"

namespace mjarm {
namespace {

// right arm of kTwoBranch: shoulder at (0, -0.2, 0.5), links 0.3 + 0.25 + 0.1 m in the
// horizontal plane; the post (radius 0.05) stands at (0.3, -0.55), 0.46 m from the shoulder
// at -49 degrees
Chain right_arm(const Robot& robot) { return Chain(robot, "right_tip"); }

Eigen::VectorXd right_q(double lift, double yaw1, double yaw2, double yaw3) {
  return (Eigen::VectorXd(4) << lift, yaw1, yaw2, yaw3).finished();
}

TEST(CollisionGuard, DetectsPairsAndGeomsAgainstAnything) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const Chain chain = right_arm(robot);
  ASSERT_EQ(chain.size(), 4);
  CollisionGuard pair(chain, {{{"r_link2", "post"}}, {}, 0.0, 4});
  CollisionGuard any(chain, {{}, {"r_link2"}, 0.0, 4});
  CollisionGuard other_pair(chain, {{{"r_link1", "post"}}, {}, 0.0, 4});
  // straight along +x: clear of the post
  EXPECT_FALSE(pair.in_contact(right_q(0, 0, 0, 0)));
  EXPECT_FALSE(any.in_contact(right_q(0, 0, 0, 0)));
  // link 2 (0.3 .. 0.55 m from the shoulder) swept through the post at -49 degrees
  const Eigen::VectorXd through = right_q(0, -0.855, 0, 0);
  EXPECT_TRUE(pair.in_contact(through));
  EXPECT_TRUE(any.in_contact(through));
  EXPECT_FALSE(other_pair.in_contact(through));  // link 1 ends at 0.3 m, short of the post
  EXPECT_NE(pair.describe_contacts(through).find("'post'"), std::string::npos);
  EXPECT_TRUE(pair.describe_contacts(right_q(0, 0, 0, 0)).empty());
}

TEST(CollisionGuard, MarginCountsNearMissesAsContact) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const Chain chain = right_arm(robot);
  // the arm at -0.6 rad passes the post with a gap of a few centimetres
  const Eigen::VectorXd near = right_q(0, -0.6, 0, 0);
  CollisionGuard tight(chain, {{{"r_link2", "post"}}, {}, 0.0, 4});
  CollisionGuard wide(chain, {{{"r_link2", "post"}}, {}, 0.1, 4});
  EXPECT_FALSE(tight.in_contact(near));
  EXPECT_TRUE(wide.in_contact(near));
}

TEST(CollisionGuard, FixedJointsComeFromSetFixedQpos) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  // a chain of the lift only: the arm's yaw joints are held by the fixed qpos
  const Chain lift(robot, {"lift"}, "right_tip");
  CollisionGuard guard(lift, {{{"r_link2", "post"}}, {}, 0.0, 4});
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(1);
  EXPECT_FALSE(guard.in_contact(q));
  Eigen::VectorXd qpos = Eigen::VectorXd::Zero(robot.nq());
  qpos[robot.joint_info(robot.joint("r_yaw1")).qpos_address] = -0.855;
  guard.set_fixed_qpos(qpos);
  EXPECT_TRUE(guard.in_contact(q));
  EXPECT_THROW(guard.set_fixed_qpos(Eigen::VectorXd::Zero(3)), Error);
}

TEST(CollisionGuard, RejectsBadSpecs) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const Chain chain = right_arm(robot);
  EXPECT_THROW(CollisionGuard(chain, {{{"r_link2", "no_such_geom"}}, {}, 0.0, 4}), Error);
  EXPECT_THROW(CollisionGuard(chain, {{{"post", "post"}}, {}, 0.0, 4}), Error);
  EXPECT_THROW(CollisionGuard(chain, {{}, {"nope"}, 0.0, 4}), Error);
  EXPECT_THROW(CollisionGuard(chain, {{{"r_link2", "post"}}, {}, -0.1, 4}), Error);
  EXPECT_THROW(CollisionGuard(chain, {{{"r_link2", "post"}}, {}, 0.0, -1}), Error);
}

TEST(CollisionGuard, SolversRollBackStepsIntoContact) {
  // from the arm along +x to a target along -y, the straight path sweeps the arm through the post
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const Chain chain = right_arm(robot);
  const Eigen::VectorXd seed = right_q(0, 0, 0, 0);
  ChainKinematics fk(chain);
  const Pose X_WT = fk.update(right_q(0, -1.4, 0, 0));
  CollisionSpec spec{{{"r_link1", "post"}, {"r_link2", "post"}, {"r_link3", "post"}}, {}, 0.0, 4};
  CollisionGuard guard(chain, spec);
  ASSERT_FALSE(guard.in_contact(seed));
  ASSERT_FALSE(guard.in_contact(right_q(0, -1.4, 0, 0)));

  PositionIkOptions free_options, guarded_options;
  guarded_options.collision = spec;
  const IkResult free_run = PositionIk(chain, free_options).solve(X_WT.p, seed);
  const IkResult guarded = PositionIk(chain, guarded_options).solve(X_WT.p, seed);
  EXPECT_TRUE(free_run.ok());  // without the hook the arm goes straight through the post
  EXPECT_EQ(guarded.status, IkStatus::not_converged);
  EXPECT_FALSE(guard.in_contact(guarded.q));
  EXPECT_GT(guarded.position_error, 0.1);

  // short steps, so that no step can hop over the post (the checks are discrete)
  PoseIkOptions pose_options;
  pose_options.collision = spec;
  pose_options.max_step = 0.05;
  const IkResult pose = PoseIk(chain, pose_options).solve(X_WT, seed);
  EXPECT_EQ(pose.status, IkStatus::not_converged);
  EXPECT_FALSE(guard.in_contact(pose.q));

  MultiTargetIkOptions multi_options;
  multi_options.collision = spec;
  multi_options.max_step = 0.05;
  MultiTargetIk multi(robot, chain.joint_names(),
                      {FrameTarget{"right_tip", TargetKind::pose, X_WT, 1, 1, 0}}, multi_options);
  const IkResult m = multi.solve(seed);
  EXPECT_EQ(m.status, IkStatus::not_converged);
  EXPECT_FALSE(guard.in_contact(m.q));

  // a seed in contact is refused at the boundary
  EXPECT_THROW(PositionIk(chain, guarded_options).solve(X_WT.p, right_q(0, -0.855, 0, 0)), Error);
}

}  // namespace
}  // namespace mjarm
