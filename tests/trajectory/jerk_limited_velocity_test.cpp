#include "mjarm/trajectory/jerk_limited_velocity.hpp"

#include <gtest/gtest.h>

#include "trajectory/jerk_limited_cases.hpp"

namespace mjarm {
namespace {

TEST(JerkLimitedVelocity, RestToCruiseMatchesTheClassicFormula) {
  const JerkLimits l{10.0, 2.0, 10.0};
  JerkBlock b;
  ASSERT_TRUE(min_time_velocity_profile({0.0, 0.0, 0.0}, 3.0, 0.0, l, b));
  EXPECT_NEAR(b.t_min, 3.0 / 2.0 + 2.0 / 10.0, 1e-12);  // Δv/a + a/j
  ASSERT_TRUE(min_time_velocity_profile({0.0, 0.0, 0.0}, 0.1, 0.0, l, b));
  EXPECT_NEAR(b.t_min, 2.0 * std::sqrt(0.1 / 10.0), 1e-12);
}

TEST(JerkLimitedVelocity, RandomTargetsAreReachedInEveryFreeDuration) {
  test::JerkCaseGenerator cases(4);
  int blocked = 0;
  for (int k = 0; k < 20000; ++k) {
    const test::JerkCase c = cases.next();
    JerkBlock b;
    ASSERT_TRUE(min_time_velocity_profile(c.start, c.target.v, c.target.a, c.limits, b)) << k;
    const KinematicState e = b.fastest().end();
    EXPECT_NEAR(e.v, c.target.v, 1e-9);
    EXPECT_NEAR(e.a, c.target.a, 1e-9);
    blocked += b.blocked_count;
    for (const double f : {1.0, 1.01, 1.5, 3.0}) {
      const double t = f * b.t_min;
      if (b.is_blocked(t)) {
        JerkProfile p;
        EXPECT_FALSE(fixed_time_velocity_profile(c.start, c.target.v, c.target.a, c.limits, t, p));
        continue;
      }
      JerkProfile p;
      ASSERT_TRUE(fixed_time_velocity_profile(c.start, c.target.v, c.target.a, c.limits, t, p))
          << k << " " << f;
      EXPECT_NEAR(p.duration(), t, 1e-9 * std::max(1.0, t));
      EXPECT_NEAR(p.end().v, c.target.v, 1e-9);
      EXPECT_NEAR(p.end().a, c.target.a, 1e-9);
      const JerkExtrema x = p.extrema();
      EXPECT_LE(std::max(-x.a_min, x.a_max), c.limits.acceleration * (1.0 + 1e-12));
    }
  }
  EXPECT_GT(blocked, 0);  // the velocity interface has blocked intervals too
}

}  // namespace
}  // namespace mjarm
