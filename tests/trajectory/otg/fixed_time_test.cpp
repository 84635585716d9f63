#include "mjarm/trajectory/otg/fixed_time.hpp"

#include <gtest/gtest.h>

#include "mjarm/trajectory/otg/min_time.hpp"
#include "trajectory/otg/cases.hpp"

namespace mjarm {
namespace {

TEST(JerkLimitedFixedTime, RestToRestSlowerThanNeeded) {
  const JerkLimits l{1.0, 2.0, 10.0};
  JerkProfile p;
  ASSERT_TRUE(fixed_time_profile({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, l, 4.0, p));
  EXPECT_NEAR(p.duration(), 4.0, 1e-12);
  EXPECT_LT(test::target_error(p, {1.0, 0.0, 0.0}), 1e-9);
  EXPECT_TRUE(p.within(l, 1e-12));
  // shorter than the minimum: no profile
  JerkBlock b;
  ASSERT_TRUE(min_time_profile({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, l, b));
  EXPECT_FALSE(fixed_time_profile({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, l, 0.99 * b.t_min, p));
  EXPECT_FALSE(fixed_time_profile({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, l, std::nan(""), p));
}

// Cases no full-jerk structure of the previous implementation covered (it needed a reduced-jerk
// (+j_r, −j_r, +j_r) fallback for them): the blend of the two extreme profiles covers them, with a
// jerk below the limit where the two extremes' jerks disagree.
TEST(JerkLimitedFixedTime, CasesWithoutAFullJerkProfileGetOne) {
  const struct {
    JerkLimits l;
    KinematicState s, f;
    double t;
  } cases[] = {{{1.8410291779337169, 5.3574362183148114, 14.729014180350156},
                {0.75605777311114997, 1.4312142524741733, -4.3759436702624006},
                {0.49741712714757647, -1.1359316408645193, 1.5900263631719189},
                1.0313789629063685},
               {{2.9440450182521913, 3.8592108536896896, 7.1660528537031434},
                {1.6825385604135703, 2.1318898742140551, -0.82737233025247214},
                {1.5386983370219003, -2.6980458454390011, -3.4385153327049718},
                1.9019444206686771},
               {{1.1470382772231527, 3.0292959783079856, 5.2668343997083449},
                {0.0012544494176456311, -0.78109233019596302, 1.7169657493911601},
                {0.71516881057161941, 0.38340132973053104, -2.5801736846812924},
                1.8759649453961278}};
  for (const auto& c : cases) {
    JerkProfile p;
    ASSERT_TRUE(fixed_time_profile(c.s, c.f, c.l, c.t, p));
    EXPECT_NEAR(p.duration(), c.t, 1e-9);
    EXPECT_LT(test::target_error(p, c.f), 1e-8);
    EXPECT_TRUE(p.within(c.l, 1e-9));
    EXPECT_LT(std::abs(p.jerk(0)), c.l.jerk);  // the jerk is reduced
  }
}

// A target at rest can always be reached later than the minimum. This case (from `mjarm bench
// otg`) had no profile from the previous implementation's structures at 10 s and longer.
TEST(JerkLimitedFixedTime, ATargetAtRestIsReachedInAnyLongerDuration) {
  const JerkLimits l{1.5025581338088374, 0.57846248159748204, 13.720501381576257};
  const KinematicState s{2.6683869852891609, -0.46675518089847673, 0.13980748995602732};
  const KinematicState f{2.4740190392189598, 0.0, 0.0};
  for (const double t : {10.0, 14.267559, 20.0}) {
    JerkProfile p;
    ASSERT_TRUE(fixed_time_profile(s, f, l, t, p)) << t;
    EXPECT_NEAR(p.duration(), t, 1e-9);
    EXPECT_LT(test::target_error(p, f), 1e-8);
    EXPECT_TRUE(p.within(l, 1e-9));
  }
}

// Every duration from the minimum up to four times it, outside blocked intervals, gets a profile
// of exactly that duration, within the limits and on target — none is missed; and a duration
// inside a blocked interval or below the minimum gets none.
TEST(JerkLimitedFixedTime, EveryFeasibleDurationGetsAProfileAndNoOtherDoes) {
  test::JerkCaseGenerator cases(8);
  int tried = 0, blocked = 0;
  for (int k = 0; k < 5000; ++k) {
    const test::JerkCase c = cases.next();
    JerkBlock b;
    ASSERT_TRUE(min_time_profile(c.start, c.target, c.limits, b));
    for (const double f : {1.0 + 1e-9, 1.001, 1.05, 1.3, 2.0, 4.0}) {
      const double t = f * b.t_min;
      if (b.is_blocked(t) || t <= 0.0) continue;
      ++tried;
      JerkProfile p;
      ASSERT_TRUE(fixed_time_profile(c.start, c.target, c.limits, t, p)) << k << " " << f;
      EXPECT_NEAR(p.duration(), t, 1e-9 * t);
      EXPECT_LT(test::target_error(p, c.target), 1e-8);
      EXPECT_TRUE(p.within(c.limits, 1e-9));
      EXPECT_LE(p.size(), 13);
    }
    JerkProfile p;
    if (b.t_min > 1e-6) {
      EXPECT_FALSE(fixed_time_profile(c.start, c.target, c.limits, b.t_min * (1.0 - 1e-6), p));
    }
    for (int i = 0; i < b.blocked_count; ++i) {
      const double mid = 0.5 * (b.blocked[i].lower + b.blocked[i].upper);
      EXPECT_FALSE(fixed_time_profile(c.start, c.target, c.limits, mid, p)) << k;
      ++blocked;
    }
  }
  EXPECT_GT(tried, 20000);
  EXPECT_GT(blocked, 10);
}

// A high jerk between long holds: the blend's two profiles end at the duration only to its
// round-off, and a ramp lengthened by that, times a jerk of 10⁴–10⁵, would miss the target's
// acceleration by 10⁻⁹ (the round-off goes into an overlap of two holds instead).
TEST(JerkLimitedFixedTime, HighJerkBetweenLongHoldsStaysOnTarget) {
  const struct {
    JerkLimits l;
    KinematicState s, f;
    double t;
  } cases[] = {{{40.729610056932152, 1.3446199006964121, 88295.275003642426},
                {-11.547435532192353, 0.0, 0.0},
                {65.267168133437366, 0.0, 0.0},
                41.333456486530025},
               {{84.549374835165963, 0.026119145934900216, 6519.5044523097749},
                {0.41527998074297301, -13.731914938312061, -0.011791882775163996},
                {-0.83268343423783198, -17.760317217620585, 0.011591935779517459},
                7549.4109950902975}};
  for (const auto& c : cases) {
    JerkProfile p;
    ASSERT_TRUE(fixed_time_profile(c.s, c.f, c.l, c.t, p));
    EXPECT_NEAR(p.end().a, c.f.a, 1e-12);
    EXPECT_NEAR(p.end().v, c.f.v, 1e-11);
    EXPECT_NEAR(p.end().p, c.f.p, 1e-9);
    EXPECT_TRUE(p.within(c.l, 1e-12));
  }
}

// Long durations integrate in double precision: a cruise of hours at exactly zero acceleration
// still ends on target (the plateau's acceleration is set to zero, not left at round-off).
TEST(JerkLimitedFixedTime, HoursLongProfilesStayOnTarget) {
  const JerkLimits l{0.87839283657225298, 5.1135620903528975, 32.806846852667228};
  const KinematicState s{2.5313618027795717, 0.16610441681497126, 2.7205153286952037};
  const KinematicState f{-1.2478474742190606, -0.20763312723601823, -1.3048239408975755};
  for (const double t : {2898.707582, 45300.834511}) {
    JerkProfile p;
    ASSERT_TRUE(fixed_time_profile(s, f, l, t, p)) << t;
    EXPECT_LT(test::target_error(p, f), 1e-8) << t;
    EXPECT_TRUE(p.within(l, 1e-9));
  }
}

}  // namespace
}  // namespace mjarm
