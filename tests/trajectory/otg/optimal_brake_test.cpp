#include "mjarm/trajectory/otg/optimal_brake.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"
#include "mjarm/trajectory/otg/validation/brake_optimality.hpp"

// the allocation counter of test_trajectory is defined once, in malloc_counter_test.cpp

namespace mjarm {
namespace {

double brake_log_uniform(Random& rng, double lo, double hi) {
  return lo * std::pow(hi / lo, uniform(rng));
}

// Every member of a brake family, for any limits: at most 3 phases at full or zero jerk, in the
// brake's order (an acceleration beyond its limit does not grow; then −s·j, a hold at −s·a_max,
// +s·j), ending startable on the velocity limit with the settled velocity asked for.
TEST(JerkLimitedBrakeFamily, EveryMemberEndsStartableInTheBrakesOrder) {
  Random rng(11);
  int with_choice = 0;
  for (int k = 0; k < 5000; ++k) {
    const JerkLimits l{brake_log_uniform(rng, 0.05, 5.0), brake_log_uniform(rng, 0.1, 20.0),
                       brake_log_uniform(rng, 0.2, 50.0)};
    const KinematicState s{0.0, 3.0 * l.velocity * uniform(rng, -1.0, 1.0),
                           3.0 * l.acceleration * uniform(rng, -1.0, 1.0)};
    const BrakeFamily family = brake_family(s, l);
    if (family.side == 0.0) continue;
    ASSERT_LE(family.lowest, family.highest) << k;
    ASSERT_GE(family.lowest, -l.velocity) << k;
    ASSERT_LE(family.highest, l.velocity) << k;
    with_choice += family.highest > family.lowest ? 1 : 0;
    for (const double u : {0.0, 0.3, 1.0}) {
      const double settled = family.lowest + u * (family.highest - family.lowest);
      JerkProfile p;
      p.reset(s);
      ASSERT_TRUE(append_brake_member(s, l, settled, p));
      ASSERT_LE(p.size(), 3);
      const KinematicState e = p.end();
      EXPECT_TRUE(is_startable(e, l)) << k;
      EXPECT_NEAR(family.side * e.v, l.velocity, 1e-8 * std::max(1.0, std::abs(s.v))) << k;
      EXPECT_NEAR(e.v + e.a * std::abs(e.a) / (2.0 * l.jerk), family.side * settled,
                  1e-7 * std::max(1.0, std::abs(s.v) + s.a * s.a / l.jerk))
          << k;
      int stage = 0;
      double excess = std::abs(s.a) - l.acceleration;
      for (int i = 0; i < p.size(); ++i) {
        const double a0 = p.at(p.duration_until(i)).a, a1 = p.at(p.duration_until(i + 1)).a;
        EXPECT_LE(std::abs(a1) - l.acceleration, std::max(excess, 0.0) + 1e-12) << k;
        excess = std::abs(a1) - l.acceleration;
        if (std::abs(a0) > l.acceleration * (1.0 + 1e-12)) continue;  // the forced ramp
        const double j = family.side * p.jerk(i);
        const int kind = j < 0.0 ? 0 : (j > 0.0 ? 2 : 1);
        EXPECT_GE(kind, stage) << k;
        stage = kind;
        if (kind == 1) EXPECT_NEAR(a0, -family.side * l.acceleration, 1e-9) << k;
      }
    }
  }
  EXPECT_GT(with_choice, 1000);
}

// A start far too fast towards a far target: the best brake comes down to v_max with zero
// acceleration and cruises from there (the standard brake ends at −a_max and must recover).
TEST(JerkLimitedBrakeFamily, AFarTargetIsReachedCruisingAtTheLimitRightAfterTheBrake) {
  const JerkLimits l{1.0, 4.0, 1.0};
  const KinematicState s{0.0, 30.0, 0.0}, t{2000.0, 0.0, 0.0};
  JerkProfile p;
  p.reset(s);
  OptimalBrakeScratch scratch;
  ASSERT_TRUE(append_optimal_brake(s, t, l, l, p, scratch));
  // −j for 4 s to −a_max, a hold, +j for 4 s: the release settles exactly at v_max
  ASSERT_EQ(p.size(), 3);
  EXPECT_NEAR(p.end().v, 1.0, 1e-9);
  EXPECT_NEAR(p.end().a, 0.0, 1e-6);
  EXPECT_NEAR(p.duration(), 4.0 + (22.0 - 9.0) / 4.0 + 4.0, 1e-6);
  JerkBlock after, standard_after;
  ASSERT_TRUE(min_time_profile(p.end(), t, l, after));
  JerkProfile standard;
  standard.reset(s);
  ASSERT_TRUE(append_brake(s, l, standard));
  ASSERT_TRUE(min_time_profile(standard.end(), t, l, standard_after));
  EXPECT_LT(p.duration() + after.t_min, standard.duration() + standard_after.t_min - 0.1);
}

// The generator from starts beyond the limits, 7 DoF, every DoF braking: no DoF's own duration
// (brake and time-optimal profile) longer than the best member of its brake family (a scan of
// 200), the standard brake measurably longer on some; every result within the limits after its
// brakes, each brake in order into the startable states, on target, one duration.
TEST(JerkLimitedBrakeFamily, TheGeneratorsBrakeIsNeverLongerThanTheFamilysBest) {
  BrakeOptimalityOptions options;
  options.cases = 45;  // 315 DoFs
  options.seed = 4;
  options.family_members = 200;
  const BrakeOptimalityResult r = run_brake_optimality(options);
  EXPECT_EQ(r.braking_dofs, 315);
  EXPECT_GT(r.with_choice, 150);
  EXPECT_EQ(r.failures, 0) << r.first_failure;
  EXPECT_EQ(r.check_failures, 0) << r.first_failure;
  EXPECT_EQ(r.optimal.longer, 0) << r.first_failure;
  EXPECT_LT(r.optimal.worst_ratio, 1.0 + 1e-9);
  EXPECT_GT(r.standard.longer, 30);  // the gap the family closes
  EXPECT_GT(r.standard.worst_ratio, 1.05);
  EXPECT_LT(r.worst_limit_excess, 1e-9);
  EXPECT_LT(r.worst_target_error, 1e-8);
}

// The independent structure search (which searches the brake's end with the motion after it)
// finds the generator's duration on braking DoFs: never shorter (which would beat it), and no
// longer on these seeds.
TEST(JerkLimitedBrakeFamily, TheStructureSearchConfirmsTheGeneratorsDurations) {
  BrakeOptimalityOptions options;
  options.cases = 2;
  options.seed = 8;
  options.family_members = 50;
  options.structure_cases = 10;
  options.structure_seeds = 8;
  const BrakeOptimalityResult r = run_brake_optimality(options);
  EXPECT_EQ(r.structure_cases, 10);
  EXPECT_EQ(r.structure_optimal.longer, 0) << r.first_failure;
  EXPECT_EQ(r.structure_optimal.shorter + r.structure_not_found, 0) << r.first_failure;
}

// Choosing the brake allocates nothing: all DoFs beyond their limits, position interface.
TEST(JerkLimitedBrakeFamily, ChoosingTheBrakeDoesNotAllocate) {
  const std::vector<JerkLimits> limits(7, JerkLimits{1.0, 2.0, 5.0});
  JerkLimitedGenerator otg(limits);
  std::vector<KinematicState> current(7), target(7);
  Random rng(21);
  std::uint64_t allocations = 0;
  int braking = 0;
  for (int k = 0; k < 50; ++k) {
    for (int i = 0; i < 7; ++i) {
      do
        current[i] = {uniform(rng, -1.0, 1.0), 1.6 * uniform(rng, -1.0, 1.0),
                      3.2 * uniform(rng, -1.0, 1.0)};
      while (is_startable(current[i], limits[0]));
      target[i] = {uniform(rng, -1.0, 1.0), 0.0, 0.0};
      braking += brake_family(current[i], limits[0]).side != 0.0 ? 1 : 0;
    }
    const std::uint64_t before = test::malloc_calls();
    const OtgResult r = otg.calculate(current, target);
    allocations += test::malloc_calls() - before;
    EXPECT_EQ(r.status, OtgStatus::working);
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(braking, 100);
}

}  // namespace
}  // namespace mjarm
