#include "mjarm/planning/cartesian_path.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "ik/malloc_counter.hpp"
#include "mjarm/ik/global_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/so3.hpp"
#include "planning/planning_support.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using planning_test::home_q;
using test::error_of;

/// Distance of @p p from the segment line through @p a and @p b, and its parameter along it.
double off_line(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                double* along = nullptr) {
  const Eigen::Vector3d u = (b - a).normalized();
  const double s = (p - a).dot(u);
  if (along != nullptr) *along = s / (b - a).norm();
  return (p - a - s * u).norm();
}

struct CartesianPanda : ::testing::Test {
  Robot robot = Robot::bundled("panda");
  Chain chain{robot, "attachment_site"};
  Eigen::VectorXd home = home_q(robot);
  ChainKinematics kin{chain};
  Pose X_home = kin.update(home);
};

TEST_F(CartesianPanda, AFreeLineIsFollowedWholeOnTheLineAndTheSlerp) {
  // 20 cm sideways while turning 0.3 rad about the world z axis
  Pose goal = X_home;
  goal.p.y() += 0.2;
  goal.R = so3::exp(Eigen::Vector3d(0, 0, 0.3)) * X_home.R;
  const CartesianPathResult r = cartesian_path(chain, home, goal);
  ASSERT_TRUE(r.complete()) << r.message;
  EXPECT_EQ(r.fraction, 1.0);
  EXPECT_EQ(r.steps, 40);  // max(0.2 m / 5 mm, 0.3 rad / 0.02 rad) = max(40, 15)
  ASSERT_EQ(r.knot_count(), 41);
  ASSERT_EQ(r.poses.size(), 41u);
  EXPECT_EQ(r.stopped_at_step, -1);
  const double tolerance = CartesianPathOptions{}.ik.position_tolerance;
  const Eigen::Quaterniond q0(X_home.R), q1(goal.R);
  for (int k = 0; k <= 40; ++k) {
    // FK of every knot, recomputed here, lies on the line at k/40 and on the slerp (Eigen's)
    const Pose& X = kin.update(r.knots.col(k));
    const Eigen::Vector3d p_line = X_home.p + (k / 40.0) * (goal.p - X_home.p);
    EXPECT_LT((X.p - p_line).norm(), tolerance + 1e-12) << k;
    const Eigen::Matrix3d R_slerp = q0.slerp(k / 40.0, q1).toRotationMatrix();
    EXPECT_LT(so3::angle(R_slerp.transpose() * X.R), 1e-5 + 1e-12) << k;
    EXPECT_TRUE(X.is_approx(r.poses[static_cast<std::size_t>(k)], 1e-12)) << k;
    EXPECT_TRUE(chain.within_limits(r.knots.col(k)));
    if (k > 0) {
      // small joint steps (an arm of ~0.8 m turns ~0.01 rad for 5 mm)
      EXPECT_LT((r.knots.col(k) - r.knots.col(k - 1)).cwiseAbs().maxCoeff(), 0.05) << k;
      EXPECT_NEAR((r.poses[k].p - r.poses[k - 1].p).norm(), 0.005, 2 * tolerance) << k;
    }
  }
  EXPECT_LE(r.max_position_error, tolerance);
  EXPECT_LE(r.max_orientation_error, 1e-5);
  EXPECT_LT(r.max_joint_step, 0.05);
}

TEST_F(CartesianPanda, WaypointsAreFollowedInOrderAndTheirStepsAddUp) {
  Pose a = X_home, b = X_home;
  a.p.x() += 0.1;  // 20 steps
  b.p = a.p;
  b.p.z() -= 0.06;  // 12 steps
  Pose c = b;
  c.R = so3::exp(Eigen::Vector3d(0, 0, 0.4)) * b.R;  // turning in place: 20 steps of 0.02 rad
  // (the relative jump test compares joint motion per unit of Cartesian step across segments of
  // different step lengths and kinds: none of these is a jump)
  const CartesianPathResult r = cartesian_path(chain, home, {a, b, c});
  ASSERT_TRUE(r.complete()) << r.message;
  EXPECT_EQ(r.steps, 52);
  ASSERT_EQ(r.knot_count(), 53);
  EXPECT_LT((r.poses[20].p - a.p).norm(), 1e-5);  // the corners are knots
  EXPECT_LT((r.poses[32].p - b.p).norm(), 1e-5);
  for (int k = 21; k <= 32; ++k) EXPECT_LT(off_line(r.poses[k].p, a.p, b.p), 1e-5) << k;
  for (int k = 33; k <= 52; ++k) {
    EXPECT_LT((r.poses[k].p - b.p).norm(), 1e-5) << k;
    EXPECT_NEAR(so3::angle(b.R.transpose() * r.poses[k].R), 0.02 * (k - 32), 1e-5) << k;
  }
  // a waypoint where E already is adds no step
  const CartesianPathResult same = cartesian_path(chain, home, {X_home, a});
  EXPECT_EQ(same.steps, 20);
  EXPECT_TRUE(same.complete());
}

TEST_F(CartesianPanda, ALineIntoABoxStopsAtTheLastCollisionFreeKnot) {
  // the box's face towards the arm is at y = 0.15; the flange moves along +y at z = 0.59
  const Robot boxed = planning_test::panda_with_box({0.307, 0.2, 0.55}, 0.05);
  const Chain box_chain(boxed, "attachment_site");
  Pose goal = X_home;
  goal.p.y() = 0.3;
  const CartesianPathResult r = cartesian_path(box_chain, home, goal);
  ASSERT_EQ(r.status, CartesianPathStatus::partial_collision) << r.message;
  EXPECT_GT(r.fraction, 0.1);
  EXPECT_LT(r.fraction, 0.5);  // stopped before the face, 0.15 of the 0.3 m line
  EXPECT_EQ(r.fraction, static_cast<double>(r.knot_count() - 1) / r.steps);
  EXPECT_EQ(r.stopped_at_step, r.knot_count());
  EXPECT_EQ(r.check.failure, CheckFailure::collision);
  EXPECT_NE(r.message.find("touches geom 'obstacle'"), std::string::npos) << r.message;
  EXPECT_LT(r.poses.back().p.y(), 0.15);
  // every knot kept is free, judged by a checker of its own
  ConfigurationChecker checker(box_chain, joint_limits_from_model(box_chain, home));
  for (int k = 0; k < r.knot_count(); ++k) EXPECT_TRUE(checker.check(r.knots.col(k)).ok()) << k;
  // with the contacts off the same line goes through the box: some knot touches it
  CartesianPathOptions blind;
  blind.check_collisions = false;
  const CartesianPathResult through = cartesian_path(box_chain, home, goal, blind);
  ASSERT_TRUE(through.complete()) << through.message;
  int first_touching = -1;
  for (int k = 0; k < through.knot_count() && first_touching < 0; ++k)
    if (checker.check(through.knots.col(k)).failure == CheckFailure::collision) first_touching = k;
  ASSERT_GT(first_touching, 0);
  // a start inside the box follows nothing
  const CartesianPathResult stuck =
      cartesian_path(box_chain, through.knots.col(first_touching), X_home);
  EXPECT_EQ(stuck.status, CartesianPathStatus::partial_collision);
  EXPECT_EQ(stuck.fraction, 0.0);
  EXPECT_EQ(stuck.knot_count(), 0);
  EXPECT_EQ(stuck.stopped_at_step, 0);
  EXPECT_NE(stuck.message.find("the start fails a check"), std::string::npos) << stuck.message;
}

TEST_F(CartesianPanda, ALineOutOfTheWorkspaceStopsWhereTheGlobalIkFindsTheReach) {
  Pose goal = X_home;
  goal.p.x() = 1.2;  // the panda reaches ~0.85 m from its shoulder; pointing down much less
  const CartesianPathResult r = cartesian_path(chain, home, goal);
  ASSERT_EQ(r.status, CartesianPathStatus::partial_ik_failure) << r.message;
  EXPECT_NE(r.message.find("no IK solution"), std::string::npos) << r.message;
  const double x_stop = r.poses.back().p.x();
  EXPECT_NEAR(r.fraction, (x_stop - X_home.p.x()) / (1.2 - X_home.p.x()), 1e-4);
  // the reach along this line by bisection with the global IK (restarts from random seeds,
  // bounded by count, not by time)
  GlobalIkOptions g;
  g.timeout = std::chrono::seconds(1000);
  g.max_restarts = 200;
  GlobalIk global(chain, g);
  double reached = X_home.p.x(), missed = 1.2;
  for (int i = 0; i < 10; ++i) {
    Pose X = X_home;
    X.p.x() = 0.5 * (reached + missed);
    (global.solve(X, home).ok() ? reached : missed) = X.p.x();
  }
  // measured: the path stops at 0.706 m, the global IK reaches 0.708 m
  EXPECT_NEAR(x_stop, reached, 0.01);
  EXPECT_LE(x_stop, missed);
}

TEST(CartesianUr5e, AWristFlipIsAJumpWhenDetectionIsOn) {
  // a straight line between two poses on both sides of the wrist singularity (wrist_2 = 0):
  // the local IK seeded at each knot gets across only by flipping wrist_1 in one step
  const Robot robot = Robot::bundled("ur5e");
  const Chain chain(robot, "attachment_site");
  ChainKinematics kin(chain);
  Eigen::VectorXd qa(6), qb(6);
  qa << 0.3, -1.2, 1.5, -1.9, 0.2, 0.0;
  qb << 0.3, -1.2, 1.5, -1.9, -0.2, 0.0;
  const Pose A = kin.update(qa);
  const Pose B = kin.update(qb);
  CartesianPathOptions off;
  off.checks.min_singular_value = 0.0;  // the σmin check would stop it first
  off.jump_factor = 0.0;
  off.jump_revolute = 0.0;
  const CartesianPathResult blind = cartesian_path(chain, qa, B, off);
  ASSERT_TRUE(blind.complete()) << blind.message;
  EXPECT_GT(blind.max_joint_step, 1.0);  // measured 1.45 rad
  // the joint-space motion of that step leaves the line by far: it is not a step of the path
  int worst = 1;
  for (int k = 1; k < blind.knot_count(); ++k)
    if ((blind.knots.col(k) - blind.knots.col(k - 1)).norm() >
        (blind.knots.col(worst) - blind.knots.col(worst - 1)).norm())
      worst = k;
  const Eigen::VectorXd middle = 0.5 * (blind.knots.col(worst) + blind.knots.col(worst - 1));
  EXPECT_GT(off_line(kin.update(middle).p, A.p, B.p), 0.01);

  for (int test = 0; test < 3; ++test) {
    CartesianPathOptions on = off;
    if (test != 1) on.jump_revolute = CartesianPathOptions{}.jump_revolute;  // 0: absolute
    if (test != 0) on.jump_factor = CartesianPathOptions{}.jump_factor;      // 1: relative
    const CartesianPathResult r = cartesian_path(chain, qa, B, on);
    ASSERT_EQ(r.status, CartesianPathStatus::partial_jump) << test << ": " << r.message;
    EXPECT_EQ(r.stopped_at_step, worst) << test;
    EXPECT_GT(r.fraction, 0.3) << test;
    EXPECT_LT(r.fraction, 0.6) << test;
    EXPECT_LT(r.max_joint_step, 0.5) << test;
    for (int k = 0; k < r.knot_count(); ++k)
      EXPECT_LT(off_line(r.poses[k].p, A.p, B.p), 1e-5) << test << " " << k;
    EXPECT_NE(r.message.find(test == 1 ? "times the mean" : "joint 'wrist_1' moves"),
              std::string::npos)
        << r.message;
  }
  // with the σmin check on (the default) the singularity itself stops it
  CartesianPathOptions sigma = off;
  sigma.checks.min_singular_value = 0.02;
  const CartesianPathResult near = cartesian_path(chain, qa, B, sigma);
  EXPECT_EQ(near.status, CartesianPathStatus::partial_limits) << near.message;
  EXPECT_EQ(near.check.failure, CheckFailure::singular);
}

TEST_F(CartesianPanda, StepsAllocateNothing) {
  // a path's allocations (its result: knots, poses, segments, message) do not grow with its
  // steps: the IK, the jump test and the checks of every step reuse the planner's buffers
  CartesianPathPlanner planner(chain);
  const auto allocations = [&](double length) {
    Pose goal = X_home;
    goal.p.y() += length;
    planner.follow(home, {goal});  // warm
    const std::uint64_t before = test::malloc_calls();
    const CartesianPathResult r = planner.follow(home, {goal});
    const std::uint64_t used = test::malloc_calls() - before;
    EXPECT_TRUE(r.complete()) << r.message;
    return used;
  };
  EXPECT_EQ(allocations(0.05), allocations(0.2));  // 10 and 40 steps
}

TEST_F(CartesianPanda, BadInputIsRefusedNamingTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Pose goal = X_home;
  goal.p.y() += 0.1;
  Pose bad = goal;
  bad.p.x() = nan;
  EXPECT_NE(error_of([&] {
              cartesian_path(chain, home, {goal, bad});
            }).find("waypoint 1"),
            std::string::npos);
  Pose skew = goal;
  skew.R(0, 0) = 2.0;
  EXPECT_NE(error_of([&] { cartesian_path(chain, home, skew); }).find("waypoint 0"),
            std::string::npos);
  Eigen::VectorXd q = home;
  q[3] = nan;
  EXPECT_NE(error_of([&] { cartesian_path(chain, q, goal); }).find("q_start"), std::string::npos);
  EXPECT_NE(
      error_of([&] { cartesian_path(chain, Eigen::VectorXd::Zero(3), goal); }).find("q_start"),
      std::string::npos);
  EXPECT_NE(error_of([&] { cartesian_path(chain, home, std::vector<Pose>{}); }).find("no waypoint"),
            std::string::npos);
  CartesianPathOptions o;
  o.max_step = 0.0;
  EXPECT_NE(error_of([&] {
              cartesian_path(chain, home, goal, o);
            }).find("cartesian path: max_step must be positive"),
            std::string::npos);
  o = {};
  o.max_rotation_step = nan;
  EXPECT_NE(error_of([&] { cartesian_path(chain, home, goal, o); }).find("max_rotation_step"),
            std::string::npos);
  o = {};
  o.jump_factor = 0.5;
  EXPECT_NE(error_of([&] { cartesian_path(chain, home, goal, o); }).find("jump_factor"),
            std::string::npos);
  o = {};
  o.checks.collision_margin = -1.0;
  EXPECT_NE(error_of([&] { cartesian_path(chain, home, goal, o); }).find("checks.collision_margin"),
            std::string::npos);
  // a waypoint 100 km away would take 2·10⁷ steps: refused before any IK
  Pose far = goal;
  far.p.x() = 1e5;
  EXPECT_NE(error_of([&] { cartesian_path(chain, home, far); }).find("max_steps"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
