#include "mjarm/trajectory/jerk_limited_brake.hpp"

#include <gtest/gtest.h>

#include <random>

namespace mjarm {
namespace {

TEST(JerkLimitedBrake, StatesInsideTheLimitsNeedNoBrake) {
  const JerkLimits l{1.0, 2.0, 4.0};
  JerkProfile p;
  p.reset({0.0, 0.5, 1.0});
  ASSERT_TRUE(append_brake({0.0, 0.5, 1.0}, l, p));
  EXPECT_EQ(p.size(), 0);
  // v = 0.9 with a = 1.5 overshoots: 0.9 + 1.5²/8 > 1
  EXPECT_FALSE(is_startable({0.0, 0.9, 1.5}, l));
  EXPECT_TRUE(is_reachable({0.0, 0.9, 1.5}, l));
  EXPECT_FALSE(is_reachable({0.0, 0.9, -1.5}, l));
}

TEST(JerkLimitedBrake, BringsAnyStateBackWithinFourPhases) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int braked = 0;
  for (int k = 0; k < 20000; ++k) {
    const JerkLimits l{0.5 + 2.0 * (u(rng) + 1.0), 0.5 + 2.0 * (u(rng) + 1.0),
                       2.0 + 10.0 * (u(rng) + 1.0)};
    if (l.acceleration * l.acceleration / (2.0 * l.jerk) > l.velocity) continue;
    const KinematicState s{0.0, 2.0 * l.velocity * u(rng), 2.0 * l.acceleration * u(rng)};
    JerkProfile p;
    p.reset(s);
    ASSERT_TRUE(append_brake(s, l, p)) << k;
    EXPECT_LE(p.size(), 4);
    EXPECT_TRUE(is_startable(p.end(), l)) << k;
    for (int i = 0; i < p.size(); ++i) EXPECT_LE(std::abs(p.jerk(i)), l.jerk);
    braked += p.size() > 0 ? 1 : 0;
  }
  EXPECT_GT(braked, 5000);
}

TEST(JerkLimitedBrake, TooFastBrakesAtFullDecelerationToTheLimit) {
  const JerkLimits l{1.0, 1.0, 10.0};
  const KinematicState s{0.0, 3.0, 0.0};
  JerkProfile p;
  p.reset(s);
  ASSERT_TRUE(append_brake(s, l, p));
  ASSERT_EQ(p.size(), 2);
  EXPECT_EQ(p.jerk(0), -10.0);
  EXPECT_NEAR(p.phase_duration(0), 0.1, 1e-15);  // a: 0 → −1
  EXPECT_NEAR(p.end().v, 1.0, 1e-12);
  EXPECT_NEAR(p.end().a, -1.0, 1e-15);
  EXPECT_NEAR(p.duration(), 0.1 + (3.0 - 0.05 - 1.0) / 1.0, 1e-12);
}

}  // namespace
}  // namespace mjarm
