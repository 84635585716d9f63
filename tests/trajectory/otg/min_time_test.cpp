#include "mjarm/trajectory/otg/min_time.hpp"

#include <gtest/gtest.h>

#include "mjarm/trajectory/otg/validation/grid_reference.hpp"
#include "trajectory/otg/cases.hpp"

namespace mjarm {
namespace {

TEST(JerkLimitedMinTime, RestToRestMatchesTheClassicFormulas) {
  const JerkLimits l{1.0, 2.0, 10.0};
  JerkBlock b;
  // long move: all three limits reached; T = d/v + v/a + a/j
  ASSERT_TRUE(min_time_profile({0.0, 0.0, 0.0}, {5.0, 0.0, 0.0}, l, b));
  EXPECT_NEAR(b.t_min, 5.0 / 1.0 + 1.0 / 2.0 + 2.0 / 10.0, 1e-12);
  EXPECT_EQ(b.fastest().size(), 7);
  // short move, no limit but jerk reached: T = 4·(d/(2j))^(1/3)
  ASSERT_TRUE(min_time_profile({0.0, 0.0, 0.0}, {0.01, 0.0, 0.0}, l, b));
  EXPECT_NEAR(b.t_min, 4.0 * std::cbrt(0.01 / 20.0), 1e-12);
  // already there: an empty profile
  ASSERT_TRUE(min_time_profile({0.3, 0.1, 0.0}, {0.3, 0.1, 0.0}, l, b));
  EXPECT_EQ(b.t_min, 0.0);
  // the mirrored move takes as long
  ASSERT_TRUE(min_time_profile({0.0, 0.0, 0.0}, {-5.0, 0.0, 0.0}, l, b));
  EXPECT_NEAR(b.t_min, 5.7, 1e-12);
}

TEST(JerkLimitedMinTime, EveryRandomCaseSucceedsWithinLimitsAndReachesTheTarget) {
  test::JerkCaseGenerator cases(21);
  double worst_error = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const test::JerkCase c = cases.next();
    JerkBlock b;
    ASSERT_TRUE(min_time_profile(c.start, c.target, c.limits, b)) << k;
    EXPECT_TRUE(b.fastest().within(c.limits, 1e-9)) << k;
    worst_error = std::max(worst_error, test::target_error(b.fastest(), c.target));
    EXPECT_EQ(b.t_min, b.durations[0]);
    EXPECT_NEAR(b.fastest().duration(), b.t_min, 1e-15);
  }
  EXPECT_LT(worst_error, 1e-8);
}

// Time optimality by the independent grid search (otg/validation/grid_reference.hpp): no grid motion
// is shorter than the computed minimum, and one exists within 3 % above it (where the grid is
// fine enough: its velocity margin j·h²/8 at most 1 % of v_max).
TEST(JerkLimitedMinTime, NoShorterMotionExistsOnTheReferenceGrid) {
  test::JerkCaseGenerator cases(5);
  int checked = 0;
  for (int k = 0; k < 40; ++k) {
    const test::JerkCase c = cases.next();
    JerkBlock b;
    ASSERT_TRUE(min_time_profile(c.start, c.target, c.limits, b));
    if (b.t_min < 1e-6) continue;
    for (const double f : {0.99, 0.9, 0.6})
      EXPECT_FALSE(grid_motion_exists(c.start, c.target, c.limits, f * b.t_min, 80)) << k;
    const double h = 1.03 * b.t_min / 80.0;
    if (!b.is_blocked(1.03 * b.t_min) && c.limits.jerk * h * h / 8.0 <= 0.01 * c.limits.velocity) {
      EXPECT_TRUE(grid_motion_exists(c.start, c.target, c.limits, 1.03 * b.t_min, 80)) << k;
    }
    ++checked;
  }
  EXPECT_GT(checked, 30);
}

// Blocked intervals: no motion has a duration inside one (grid reference), and some exist on
// both sides.
TEST(JerkLimitedMinTime, BlockedIntervalsHoldNoMotion) {
  test::JerkCaseGenerator cases(77);
  int intervals = 0;
  for (int k = 0; k < 20000 && intervals < 6; ++k) {
    const test::JerkCase c = cases.next();
    JerkBlock b;
    ASSERT_TRUE(min_time_profile(c.start, c.target, c.limits, b));
    for (int i = 0; i < b.blocked_count; ++i) {
      const JerkInterval& in = b.blocked[i];
      const double mid = 0.5 * (in.lower + in.upper);
      EXPECT_TRUE(b.is_blocked(mid));
      EXPECT_FALSE(grid_motion_exists(c.start, c.target, c.limits, mid, 120)) << k;
      ++intervals;
    }
  }
  EXPECT_GE(intervals, 6);
}

}  // namespace
}  // namespace mjarm
