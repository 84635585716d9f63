#include "mjarm/trajectory/trapezoid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/random.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(Trapezoid, ClassicDefaultsAndPhases) {
  // 0.5 m at 0.18 m/s and 0.9 m/s²: t_acc = 0.2 s, d_acc = 0.018 m, cruise 0.464 m over 2.5778 s
  const TrapezoidProfile p = trap_profile(0.5);
  EXPECT_FALSE(p.triangular());
  EXPECT_DOUBLE_EQ(p.acceleration_time(), 0.2);
  EXPECT_NEAR(p.cruise_time(), (0.5 - 0.036) / 0.18, 1e-15);
  EXPECT_NEAR(p.duration(), 0.4 + (0.5 - 0.036) / 0.18, 1e-15);
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 0.18);
  // the phases: 1/2·a·t² while accelerating, v_max cruising, symmetric braking
  EXPECT_NEAR(p.at(0.1).position, 0.5 * 0.9 * 0.01, 1e-15);
  EXPECT_NEAR(p.at(0.1).velocity, 0.09, 1e-15);
  EXPECT_EQ(p.at(0.1).acceleration, 0.9);
  EXPECT_EQ(p.at(1.0).acceleration, 0.0);
  EXPECT_NEAR(p.at(1.0).velocity, 0.18, 1e-15);
  EXPECT_EQ(p.at(p.duration() - 0.1).acceleration, -0.9);
  EXPECT_NEAR(p.at(p.duration() / 2).position, 0.25, 1e-15);
  EXPECT_NEAR(trap_frac(p, p.duration() / 2), 0.5, 1e-15);
}

TEST(Trapezoid, BecomesATriangleWhenTheCruiseSpeedIsNotReached) {
  // 2·d_acc = 0.036 m > 0.02 m
  const TrapezoidProfile p = trap_profile(0.02);
  EXPECT_TRUE(p.triangular());
  EXPECT_EQ(p.cruise_time(), 0.0);
  EXPECT_NEAR(p.acceleration_time(), std::sqrt(0.02 / 0.9), 1e-15);
  EXPECT_NEAR(p.peak_velocity(), 0.9 * std::sqrt(0.02 / 0.9), 1e-15);
  EXPECT_LT(p.peak_velocity(), 0.18);
  EXPECT_NEAR(p.at(p.duration() / 2).velocity, p.peak_velocity(), 1e-12);
  // the boundary case 2·d_acc = d is a trapezoid with no cruise
  const TrapezoidProfile edge = trap_profile(0.036);
  EXPECT_FALSE(edge.triangular());
  EXPECT_NEAR(edge.cruise_time(), 0.0, 1e-15);
}

TEST(Trapezoid, ClampedOutsideTheDurationAndContinuousInside) {
  for (const double d : {0.02, 0.3, 2.0}) {
    const TrapezoidProfile p(d, 0.5, 2.0);
    EXPECT_EQ(p.at(-1.0).position, 0.0);
    EXPECT_EQ(p.at(kNan).fraction, 0.0);
    EXPECT_EQ(p.at(p.duration() + 1.0).position, d);
    EXPECT_EQ(p.at(p.duration() + 1.0).velocity, 0.0);
    EXPECT_EQ(p.fraction(1e9), 1.0);
    // derivatives agree with finite differences; the position never decreases
    const double h = 1e-7;
    double last = 0.0;
    for (int k = 1; k < 400; ++k) {
      const double t = p.duration() * k / 400.0;
      const auto s = p.at(t);
      EXPECT_GE(s.position, last);
      last = s.position;
      EXPECT_NEAR((p.at(t + h).position - p.at(t - h).position) / (2 * h), s.velocity, 1e-6);
      EXPECT_LE(s.velocity, 0.5 + 1e-15);
      EXPECT_NEAR(s.fraction, s.position / d, 1e-15);
    }
  }
}

TEST(Trapezoid, ZeroDistanceIsAValidZeroDurationProfile) {
  const TrapezoidProfile p = trap_profile(0.0);
  EXPECT_EQ(p.duration(), 0.0);
  EXPECT_EQ(p.at(0.0).fraction, 1.0);
  EXPECT_EQ(p.at(0.0).velocity, 0.0);
  EXPECT_EQ(p.at(-0.1).fraction, 0.0);
}

TEST(Trapezoid, RejectsBadInput) {
  EXPECT_THROW(trap_profile(-0.1), Error);
  EXPECT_THROW(trap_profile(kNan), Error);
  EXPECT_THROW(trap_profile(kInf), Error);
  EXPECT_THROW(trap_profile(0.1, 0.0), Error);
  EXPECT_THROW(trap_profile(0.1, -0.18), Error);
  EXPECT_THROW(trap_profile(0.1, kNan), Error);
  EXPECT_THROW(trap_profile(0.1, 0.18, -0.9), Error);
  EXPECT_THROW(trap_profile(0.1, 0.18, kInf), Error);
  EXPECT_NE(test::error_of([] { trap_profile(0.1, 0.18, 0.0); }).find("max acceleration"),
            std::string::npos);
  // finite input whose duration overflows: an error, not T = inf
  EXPECT_NE(test::error_of([] { trap_profile(1e300, 1e-300, 1e-300); }).find("longer than"),
            std::string::npos);
  EXPECT_THROW(SyncedTrapezoid(Eigen::Vector2d(0, 0), Eigen::Vector2d(1e300, 1), 1e-300, 1.0),
               Error);
  // a tiny distance is a valid, tiny profile
  const TrapezoidProfile tiny = trap_profile(1e-300);
  EXPECT_GT(tiny.duration(), 0.0);
  EXPECT_EQ(tiny.fraction(tiny.duration()), 1.0);
}

TEST(SyncedTrapezoid, EveryAxisFinishesTogetherWithinItsLimits) {
  mjarm::Random rng(11);
  const auto pos = [](mjarm::Random& r) { return mjarm::uniform(r, -2.0, 2.0); };
  const auto lim = [](mjarm::Random& r) { return mjarm::uniform(r, 0.2, 3.0); };
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 1 + trial % 7;
    Eigen::VectorXd q0(n), q1(n), v(n), a(n);
    for (int i = 0; i < n; ++i) {
      q0[i] = pos(rng);
      q1[i] = i == 1 ? q0[i] : pos(rng);  // axis 1 does not move
      v[i] = lim(rng);
      a[i] = lim(rng);
    }
    const SyncedTrapezoid move(q0, q1, v, a);
    double longest = 0.0;
    for (int i = 0; i < n; ++i) {
      longest = std::max(longest, TrapezoidProfile(std::abs(q1[i] - q0[i]), v[i], a[i]).duration());
    }
    EXPECT_DOUBLE_EQ(move.duration(), longest);
    Eigen::VectorXd q(n), qd(n), qdd(n);
    const double T = move.duration();
    for (int k = 0; k <= 200; ++k) {
      const double t = T * k / 200.0;
      move.at(t, q, qd, qdd);
      for (int i = 0; i < n; ++i) {
        EXPECT_LE(std::abs(qd[i]), v[i] * (1 + 1e-12));
        EXPECT_LE(std::abs(qdd[i]), a[i] * (1 + 1e-12));
        // between the start and the goal, moving towards the goal
        EXPECT_LE(std::min(q0[i], q1[i]) - 1e-12, q[i]);
        EXPECT_LE(q[i], std::max(q0[i], q1[i]) + 1e-12);
        EXPECT_GE(qd[i] * (q1[i] - q0[i]), 0.0);
      }
    }
    // every axis is still moving just before T and at its goal at T
    move.at(T * (1 - 1e-3), q, qd, qdd);
    for (int i = 0; i < n; ++i)
      if (q1[i] != q0[i]) {
        EXPECT_GT(std::abs(qd[i]), 0.0) << i;
      }
    move.at(T, q, qd, qdd);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(q[i], q1[i], 1e-12);
    EXPECT_EQ(qd.norm(), 0.0);
    EXPECT_EQ(move.fraction(T), 1.0);
  }
}

TEST(SyncedTrapezoid, AFasterAxisUsesScaledLimitsOfTheSameShape) {
  // axis 0 needs 1.5 s at its limits; axis 1 alone (a triangle) takes √½ s: stretched by λ ≈ 0.47
  const SyncedTrapezoid move(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0.25), 1.0, 2.0);
  EXPECT_EQ(move.limiting_axis(), 0u);
  EXPECT_NEAR(move.duration(), 1.5, 1e-15);  // t_acc 0.5, cruise 0.5
  const double lambda = move.time_scale(1);
  EXPECT_NEAR(lambda, move.axis(1).duration() / 1.5, 1e-15);
  Eigen::Vector2d q, qd, qdd;
  move.at(0.1, q, qd, qdd);
  EXPECT_NEAR(qdd[1], lambda * lambda * 2.0, 1e-12);
  move.at(0.75, q, qd, qdd);
  EXPECT_NEAR(qd[1], lambda * move.axis(1).peak_velocity(), 1e-12);  // the triangle's peak
  EXPECT_NEAR(q[1], 0.125, 1e-12);
}

TEST(SyncedTrapezoid, RejectsBadInput) {
  const Eigen::Vector2d a(0, 0), b(1, 1);
  EXPECT_THROW(SyncedTrapezoid(a, Eigen::Vector3d(1, 1, 1), 1.0, 1.0), Error);
  EXPECT_THROW(SyncedTrapezoid(Eigen::VectorXd(), Eigen::VectorXd(), 1.0, 1.0), Error);
  EXPECT_THROW(SyncedTrapezoid(a, Eigen::Vector2d(1, kNan), 1.0, 1.0), Error);
  EXPECT_THROW(SyncedTrapezoid(a, b, Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)), Error);
  EXPECT_THROW(SyncedTrapezoid(a, b, 1.0, -1.0), Error);
  EXPECT_NE(test::error_of([&] {
              SyncedTrapezoid(a, b, Eigen::Vector2d(1, 1), Eigen::Vector2d(1, kInf));
            }).find("axis 1 max acceleration"),
            std::string::npos);
  const SyncedTrapezoid move(a, b, 1.0, 1.0);
  Eigen::VectorXd q(3), qd(2), qdd(2);
  EXPECT_THROW(move.at(0.1, q, qd, qdd), Error);
  // start equal to goal: zero duration, at the goal at once
  const SyncedTrapezoid still(b, b, 1.0, 1.0);
  EXPECT_EQ(still.duration(), 0.0);
  Eigen::VectorXd p(2), pd(2), pdd(2);
  still.at(0.0, p, pd, pdd);
  EXPECT_EQ(p, Eigen::VectorXd(b));
}

}  // namespace
}  // namespace mjarm
