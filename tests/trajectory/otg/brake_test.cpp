#include "mjarm/trajectory/otg/brake.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/random.hpp"

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

// Any state, for any limits — also those where a_max²/(2 j_max) > 2 v_max, in which a hold at
// −a_max until v = v_max would overshoot −v_max afterwards: at most 3 phases at full jerk or zero
// jerk end in a startable state, on the limit v = v_max when the velocity had to come down.
TEST(JerkLimitedBrake, BringsAnyStateBackForAnyLimits) {
  mjarm::Random rng(3);
  const auto u = [](mjarm::Random& r) { return mjarm::uniform(r, -1.0, 1.0); };
  auto log_uniform = [&](double lo, double hi) {
    return lo * std::pow(hi / lo, 0.5 * (u(rng) + 1.0));
  };
  int braked = 0, strong = 0;
  for (int k = 0; k < 20000; ++k) {
    const JerkLimits l{log_uniform(0.05, 5.0), log_uniform(0.1, 20.0), log_uniform(0.2, 50.0)};
    const KinematicState s{0.0, 3.0 * l.velocity * u(rng), 3.0 * l.acceleration * u(rng)};
    JerkProfile p;
    p.reset(s);
    ASSERT_TRUE(append_brake(s, l, p)) << k;
    EXPECT_LE(p.size(), 3);
    EXPECT_TRUE(is_startable(p.end(), l)) << k;
    for (int i = 0; i < p.size(); ++i) {
      EXPECT_TRUE(std::abs(p.jerk(i)) == l.jerk || p.jerk(i) == 0.0);
      EXPECT_GE(p.phase_duration(i), 0.0);
    }
    // a phase of zero jerk holds the acceleration at −a_max or +a_max
    for (int i = 0; i < p.size(); ++i) {
      if (p.jerk(i) == 0.0) {
        EXPECT_NEAR(std::abs(p.at(p.duration_until(i)).a), l.acceleration, 1e-9);
      }
    }
    if (p.size() > 0) ++braked;
    if (p.size() > 0 && l.acceleration * l.acceleration / (2.0 * l.jerk) > 2.0 * l.velocity)
      ++strong;
  }
  EXPECT_GT(braked, 10000);
  EXPECT_GT(strong, 1000);
}

// Strong limits (a_max²/(2 j_max) = 8 > 2 v_max): too fast at rest acceleration, the brake ramps
// down, holds at −a_max and ramps back so that the acceleration would settle at zero velocity.
TEST(JerkLimitedBrake, StrongLimitsSettleAtRestVelocity) {
  const JerkLimits l{1.0, 4.0, 1.0};
  const KinematicState s{0.0, 30.0, 0.0};
  JerkProfile p;
  p.reset(s);
  ASSERT_TRUE(append_brake(s, l, p));
  ASSERT_EQ(p.size(), 3);
  EXPECT_EQ(p.jerk(0), -1.0);
  EXPECT_EQ(p.jerk(1), 0.0);
  EXPECT_EQ(p.jerk(2), 1.0);
  const KinematicState e = p.end();
  // on the limit (the brake aims 1e-10 inside it: kBrakeMargin)
  EXPECT_NEAR(e.v, 1.0, 1e-9);
  EXPECT_LE(e.v, 1.0);
  EXPECT_NEAR(e.a, -std::sqrt(2.0), 1e-9);  // v − a²/(2j) = 0
  EXPECT_NEAR(p.duration(), 4.0 + (30.0 - 16.0) / 4.0 + (4.0 - std::sqrt(2.0)), 1e-9);
  // the brake the old code used (hold at −a_max to v = v_max) would settle at 1 − 8 = −7
  EXPECT_TRUE(is_startable(e, l));
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
  EXPECT_NEAR(p.end().v, 1.0, 1e-9);
  EXPECT_LE(p.end().v, 1.0);
  EXPECT_NEAR(p.end().a, -1.0, 1e-15);
  EXPECT_NEAR(p.duration(), 0.1 + (3.0 - 0.05 - 1.0) / 1.0, 1e-9);
}

}  // namespace
}  // namespace mjarm
