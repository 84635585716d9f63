#include "mjarm/planning/waypoint_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "planning/planning_support.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using planning_test::five_waypoints;
using planning_test::home_q;
using planning_test::panda_with_box;

struct PandaPlan : ::testing::Test {
  Robot robot = Robot::bundled("panda_torque");
  Chain chain{robot, "attachment_site"};
};

TEST_F(PandaPlan, FiveWaypointsPassThePosesInMotionWithinTheLimits) {
  WaypointPlanner planner(chain);
  const std::vector<Pose> path = five_waypoints();
  const PlanResult r = planner.plan(home_q(robot), path);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.waypoints.size(), 5u);
  ChainKinematics kin(chain);
  Eigen::VectorXd q(7), qd(7), qdd(7);
  for (const WaypointReport& w : r.waypoints) {
    r.trajectory.at(w.time, q, qd, qdd);
    const Pose& X = kin.update(q);
    EXPECT_LT((X.p - path[w.index].p).norm(), 1e-4) << w.index;
    EXPECT_TRUE(w.check.ok());
    EXPECT_GE(w.min_sigma, planner.options().checks.min_singular_value);
    EXPECT_LE(w.max_torque_ratio, 1.0);
    // interior waypoints are passed in motion
    if (w.index < 4) {
      EXPECT_GT(qd.norm(), 1e-3) << w.index;
    }
  }
  r.trajectory.at(r.trajectory.duration(), q, qd, qdd);
  EXPECT_LT(qd.norm(), 1e-12);
  // every sample honours the limits the plan used
  for (int j = 0; j <= 3000; ++j) {
    r.trajectory.at(r.trajectory.duration() * j / 3000.0, q, qd, qdd);
    EXPECT_TRUE(chain.within_limits(q, 1e-9));
    for (int i = 0; i < 7; ++i) {
      EXPECT_LE(std::abs(qd[i]), r.limits.max_velocity[i] * (1 + 1e-9));
      EXPECT_LE(std::abs(qdd[i]), r.limits.max_acceleration[i] * (1 + 1e-9));
    }
  }
  EXPECT_GT(r.samples, 100);
  EXPECT_NEAR(r.sample_spacing, 0.01, 1e-12);  // min(10 ms, 0.02 rad / 1 rad/s)
}

TEST_F(PandaPlan, DurationsComeFromTheLimitsAndTheSameSeedGivesTheSamePlan) {
  PlanOptions options;
  options.limits.max_velocity = Eigen::VectorXd::Constant(7, 0.5);
  const PlanResult slow = WaypointPlanner(chain, options).plan(home_q(robot), five_waypoints());
  const PlanResult fast = WaypointPlanner(chain).plan(home_q(robot), five_waypoints());
  ASSERT_TRUE(slow.ok() && fast.ok());
  EXPECT_GT(slow.trajectory.duration(), 1.5 * fast.trajectory.duration());
  const PlanResult again = WaypointPlanner(chain).plan(home_q(robot), five_waypoints());
  EXPECT_EQ(again.trajectory.duration(), fast.trajectory.duration());
}

TEST_F(PandaPlan, AWaypointOutsideTheWorkspaceIsUnreachable) {
  std::vector<Pose> path = five_waypoints();
  path[2].p = Eigen::Vector3d(1.5, 0.0, 0.5);  // the panda reaches about 0.85 m
  PlanOptions options;
  options.ik_branches = 2;
  const PlanResult r = WaypointPlanner(chain, options).plan(home_q(robot), path);
  EXPECT_EQ(r.status, PlanStatus::unreachable);
  EXPECT_EQ(r.failed_waypoint, 2);
  EXPECT_NE(r.message.find("waypoint 2: no IK solution"), std::string::npos) << r.message;
  EXPECT_TRUE(r.trajectory.empty());
}

TEST_F(PandaPlan, AWaypointAtTheStretchedSingularityIsRefused) {
  Eigen::VectorXd up(7);
  up << 0, 0, 0, -0.0698, 0, 2.5, 0;  // the top of the reach (z = 1.176 m): stretched out
  ChainKinematics kin(chain);
  std::vector<Pose> path{five_waypoints()[0], kin.update(up)};
  PlanOptions options;
  // every IK branch found there has σmin ≈ 0.055; home and waypoint 0 have ≈ 0.22
  options.checks.min_singular_value = 0.1;
  const PlanResult r = WaypointPlanner(chain, options).plan(home_q(robot), path);
  EXPECT_EQ(r.status, PlanStatus::singular) << r.message;
  EXPECT_EQ(r.failed_waypoint, 1);
  EXPECT_NE(r.message.find("singular value"), std::string::npos) << r.message;
}

TEST_F(PandaPlan, AWaypointThatNeedsMoreTorqueThanTheLimitsIsRefused) {
  // limits just above the gravity torques at home: reaching far out needs more at the shoulder
  DataPtr data = robot.make_data();
  chain.scatter(home_q(robot), data->qpos);
  mj_forward(&robot.model(), data.get());
  ChainDynamics dynamics(chain);
  dynamics.update(*data);
  PlanOptions options;
  options.limits.max_torque = (1.1 * dynamics.gravity().cwiseAbs()).cwiseMax(1.0);
  options.ik_branches = 3;
  Pose far = five_waypoints()[0];
  far.p = Eigen::Vector3d(0.75, 0.0, 0.25);
  const PlanResult r = WaypointPlanner(chain, options).plan(home_q(robot), {far});
  EXPECT_EQ(r.status, PlanStatus::torque) << r.message;
  EXPECT_EQ(r.failed_waypoint, 0);
  EXPECT_NE(r.message.find("of its torque limit"), std::string::npos) << r.message;
}

TEST_F(PandaPlan, FastLimitsAreSlowedDownUntilTheTorquesFit) {
  PlanOptions options;
  options.limits.max_velocity = Eigen::VectorXd::Constant(7, 3.0);
  options.limits.max_acceleration = Eigen::VectorXd::Constant(7, 300.0);
  const PlanResult r = WaypointPlanner(chain, options).plan(home_q(robot), five_waypoints());
  ASSERT_TRUE(r.ok()) << r.message;
  for (const WaypointReport& w : r.waypoints) EXPECT_LE(w.max_torque_ratio, 1.0) << w.index;
  // at 300 rad/s² the wrist joints alone would need more than their 12 N·m: some segment was
  // stretched beyond the shortest duration the velocity and acceleration limits allow
  bool stretched = false;
  for (int k = 0; k < r.trajectory.segments(); ++k) {
    const JointSpline& s = r.trajectory;
    const QuinticDuration shortest = shortest_quintic_duration(
        {s.knots()[k], s.knot_velocities()[k], Eigen::VectorXd::Zero(7)},
        {s.knots()[k + 1], s.knot_velocities()[k + 1], Eigen::VectorXd::Zero(7)},
        options.limits.max_velocity, options.limits.max_acceleration, options.min_segment_duration);
    stretched = stretched || s.segment(k).duration() > 1.01 * shortest.duration;
  }
  EXPECT_TRUE(stretched);
}

TEST(WaypointPlanner, AWaypointInsideAnObstacleIsACollision) {
  const Robot robot = panda_with_box({0.45, 0.20, 0.40}, 0.06);  // around waypoint 1
  const Chain chain(robot, "attachment_site");
  PlanOptions options;
  options.ik_branches = 3;
  const PlanResult r = WaypointPlanner(chain, options).plan(home_q(robot), five_waypoints());
  EXPECT_EQ(r.status, PlanStatus::collision) << r.message;
  EXPECT_EQ(r.failed_waypoint, 1);
  EXPECT_NE(r.message.find("'obstacle'"), std::string::npos) << r.message;
}

TEST(WaypointPlanner, AnObstacleBetweenWaypointsIsGoneAround) {
  // a box across the way from waypoint 0 to waypoint 1, clear of both
  const Robot robot = panda_with_box({0.47, 0.10, 0.45}, 0.035);
  const Chain chain(robot, "attachment_site");
  const std::vector<Pose> path = five_waypoints();
  const PlanResult r = WaypointPlanner(chain).plan(home_q(robot), {path[0], path[1]});
  ASSERT_TRUE(r.ok()) << r.message;
  // without the box the direct motion would touch it: the plan went around (branch or detour)
  const Robot plain = Robot::bundled("panda_torque");
  const PlanResult direct =
      WaypointPlanner(Chain(plain, "attachment_site")).plan(home_q(plain), {path[0], path[1]});
  ASSERT_TRUE(direct.ok());
  ConfigurationChecker checker(chain, r.limits);
  const auto collisions = [&checker](const JointSpline& s) {
    int count = 0;
    Eigen::VectorXd q(7), qd(7), qdd(7);
    for (int j = 0; j <= 4000; ++j) {
      s.at(s.duration() * j / 4000.0, q, qd, qdd);
      count += checker.check(q).failure == CheckFailure::collision;
    }
    return count;
  };
  EXPECT_GT(collisions(direct.trajectory), 0);
  EXPECT_EQ(collisions(r.trajectory), 0);
  EXPECT_TRUE(r.waypoints[1].detour || r.waypoints[1].branch > 0);
}

TEST(WaypointPlanner, AStartInCollisionIsReported) {
  const Robot robot = panda_with_box({0.31, 0.0, 0.56}, 0.05);
  const Chain chain(robot, "attachment_site");
  const PlanResult r = WaypointPlanner(chain).plan(home_q(robot), five_waypoints());
  EXPECT_EQ(r.status, PlanStatus::start_failed);
  EXPECT_NE(r.message.find("start configuration fails"), std::string::npos);
}

TEST_F(PandaPlan, AStartBeyondTheJointLimitsIsAnHonestStatus) {
  Eigen::VectorXd q = home_q(robot);
  q[3] = 0.5;  // joint4's range is [−3.07, −0.07]
  const PlanResult r = WaypointPlanner(chain).plan(q, five_waypoints());
  EXPECT_EQ(r.status, PlanStatus::start_failed);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.message.find("joint4"), std::string::npos) << r.message;
  EXPECT_EQ(r.trajectory.duration(), 0.0);  // no trajectory to follow
}

TEST_F(PandaPlan, BadInputIsAnError) {
  WaypointPlanner planner(chain);
  EXPECT_THROW(planner.plan(home_q(robot), {}), Error);
  // a start that is not finite
  Eigen::VectorXd q_nan = home_q(robot);
  q_nan[2] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(planner.plan(q_nan, five_waypoints()), Error);
  // a waypoint rotation that is not a rotation
  std::vector<Pose> skewed = five_waypoints();
  skewed[1].R(0, 1) += 0.1;
  EXPECT_THROW(planner.plan(home_q(robot), skewed), Error);
  // zero, negative or NaN limits, named
  for (double bad : {0.0, -1.0, std::nan("")}) {
    for (int which = 0; which < 3; ++which) {
      PlanOptions limited;
      Eigen::VectorXd v = Eigen::VectorXd::Ones(7);
      v[4] = bad;
      (which == 0   ? limited.limits.max_velocity
       : which == 1 ? limited.limits.max_acceleration
                    : limited.limits.max_torque) = v;
      const std::string message = test::error_of(
          [&] { WaypointPlanner(chain, limited).plan(home_q(robot), five_waypoints()); });
      EXPECT_FALSE(message.empty()) << "limit " << which << " = " << bad;
    }
  }
  std::vector<Pose> path = five_waypoints();
  path[3].p.x() = std::nan("");
  EXPECT_THROW(planner.plan(home_q(robot), path), Error);
  EXPECT_THROW(planner.plan(Eigen::VectorXd::Zero(3), five_waypoints()), Error);
  PlanOptions options;
  options.sample_period = 0.0;
  EXPECT_THROW(WaypointPlanner(chain, options), Error);
  options = PlanOptions{};
  options.limits.max_velocity = Eigen::VectorXd::Ones(2);
  EXPECT_THROW(WaypointPlanner(chain, options), Error);
  // limits out of proportion: an error, not a billion samples or an overflow
  options = PlanOptions{};
  options.limits.max_velocity = Eigen::VectorXd::Constant(7, 1e12);
  options.limits.max_acceleration = Eigen::VectorXd::Constant(7, 1e-6);
  EXPECT_NE(test::error_of([&] {
              WaypointPlanner(chain, options).plan(home_q(robot), five_waypoints());
            }).find("beyond the 100000 samples a segment may have"),
            std::string::npos);
  options = PlanOptions{};
  options.max_samples = 0;
  EXPECT_THROW(WaypointPlanner(chain, options), Error);
  options = PlanOptions{};
  options.max_segment_samples = 0;
  EXPECT_THROW(WaypointPlanner(chain, options), Error);
}

// issue 16, item 4's rule in the planner: slow limits made `mjarm plan` check a motion of hours
// at every 10 ms (--velocity-limit 0.0001: over a minute, no end in sight); the work is bounded
// and refused before the checks, naming the bound
TEST_F(PandaPlan, SlowLimitsAreRefusedBeforeTheChecksNotAfterMinutes) {
  PlanOptions options;
  options.limits.max_velocity = Eigen::VectorXd::Constant(7, 1e-4);
  const std::string message = test::error_of(
      [&] { WaypointPlanner(chain, options).plan(home_q(robot), five_waypoints()); });
  EXPECT_NE(message.find("beyond the 100000 samples a segment may have"), std::string::npos)
      << message;
  // refused at the first segment, before a single sample of it or of any other was checked
  EXPECT_NE(message.find("the plan had checked 0 before it"), std::string::npos) << message;
  // the work of a whole plan is bounded too: a small budget refuses even the usual five
  // waypoints, at the segment that would pass it
  PlanOptions small;
  small.max_samples = 200;
  const std::string total =
      test::error_of([&] { WaypointPlanner(chain, small).plan(home_q(robot), five_waypoints()); });
  EXPECT_NE(total.find("beyond the 200 samples a plan may check in all"), std::string::npos)
      << total;
  small.max_samples = PlanOptions{}.max_samples;
  EXPECT_TRUE(WaypointPlanner(chain, small).plan(home_q(robot), five_waypoints()).ok());
}

}  // namespace
}  // namespace mjarm
