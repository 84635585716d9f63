#include "mjarm/trajectory/otg/reach.hpp"

#include <gtest/gtest.h>


#include "mjarm/random.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"
#include "mjarm/trajectory/otg/validation/grid_reference.hpp"
#include "trajectory/otg/cases.hpp"

namespace mjarm {
namespace {

/// The profile @p phases from @p start.
JerkProfile reach_profile(const KinematicState& start, const JerkPhases& phases) {
  JerkProfile p;
  p.reset(start);
  phases.append_to(p);
  return p;
}

// Rest to rest in T: the highest position is the time-optimal rest-to-rest distance for T (the
// classic formula with all three limits reached: d = V·(T − V/A − A/J)), the lowest its mirror.
TEST(JerkLimitedReach, RestToRestMatchesTheClassicFormula) {
  const JerkLimits l{1.0, 2.0, 10.0};
  JerkReach r;
  ASSERT_TRUE(reach_range({0.3, 0.0, 0.0}, 0.0, 0.0, l, 4.0, r));
  EXPECT_NEAR(r.p_max, 0.3 + 1.0 * (4.0 - 0.5 - 0.2), 1e-12);
  EXPECT_NEAR(r.p_min, 0.3 - 1.0 * (4.0 - 0.5 - 0.2), 1e-12);
  // jerk only: d = 2·J·(T/4)³
  ASSERT_TRUE(reach_range({0.0, 0.0, 0.0}, 0.0, 0.0, l, 0.4, r));
  EXPECT_NEAR(r.p_max, 2.0 * 10.0 * 0.001, 1e-14);
  // no time: the start only, and only when it has the target's velocity and acceleration
  ASSERT_TRUE(reach_range({0.5, 0.2, 0.1}, 0.2, 0.1, l, 0.0, r));
  EXPECT_EQ(r.p_min, 0.5);
  EXPECT_EQ(r.p_max, 0.5);
  EXPECT_FALSE(reach_range({0.5, 0.2, 0.1}, 0.0, 0.0, l, 0.0, r));
  EXPECT_FALSE(reach_range({0.0, 0.0, 0.0}, 0.0, 0.0, l, std::nan(""), r));
}

// The ends of the range are reached by their profiles within the limits, and the independent
// grid reference (otg/validation/grid_reference.hpp) finds no motion beyond either end: a grid motion is
// a true motion, so one ending beyond p_max would prove p_max wrong.
TEST(JerkLimitedReach, NoMotionEndsBeyondTheRange) {
  test::JerkCaseGenerator cases(31);
  const auto factor = [](mjarm::Random& r) { return mjarm::uniform(r, 0.5, 3.0); };
  int probed = 0;
  for (int k = 0; k < 40; ++k) {
    const test::JerkCase c = cases.next();
    JerkBlock b;
    ASSERT_TRUE(min_time_profile(c.start, c.target, c.limits, b));
    const double T = factor(cases.rng()) * std::max(b.t_min, 0.05);
    JerkReach r;
    if (!reach_range(c.start, c.target.v, c.target.a, c.limits, T, r)) continue;
    for (const JerkPhases* phases : {&r.highest, &r.lowest}) {
      const JerkProfile p = reach_profile(c.start, *phases);
      EXPECT_NEAR(p.duration(), T, 1e-9 * T) << k;
      EXPECT_TRUE(p.within(c.limits, 1e-9)) << k;
      EXPECT_NEAR(p.end().v, c.target.v, 1e-9) << k;
      EXPECT_NEAR(p.end().a, c.target.a, 1e-9) << k;
    }
    EXPECT_NEAR(reach_profile(c.start, r.highest).end().p, r.p_max, 1e-9);
    EXPECT_NEAR(reach_profile(c.start, r.lowest).end().p, r.p_min, 1e-9);
    const double margin = 1e-3 * std::max(r.p_max - r.p_min, 1e-3);
    KinematicState beyond = c.target;
    beyond.p = r.p_max + margin;
    EXPECT_FALSE(grid_motion_exists(c.start, beyond, c.limits, T, 60)) << k;
    beyond.p = r.p_min - margin;
    EXPECT_FALSE(grid_motion_exists(c.start, beyond, c.limits, T, 60)) << k;
    ++probed;
  }
  EXPECT_GT(probed, 30);
}

// Step 1 and the range agree: at every extremal duration the target lies on an end of the range,
// just above t_min it lies inside, and just below t_min outside (or the range is empty).
TEST(JerkLimitedReach, ExtremalDurationsAreWhereTheRangeMeetsTheTarget) {
  test::JerkCaseGenerator cases(32);
  for (int k = 0; k < 3000; ++k) {
    const test::JerkCase c = cases.next();
    JerkBlock b;
    ASSERT_TRUE(min_time_profile(c.start, c.target, c.limits, b));
    if (b.t_min < 1e-6) continue;
    for (int i = 0; i < b.duration_count; ++i) {
      JerkReach r;
      ASSERT_TRUE(reach_range(c.start, c.target.v, c.target.a, c.limits, b.durations[i], r)) << k;
      const double tol = 1e-8 * std::max(1.0, std::abs(c.target.p));
      EXPECT_TRUE(std::abs(r.p_max - c.target.p) <= tol || std::abs(r.p_min - c.target.p) <= tol)
          << k << " duration " << i;
    }
    EXPECT_TRUE(duration_feasible(c.start, c.target, c.limits, b.t_min * (1.0 + 1e-7))) << k;
    EXPECT_FALSE(duration_feasible(c.start, c.target, c.limits, b.t_min * (1.0 - 1e-6))) << k;
  }
}

}  // namespace
}  // namespace mjarm
