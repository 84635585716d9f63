#include "mjarm/trajectory/joint_move.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

// @p f throws an Error whose message holds @p part
template <class F>
void expect_move_error(F&& f, const std::string& part) {
  const std::string message = test::error_of(f);
  EXPECT_NE(message.find(part), std::string::npos) << message;
}

JointMoveRequest two_axes() {
  JointMoveRequest r;
  r.start = Eigen::Vector2d(0.0, 0.1);
  r.target = Eigen::Vector2d(0.5, 0.08);
  r.max_velocity = Eigen::Vector2d::Constant(0.18);
  r.max_acceleration = Eigen::Vector2d::Constant(0.9);
  return r;
}

TEST(JointMove, TheKindsTable) {
  ASSERT_EQ(profile_kinds().size(), 5u);
  for (const ProfileKindInfo& info : profile_kinds()) {
    EXPECT_EQ(std::string(to_string(info.kind)), info.name);
    EXPECT_EQ(&profile_kind_info(info.kind), &info);
  }
  EXPECT_EQ(std::string(to_string(ProfileKind::jerk_limited)), "jerk-limited");
  EXPECT_TRUE(profile_kind_info(ProfileKind::quintic).moving_ends);
  EXPECT_FALSE(profile_kind_info(ProfileKind::trapezoid).given_duration);
  EXPECT_TRUE(profile_kind_info(ProfileKind::jerk_limited).jerk_limit);
}

TEST(JointMove, TrapezoidIsTheSyncedTrapezoidWithItsExactPeaks) {
  const JointMove move(ProfileKind::trapezoid, two_axes());
  const SyncedTrapezoid reference(Eigen::Vector2d(0.0, 0.1), Eigen::Vector2d(0.5, 0.08), 0.18, 0.9);
  EXPECT_EQ(move.duration(), reference.duration());
  EXPECT_EQ(move.limiting_axis(), 0);
  ASSERT_TRUE(std::holds_alternative<SyncedTrapezoid>(move.profile()));
  // axis 0 cruises at its limit; axis 1 (stretched) stays below; the acceleration steps
  EXPECT_DOUBLE_EQ(move.peaks().velocity[0], 0.18);
  EXPECT_LT(move.peaks().velocity[1], 0.18);
  EXPECT_TRUE(std::isinf(move.peaks().jerk[0]));
  EXPECT_TRUE(move.violations().empty());
  // the defaults filled: at rest, no jerk limit
  EXPECT_TRUE(move.request().start_velocity.isZero());
  EXPECT_TRUE(move.request().max_jerk.hasNaN());
  TrajectorySample s;
  Eigen::Vector2d q, qd, qdd;
  for (double t : {0.0, 0.7, 1.9, move.duration()}) {
    move.at(t, s);
    reference.at(t, q, qd, qdd);
    EXPECT_EQ(s.position, Eigen::VectorXd(q));
    EXPECT_EQ(s.velocity, Eigen::VectorXd(qd));
  }
}

TEST(JointMove, QuinticTakesTheShortestDurationOrTheGivenOne) {
  JointMoveRequest r = two_axes();
  r.start_velocity = Eigen::Vector2d(0.1, -0.1);
  r.max_velocity = Eigen::Vector2d::Constant(0.5);
  r.max_acceleration = Eigen::Vector2d::Constant(2.0);
  const JointMove shortest(ProfileKind::quintic, r);
  const QuinticDuration d =
      shortest_quintic_duration({r.start, r.start_velocity, Eigen::Vector2d::Zero()},
                                {r.target, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()},
                                r.max_velocity, r.max_acceleration);
  ASSERT_TRUE(shortest.quintic_duration().has_value());
  EXPECT_EQ(shortest.duration(), d.duration);
  EXPECT_EQ(shortest.limiting_axis(), d.limiting_joint);
  EXPECT_LE(shortest.peaks().velocity.maxCoeff(), 0.5 * (1 + 1e-9));
  EXPECT_TRUE(shortest.violations().empty());
  TrajectorySample s;
  shortest.at(0.0, s);
  EXPECT_EQ(s.velocity[1], -0.1);

  r.duration = 0.5;  // too short: the peaks break the limits, and say so
  const JointMove given(ProfileKind::quintic, r);
  EXPECT_FALSE(given.quintic_duration().has_value());
  EXPECT_EQ(given.duration(), 0.5);
  EXPECT_EQ(given.limiting_axis(), -1);
  const std::vector<LimitViolation> broken = given.violations();
  ASSERT_FALSE(broken.empty());
  EXPECT_EQ(broken.front().axis, 0);
  EXPECT_EQ(broken.front().quantity, LimitViolation::Quantity::velocity);
  EXPECT_GT(broken.front().peak, broken.front().limit);
  EXPECT_EQ(broken.front().peak, given.peaks().velocity[0]);
}

TEST(JointMove, RampsFollowTheirSmoothRampTrajectory) {
  const JointMove move(ProfileKind::smootherstep, two_axes());
  const auto reference = SmoothRampTrajectory::within_limits(
      SmoothRamp::Kind::smootherstep, Eigen::Vector2d(0.0, 0.1), Eigen::Vector2d(0.5, 0.08),
      Eigen::Vector2d::Constant(0.18), Eigen::Vector2d::Constant(0.9));
  EXPECT_EQ(move.duration(), reference.duration());
  EXPECT_EQ(move.limiting_axis(), 0);
  EXPECT_EQ(move.peaks().jerk, reference.peak_jerk());
  JointMoveRequest r = two_axes();
  r.duration = 4.0;
  const JointMove step(ProfileKind::smoothstep, r);
  EXPECT_EQ(step.duration(), 4.0);
  EXPECT_EQ(step.limiting_axis(), -1);
}

TEST(JointMove, JerkLimitedBrakesAStartBeyondItsLimitsAndKeepsThemAfterward) {
  JointMoveRequest r = two_axes();
  r.start_velocity = Eigen::Vector2d(0.35, 0.0);  // beyond 0.3
  r.start_acceleration = Eigen::Vector2d(0.5, -0.3);
  r.max_velocity = Eigen::Vector2d::Constant(0.3);
  r.max_acceleration = Eigen::Vector2d::Constant(1.0);
  r.max_jerk = Eigen::Vector2d::Constant(8.0);
  const JointMove move(ProfileKind::jerk_limited, r);
  const auto& otg = std::get<JerkLimitedGenerator>(move.profile());
  EXPECT_EQ(move.duration(), otg.duration());
  EXPECT_GT(otg.brake_phases(0), 0);
  EXPECT_LE(move.peaks().velocity[0], 0.3 * (1 + 1e-9));  // after the brake
  EXPECT_LE(move.peaks().jerk.maxCoeff(), 8.0 * (1 + 1e-12));
  EXPECT_TRUE(move.violations().empty());
  TrajectorySample s;
  move.at(move.duration(), s);
  EXPECT_NEAR(s.position[1], 0.08, 1e-9);
  move.at(move.duration() + 1.0, s);
  EXPECT_TRUE(s.jerk.isZero());
}

TEST(JointMove, BadRequestsAreRefusedNamingWhatIsWrong) {
  JointMoveRequest r = two_axes();
  r.start_velocity = Eigen::Vector2d(0.1, 0.0);
  expect_move_error([&] { (void)JointMove(ProfileKind::smoothstep, r); }, "rest to rest");
  r = two_axes();
  r.duration = 1.0;
  expect_move_error([&] { (void)JointMove(ProfileKind::trapezoid, r); }, "not a given one");
  r.duration = -1.0;
  expect_move_error([&] { (void)JointMove(ProfileKind::quintic, r); }, "positive and finite");
  r = two_axes();
  expect_move_error([&] { (void)JointMove(ProfileKind::jerk_limited, r); }, "needs a jerk limit");
  r.max_acceleration[1] = 0.0;
  expect_move_error([&] { (void)JointMove(ProfileKind::trapezoid, r); }, "axis 1");
  r = two_axes();
  r.target = Eigen::Vector3d::Zero();
  expect_move_error([&] { (void)JointMove(ProfileKind::trapezoid, r); }, "the target has 3");
  r = two_axes();
  r.start[0] = std::numeric_limits<double>::infinity();
  expect_move_error([&] { (void)JointMove(ProfileKind::quintic, r); }, "finite");
  // no quintic duration keeps a start beyond the velocity limit
  r = two_axes();
  r.start_velocity = Eigen::Vector2d(0.5, 0.0);
  expect_move_error([&] { (void)JointMove(ProfileKind::quintic, r); },
                    "start beyond limits (axis 0, velocity)");
  // the generator's own refusal: a target velocity beyond its limit
  r = two_axes();
  r.target_velocity = Eigen::Vector2d(0.5, 0.0);
  r.max_jerk = Eigen::Vector2d::Constant(5.0);
  expect_move_error([&] { (void)JointMove(ProfileKind::jerk_limited, r); },
                    "target velocity 0.5 exceeds its limit");
}

}  // namespace
}  // namespace mjarm
