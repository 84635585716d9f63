#include "mjarm/planning/ompl_planner.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/planning/collision_checker.hpp"
#include "mjarm/planning/configuration_check.hpp"
#include "mjarm/planning/planned_reference.hpp"
#include "mjarm/planning/waypoint_planner.hpp"
#include "mjarm/random.hpp"
#include "planning/planning_support.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using planning_test::home_q;
using planning_test::panda_with_box;

/// The panda with a box in the way of joint 1's swing from home to the left.
struct OmplPanda : ::testing::Test {
  Robot robot = panda_with_box({0.22, 0.22, 0.55}, 0.08);
  Chain chain{robot, "attachment_site"};
  Eigen::VectorXd start = home_q(robot);
  Eigen::VectorXd goal = swung(home_q(robot), 1.6);

  static Eigen::VectorXd swung(Eigen::VectorXd q, double joint1) {
    q[0] = joint1;
    return q;
  }
  OmplOptions fast() const {
    OmplOptions o;
    o.time_budget = 20.0;  // an upper bound only: RRT-Connect stops at its first path
    return o;
  }
};

/// Every state of @p trajectory every 2 ms: collision-free by a separate checker, within limits.
void expect_trajectory_clear(const OmplResult& r, const Chain& chain) {
  CollisionChecker checker(chain);
  const JointSpline& s = r.trajectory;
  Eigen::VectorXd q(7), qd(7), qdd(7);
  const int m = static_cast<int>(std::ceil(s.duration() / 0.002));
  for (int j = 0; j <= m; ++j) {
    s.at(s.duration() * j / m, q, qd, qdd);
    ASSERT_TRUE(checker.valid(q)) << "t = " << s.duration() * j / m << ": "
                                  << checker.describe_last();
    for (int i = 0; i < 7; ++i) {
      EXPECT_LE(std::abs(qd[i]), r.limits.max_velocity[i] * (1 + 1e-9));
      EXPECT_LE(std::abs(qdd[i]), r.limits.max_acceleration[i] * (1 + 1e-9));
    }
  }
}

TEST_F(OmplPanda, StraightMotionCollidesOmplFindsATimedPathClearOfTheBox) {
  CollisionChecker checker(chain);
  ASSERT_TRUE(checker.valid(start)) << checker.describe_last();
  ASSERT_TRUE(checker.valid(goal)) << checker.describe_last();
  bool straight_collides = false;
  for (int j = 0; j <= 200; ++j)
    straight_collides = straight_collides || !checker.valid(start + (goal - start) * j / 200.0);
  ASSERT_TRUE(straight_collides);

  OmplPlanner planner(chain, fast());
  const OmplResult r = planner.plan(start, JointGoal{goal});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.path.size(), 3u);  // not the straight line
  EXPECT_LT((r.path.front() - start).norm(), 1e-12);
  EXPECT_LT((r.path.back() - goal).norm(), 1e-12);
  EXPECT_GT(r.path_length, (goal - start).norm());
  EXPECT_GT(r.validity_checks, 10);
  EXPECT_GT(r.trajectory_samples, 10);
  Eigen::VectorXd q(7), qd(7), qdd(7);
  r.trajectory.at(r.trajectory.duration(), q, qd, qdd);
  EXPECT_LT((q - goal).norm(), 1e-9);
  EXPECT_LT(qd.norm(), 1e-12);
  expect_trajectory_clear(r, chain);
}

TEST_F(OmplPanda, TheTimeOptimalTimingIsClearWithinTheLimitsAndFasterThanTheSpline) {
  OmplPlanner planner(chain, fast());
  const OmplResult r = planner.plan(start, JointGoal{goal});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_TRUE(r.time_optimal.has_value()) << r.message;
  const TimeOptimalPath& path = *r.time_optimal;
  EXPECT_LT(path.duration(), r.trajectory.duration());
  // every 2 ms, by a separate checker: touching nothing, within the limits, from start to goal
  CollisionChecker checker(chain);
  TrajectorySample s(7);
  const int m = static_cast<int>(std::ceil(path.duration() / 0.002));
  for (int j = 0; j <= m; ++j) {
    path.at(path.duration() * j / m, s);
    ASSERT_TRUE(checker.valid(s.position)) << "t = " << path.duration() * j / m;
    for (int i = 0; i < 7; ++i) {
      EXPECT_LE(std::abs(s.velocity[i]), r.limits.max_velocity[i] * (1 + 1e-9));
      EXPECT_LE(std::abs(s.acceleration[i]), r.limits.max_acceleration[i] * (1 + 1e-9));
    }
  }
  path.at(0.0, s);
  EXPECT_LT((s.position - start).norm(), 1e-9);
  path.at(path.duration(), s);
  EXPECT_LT((s.position - goal).norm(), 1e-9);
  EXPECT_LT(s.velocity.norm(), 1e-9);

  // tracked as a reference: the joint reference is the path's sample at t − t₀
  PlannedReference reference(chain, path, 0.2);
  EXPECT_DOUBLE_EQ(reference.run_time(), path.duration() + 0.2);
  Reference ref;
  reference.evaluate(0.5 * path.duration(), ref);
  path.at(0.5 * path.duration(), s);
  EXPECT_LT((ref.joint.q - s.position).norm(), 1e-15);
  EXPECT_LT((ref.joint.qd - s.velocity).norm(), 1e-15);
  EXPECT_EQ(reference.spline(), nullptr);
  OmplOptions spline_only = fast();
  spline_only.time_optimal = false;
  EXPECT_FALSE(OmplPlanner(chain, spline_only).plan(start, JointGoal{goal}).time_optimal);
}

TEST_F(OmplPanda, TheSameSeedGivesTheSamePath) {
  OmplPlanner planner(chain, fast());
  const OmplResult a = planner.plan(start, JointGoal{goal});
  const OmplResult b = planner.plan(start, JointGoal{goal});
  OmplPlanner fresh(chain, fast());
  const OmplResult c = fresh.plan(start, JointGoal{goal});
  ASSERT_TRUE(a.ok() && b.ok() && c.ok()) << a.message << b.message << c.message;
  ASSERT_EQ(a.path.size(), b.path.size());
  ASSERT_EQ(a.path.size(), c.path.size());
  for (std::size_t k = 0; k < a.path.size(); ++k) {
    EXPECT_EQ(a.path[k], b.path[k]) << k;
    EXPECT_EQ(a.path[k], c.path[k]) << k;
  }
  EXPECT_EQ(a.validity_checks, c.validity_checks);
}

TEST_F(OmplPanda, AStartOrGoalInCollisionIsTheStatus) {
  // the middle of the straight swing: the arm inside the box
  const Eigen::VectorXd buried = 0.5 * (start + goal);
  CollisionChecker checker(chain);
  ASSERT_FALSE(checker.valid(buried));
  EXPECT_NE(checker.describe_last().find("obstacle"), std::string::npos);
  OmplPlanner planner(chain, fast());
  OmplResult r = planner.plan(buried, JointGoal{goal});
  EXPECT_EQ(r.status, OmplStatus::start_in_collision) << r.message;
  EXPECT_TRUE(r.path.empty());
  r = planner.plan(start, JointGoal{buried});
  EXPECT_EQ(r.status, OmplStatus::goal_in_collision) << r.message;
  EXPECT_NE(r.message.find("touches"), std::string::npos) << r.message;
  // a goal beyond a joint's range is bad input, not a collision
  Eigen::VectorXd beyond = goal;
  beyond[3] = 0.5;  // joint 4's range ends below 0
  r = planner.plan(start, JointGoal{beyond});
  EXPECT_EQ(r.status, OmplStatus::invalid_input) << r.message;
  EXPECT_THROW(planner.plan(start, JointGoal{Eigen::VectorXd::Zero(3)}), Error);
}

TEST_F(OmplPanda, APoseGoalIsReachedToItsToleranceByForwardKinematics) {
  ChainKinematics kin(chain);
  PoseGoal target;
  target.X_WT = kin.update(goal);
  OmplPlanner planner(chain, fast());
  const OmplResult r = planner.plan(start, target);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_GE(r.goal_states, 1);
  const Pose X = kin.update(r.path.back());
  EXPECT_LT((X.p - target.X_WT.p).norm(), std::sqrt(3.0) * target.position_tolerance);
  EXPECT_LT(Eigen::AngleAxisd(X.R.transpose() * target.X_WT.R).angle(),
            std::sqrt(3.0) * target.orientation_tolerance);
  expect_trajectory_clear(r, chain);
}

TEST_F(OmplPanda, APoseRegionGoalEndsInsideTheRegion) {
  ChainKinematics kin(chain);
  const Pose X_goal = kin.update(goal);
  PoseRegionGoal region;
  region.lower = X_goal.p - Eigen::Vector3d(0.03, 0.03, 0.0);
  region.upper = X_goal.p + Eigen::Vector3d(0.03, 0.03, 0.05);
  region.R_WT = X_goal.R;
  region.orientation_tolerance = 0.2;
  OmplPlanner planner(chain, fast());
  const OmplResult r = planner.plan(start, region);
  ASSERT_TRUE(r.ok()) << r.message;
  const Pose X = kin.update(r.path.back());
  EXPECT_TRUE((X.p.array() >= region.lower.array() - 2e-4).all()) << X.p.transpose();
  EXPECT_TRUE((X.p.array() <= region.upper.array() + 2e-4).all()) << X.p.transpose();
  EXPECT_LE(Eigen::AngleAxisd(X.R.transpose() * region.R_WT).angle(), 0.2);
}

TEST_F(OmplPanda, APoseOutsideTheWorkspaceIsUnreachable) {
  PoseGoal far;
  far.X_WT.p = Eigen::Vector3d(2.0, 0.0, 0.5);
  OmplOptions o = fast();
  o.ik_goals = 2;
  OmplPlanner planner(chain, o);
  const OmplResult r = planner.plan(start, far);
  EXPECT_EQ(r.status, OmplStatus::goal_unreachable) << r.message;
}

TEST_F(OmplPanda, ATimeBudgetOfZeroNanOrAGigasecondIsRefused) {
  for (const double budget : {0.0, std::numeric_limits<double>::quiet_NaN(), 1e9, -1.0}) {
    OmplOptions o;
    o.time_budget = budget;
    const std::string message = test::error_of([&] { OmplPlanner(chain, o); });
    EXPECT_NE(message.find("time_budget"), std::string::npos) << message;
  }
}

TEST_F(OmplPanda, AnUnknownAllowedCollisionNameIsRefusedByName) {
  OmplOptions o;
  o.allowed_collisions = {{"link7", "obstacel"}};
  const std::string message = test::error_of([&] { OmplPlanner(chain, o); });
  EXPECT_NE(message.find("'obstacel'"), std::string::npos) << message;
  EXPECT_NE(message.find("obstacle"), std::string::npos) << message;  // the closest name
}

TEST_F(OmplPanda, AllowingTheObstacleToTouchEveryLinkLeavesTheStraightPath) {
  OmplOptions o = fast();
  for (const char* link : {"link1", "link2", "link3", "link4", "link5", "link6", "link7"})
    o.allowed_collisions.push_back({link, "obstacle"});
  OmplPlanner planner(chain, o);
  const OmplResult r = planner.plan(start, JointGoal{goal});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.path.size(), 2u);  // simplified to the straight line through the box
  EXPECT_NEAR(r.path_length, (goal - start).norm(), 1e-9);
}

TEST_F(OmplPanda, EachPlannerIsSelectableByNameAndSolvesTheBox) {
  for (const char* name : {"rrtconnect", "prm", "rrtstar", "bitstar"}) {
    OmplOptions o = fast();
    o.planner = parse_enum<OmplPlannerType>(name, "planner");
    OmplPlanner planner(chain, o);
    const OmplResult r = planner.plan(start, JointGoal{goal});
    ASSERT_TRUE(r.ok()) << name << ": " << r.message;
    expect_trajectory_clear(r, chain);
  }
}

TEST_F(OmplPanda, TheWaypointPlannerFallsBackToOmplWhenItsDetourFails) {
  // the waypoint: the tool where the goal configuration holds it, behind the box
  const Robot torque_robot = panda_with_box({0.22, 0.22, 0.55}, 0.08);
  const Chain torque_chain(torque_robot, "attachment_site");
  ChainKinematics kin(torque_chain);
  const Pose X_goal = kin.update(goal);
  // the planner's own search cut short (the default one finds a way around this box): no global
  // branches, and detours only near the straight motion's middle, which is inside the box
  PlanOptions options;
  options.ik_branches = 0;
  options.detour_samples = 4;
  options.detour_radius = 0.05;
  options.ompl_fallback = false;
  WaypointPlanner without(torque_chain, options);
  const PlanResult blocked = without.plan(start, {X_goal});
  ASSERT_EQ(blocked.status, PlanStatus::blocked) << blocked.message;

  options.ompl_fallback = true;
  WaypointPlanner with(torque_chain, options);
  const PlanResult r = with.plan(start, {X_goal});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.waypoints.size(), 1u);
  EXPECT_TRUE(r.waypoints[0].detour);
  EXPECT_GE(r.waypoints[0].ompl_knots, 1);
  Eigen::VectorXd q(7), qd(7), qdd(7);
  r.trajectory.at(r.trajectory.duration(), q, qd, qdd);
  EXPECT_LT((kin.update(q).p - X_goal.p).norm(), 1e-4);
  CollisionChecker checker(torque_chain);
  for (int j = 0; j <= 2000; ++j) {
    r.trajectory.at(r.trajectory.duration() * j / 2000.0, q, qd, qdd);
    ASSERT_TRUE(checker.valid(q)) << j << ": " << checker.describe_last();
  }
}

TEST(OmplCollisionChecker, AgreesWithTheConfigurationCheckOnRandomStates) {
  // mj_kinematics + mj_collision against the checks' mj_fwdPosition, both through RobotContacts
  const Robot robot = panda_with_box({0.4, 0.0, 0.4}, 0.15);
  const Chain chain(robot, "attachment_site");
  CollisionChecker fast(chain);
  JointLimits limits;
  limits.max_velocity = limits.max_acceleration = Eigen::VectorXd::Ones(7);
  limits.max_torque = Eigen::VectorXd::Constant(7, std::numeric_limits<double>::infinity());
  CheckOptions options;
  options.min_singular_value = 0.0;
  ConfigurationChecker full(chain, limits, options);
  Random rng(7);
  int collisions = 0;
  for (int k = 0; k < 300; ++k) {
    Eigen::VectorXd q(7);
    for (int i = 0; i < 7; ++i) q[i] = uniform(rng, chain.lower()[i], chain.upper()[i]);
    const bool valid = fast.valid(q);
    const ConfigurationCheck& c = full.check(q);
    EXPECT_EQ(valid, c.ok()) << k << ": " << fast.describe_last() << " / " << full.describe(c);
    collisions += valid ? 0 : 1;
  }
  EXPECT_GT(collisions, 20);  // the comparison saw both answers
  EXPECT_LT(collisions, 280);
  EXPECT_EQ(fast.checks(), 300);
}

TEST(OmplCollisionChecker, AValidityCheckAllocatesNothing) {
  const Robot robot = panda_with_box({0.4, 0.0, 0.4}, 0.15);
  const Chain chain(robot, "attachment_site");
  CollisionChecker checker(chain);
  const Eigen::VectorXd free = home_q(robot);
  Eigen::VectorXd touching = free;
  touching[1] = 1.0;    // leaning into the box
  checker.valid(free);  // warm
  checker.valid(touching);
  const std::uint64_t before = test::malloc_calls();
  int collisions = 0;
  for (int j = 0; j < 20; ++j)
    collisions += (checker.valid(free) ? 0 : 1) + (checker.valid(touching) ? 0 : 1);
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_EQ(collisions, 20);  // both answers were given
}

}  // namespace
}  // namespace mjarm
