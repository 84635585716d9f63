#include "mjarm/trajectory/smooth_ramp_trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

// @p f throws an Error whose message holds @p part
template <class F>
void expect_ramp_error(F&& f, const std::string& part) {
  const std::string message = test::error_of(f);
  EXPECT_NE(message.find(part), std::string::npos) << message;
}

const Eigen::Vector3d kRampStart(0.0, 1.0, -0.5);
const Eigen::Vector3d kRampGoal(0.4, 0.7, -0.5);  // axis 2 does not move

TEST(SmoothRampTrajectory, EveryAxisFollowsTheOneRamp) {
  for (const auto kind : {SmoothRamp::Kind::smoothstep, SmoothRamp::Kind::smootherstep}) {
    const SmoothRampTrajectory move(kind, kRampStart, kRampGoal, 2.0);
    const SmoothRamp ramp(kind, 2.0);
    EXPECT_EQ(move.duration(), 2.0);
    EXPECT_EQ(move.dofs(), 3);
    EXPECT_EQ(move.limiting_axis(), -1);  // the duration was given
    TrajectorySample s;
    for (double t : {-1.0, 0.0, 0.3, 1.0, 1.7, 2.0, 5.0}) {
      move.at(t, s);
      const RampSample r = ramp.at(t);
      for (int i = 0; i < 3; ++i) {
        const double d = kRampGoal[i] - kRampStart[i];
        EXPECT_EQ(s.position[i], kRampStart[i] + r.s * d) << t;
        EXPECT_EQ(s.velocity[i], r.ds * d) << t;
        EXPECT_EQ(s.acceleration[i], r.dds * d) << t;
        EXPECT_EQ(s.jerk[i], r.ddds * d) << t;
      }
    }
    move.at(2.0, s);
    EXPECT_EQ(s.position, Eigen::VectorXd(kRampGoal));
    EXPECT_TRUE(s.velocity.isZero());
  }
}

TEST(SmoothRampTrajectory, WithinLimitsTheSlowestAxisSetsTheDurationAndMeetsItsLimit) {
  const Eigen::Vector3d v_max(0.5, 0.05, 1.0), a_max(2.0, 2.0, 2.0);
  const auto move = SmoothRampTrajectory::within_limits(SmoothRamp::Kind::smoothstep, kRampStart,
                                                        kRampGoal, v_max, a_max);
  // axis 1: 0.3 at 0.05 u/s under a peak slope of 1.5 → 9 s; axis 0 needs 1.2 s
  EXPECT_EQ(move.limiting_axis(), 1);
  EXPECT_DOUBLE_EQ(move.duration(), 1.5 * 0.3 / 0.05);
  EXPECT_NEAR(move.peak_velocity()[1], 0.05, 1e-15);
  EXPECT_LE(move.peak_velocity()[0], v_max[0]);
  EXPECT_EQ(move.peak_velocity()[2], 0.0);
  // the peaks are those of the samples
  TrajectorySample s;
  double peak_v = 0.0, peak_a = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    move.at(move.duration() * k / 2000.0, s);
    peak_v = std::max(peak_v, std::abs(s.velocity[1]));
    peak_a = std::max(peak_a, std::abs(s.acceleration[1]));
  }
  EXPECT_NEAR(peak_v, move.peak_velocity()[1], 1e-12);
  EXPECT_NEAR(peak_a, move.peak_acceleration()[1], 1e-12);
  EXPECT_DOUBLE_EQ(move.peak_jerk()[1], 12.0 * 0.3 / std::pow(move.duration(), 3));
}

TEST(SmoothRampTrajectory, NothingToMoveTakesNoTime) {
  const auto move =
      SmoothRampTrajectory::within_limits(SmoothRamp::Kind::smootherstep, kRampStart, kRampStart,
                                          Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones());
  EXPECT_EQ(move.duration(), 0.0);
  EXPECT_EQ(move.limiting_axis(), -1);
  TrajectorySample s;
  move.at(0.5, s);
  EXPECT_EQ(s.position, Eigen::VectorXd(kRampStart));
  EXPECT_TRUE(s.velocity.isZero() && s.acceleration.isZero() && s.jerk.isZero());
  EXPECT_TRUE(move.peak_velocity().isZero());
}

TEST(SmoothRampTrajectory, BadInputIsRefusedNamingIt) {
  const auto kind = SmoothRamp::Kind::smoothstep;
  expect_ramp_error(
      [&] { (void)SmoothRampTrajectory(kind, kRampStart, Eigen::Vector2d(0, 1), 1.0); },
      "same number of axes");
  expect_ramp_error([&] { (void)SmoothRampTrajectory(kind, kRampStart, kRampGoal, 0.0); },
                    "must be positive");
  expect_ramp_error(
      [&] {
        (void)SmoothRampTrajectory(kind, kRampStart, kRampGoal,
                                   std::numeric_limits<double>::infinity());
      },
      "finite");
  Eigen::Vector3d bad = kRampGoal;
  bad[2] = std::nan("");
  expect_ramp_error([&] { (void)SmoothRampTrajectory(kind, kRampStart, bad, 1.0); }, "axis 2");
  expect_ramp_error(
      [&] {
        SmoothRampTrajectory::within_limits(kind, kRampStart, kRampGoal, Eigen::Vector3d(1, 0, 1),
                                            Eigen::Vector3d::Ones());
      },
      "axis 1: the limits must be positive");
}

}  // namespace
}  // namespace mjarm
