#include "mjarm/trajectory/jerk_limited.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/trajectory/jerk_limited_brake.hpp"
#include "mjarm/trajectory/jerk_limited_sync.hpp"
#include "trajectory/jerk_limited_cases.hpp"

// the allocation counter of test_trajectory is defined once, in malloc_counter_test.cpp

namespace mjarm {
namespace {

std::vector<JerkLimits> seven_limits() {
  return {{2.0, 5.0, 30.0}, {2.0, 5.0, 30.0}, {2.5, 6.0, 40.0}, {2.5, 6.0, 40.0},
          {3.0, 8.0, 50.0}, {3.0, 8.0, 50.0}, {3.0, 8.0, 50.0}};
}

TEST(JerkLimitedGenerator, SynchronizesEveryDoFToTheSlowest) {
  JerkLimitedGenerator otg(seven_limits());
  std::vector<KinematicState> current(7), target(7);
  for (int i = 0; i < 7; ++i) {
    current[i] = {0.1 * i, 0.2 * (i % 3) - 0.2, 0.5 * (i % 2)};
    target[i] = {1.0 - 0.3 * i, 0.0, 0.0};
  }
  const OtgResult r = otg.calculate(current, target);
  ASSERT_EQ(r.status, OtgStatus::working);
  ASSERT_GE(r.limiting_dof, 0);
  EXPECT_NEAR(r.duration, otg.block(r.limiting_dof).t_min, 1e-12);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(otg.profile(i).duration(), r.duration, 1e-9) << i;
    EXPECT_LT(test::target_error(otg.profile(i), target[i]), 1e-8) << i;
    EXPECT_TRUE(otg.profile(i).within(otg.limits(i), 1e-9)) << i;
    EXPECT_GE(r.duration, otg.block(i).t_min - 1e-12);
  }
  // stepping along reaches the target
  std::vector<KinematicState> state(7);
  OtgStatus s = OtgStatus::working;
  int ticks = 0;
  while (s == OtgStatus::working && ticks < 100000) {
    s = otg.step(0.001, state);
    ++ticks;
  }
  EXPECT_EQ(s, OtgStatus::finished);
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(state[i].p, target[i].p, 1e-6);
}

TEST(JerkLimitedGenerator, AMovingTargetIsFollowedFromTheCurrentStateEveryTick) {
  const std::vector<JerkLimits> limits(3, JerkLimits{1.0, 3.0, 20.0});
  JerkLimitedGenerator otg(limits);
  std::vector<KinematicState> state(3), target(3), next(3);
  const double dt = 0.002;
  double worst_jerk = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const double t = k * dt;
    for (int i = 0; i < 3; ++i) target[i] = {0.5 * std::sin(0.7 * t + i), 0.0, 0.0};
    const OtgResult r = otg.calculate(state, target);
    ASSERT_TRUE(r.status == OtgStatus::working || r.status == OtgStatus::finished) << k;
    otg.step(dt, next);
    for (int i = 0; i < 3; ++i) {
      // the new state continues the old one: the acceleration changes by at most j·dt
      worst_jerk = std::max(worst_jerk, std::abs(next[i].a - state[i].a) / dt);
      EXPECT_LE(std::abs(next[i].v), 1.0 + 1e-9);
      EXPECT_LE(std::abs(next[i].a), 3.0 + 1e-9);
    }
    state = next;
  }
  EXPECT_LE(worst_jerk, 20.0 * (1.0 + 1e-6));
  EXPECT_GT(worst_jerk, 1.0);
}

TEST(JerkLimitedGenerator, BrakesFromBeyondTheLimitsFirst) {
  const std::vector<JerkLimits> limits(2, JerkLimits{1.0, 2.0, 10.0});
  JerkLimitedGenerator otg(limits);
  const std::vector<KinematicState> current = {{0.0, 2.5, 0.0}, {0.0, 0.0, -3.0}};
  const std::vector<KinematicState> target = {{1.0, 0.0, 0.0}, {0.5, 0.0, 0.0}};
  const OtgResult r = otg.calculate(current, target);
  ASSERT_EQ(r.status, OtgStatus::working);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(otg.brake_phases(i), 0);
    EXPECT_LT(test::target_error(otg.profile(i), target[i]), 1e-8);
    // after the brake, the limits hold
    const JerkExtrema e = otg.profile(i).extrema(otg.brake_phases(i));
    EXPECT_LE(std::max(-e.v_min, e.v_max), 1.0 + 1e-9);
    EXPECT_LE(std::max(-e.a_min, e.a_max), 2.0 + 1e-9);
  }
}

// Limits with a_max²/(2 j_max) far above 2 v_max (a strong actuator on a slow axis): starts far
// beyond them brake without overshooting to the other side, then reach the target.
TEST(JerkLimitedGenerator, BrakesForAnyLimits) {
  const std::vector<JerkLimits> limits = {{0.2, 8.0, 0.5}, {0.3, 6.0, 1.0}, {1.0, 2.0, 10.0}};
  JerkLimitedGenerator otg(limits);
  const std::vector<KinematicState> current = {
      {0.0, 0.3, 12.0}, {0.0, -0.1, -9.0}, {0.0, 0.0, 0.0}};
  const std::vector<KinematicState> target = {{0.5, 0.0, 0.0}, {-0.2, 0.1, 0.0}, {1.0, 0.0, 0.0}};
  const OtgResult r = otg.calculate(current, target);
  ASSERT_EQ(r.status, OtgStatus::working);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(otg.profile(i).duration(), r.duration, 1e-9 * r.duration) << i;
    EXPECT_LT(test::target_error(otg.profile(i), target[i]), 1e-8) << i;
    const JerkExtrema e = otg.profile(i).extrema(otg.brake_phases(i));
    EXPECT_LE(std::max(-e.v_min, e.v_max), limits[i].velocity * (1.0 + 1e-9)) << i;
    EXPECT_LE(std::max(-e.a_min, e.a_max), limits[i].acceleration * (1.0 + 1e-9)) << i;
  }
  EXPECT_GT(otg.brake_phases(0), 0);
  EXPECT_GT(otg.brake_phases(1), 0);
  EXPECT_EQ(otg.brake_phases(2), 0);
}

// Step 1 runs only for the DoFs that decide the duration; the duration is the one a
// synchronization over every DoF's blocked intervals gives (block(i) runs step 1 on demand).
TEST(JerkLimitedGenerator, LazyStepOneGivesTheFullSynchronization) {
  test::JerkCaseGenerator cases(17);
  int checked = 0;
  for (int k = 0; k < 400; ++k) {
    std::vector<JerkLimits> limits(7);
    std::vector<KinematicState> current(7), target(7);
    for (int i = 0; i < 7; ++i) {
      const test::JerkCase c = cases.next();
      limits[i] = c.limits;
      current[i] = c.start;
      target[i] = c.target;
    }
    if (k % 4 == 0) {  // ties: two DoFs alike
      limits[3] = limits[2];
      current[3] = current[2];
      target[3] = target[2];
    }
    JerkLimitedGenerator otg(limits);
    const OtgResult r = otg.calculate(current, target);
    ASSERT_TRUE(r.status == OtgStatus::working || r.status == OtgStatus::finished) << k;
    std::vector<JerkBlock> blocks(7);
    std::vector<double> offsets(7);
    for (int i = 0; i < 7; ++i) {
      blocks[i] = otg.block(i);
      offsets[i] = otg.brake_duration(i);
    }
    JerkSync sync;
    ASSERT_TRUE(synchronize(blocks, offsets, sync));
    EXPECT_NEAR(r.duration, sync.duration, 1e-12 * std::max(1.0, sync.duration)) << k;
    // the limiting DoF's minimum or the end of one of its blocked intervals
    const JerkBlock& b = otg.block(r.limiting_dof);
    bool at_an_end = std::abs(b.t_min - r.duration) <= 1e-12 * std::max(1.0, r.duration);
    for (int i = 0; i < b.blocked_count; ++i)
      at_an_end = at_an_end || std::abs(b.blocked[i].upper - r.duration) <= 1e-12 * r.duration;
    EXPECT_TRUE(at_an_end) << k;
    ++checked;
  }
  EXPECT_EQ(checked, 400);
}

// Limits over four decades each (v, a in [0.01, 100], j in [0.1, 10⁴]), positions in ±10, a
// tenth of the DoFs starting beyond their limits: every calculation succeeds, within the limits,
// on target to 1e-9 relative to the largest position involved (see JerkTolerance).
TEST(JerkLimitedGenerator, WideRangesOfLimitsSucceed) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0), share(0.0, 1.0);
  const auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, share(rng)); };
  for (int k = 0; k < 300; ++k) {
    std::vector<JerkLimits> limits(7);
    std::vector<KinematicState> current(7), target(7);
    for (int i = 0; i < 7; ++i) {
      const JerkLimits l{log_uniform(0.01, 100.0), log_uniform(0.01, 100.0), log_uniform(0.1, 1e4)};
      limits[i] = l;
      const bool beyond = share(rng) < 0.1;
      do {
        const double scale = beyond ? 1.6 : 1.0;
        current[i] = {10.0 * u(rng), scale * l.velocity * u(rng), scale * l.acceleration * u(rng)};
      } while (beyond == is_startable(current[i], l));
      do target[i] = {10.0 * u(rng), l.velocity * u(rng), l.acceleration * u(rng)};
      while (!is_reachable(target[i], l));
    }
    JerkLimitedGenerator otg(limits);
    const OtgResult r = otg.calculate(current, target);
    ASSERT_TRUE(r.status == OtgStatus::working || r.status == OtgStatus::finished)
        << k << " " << to_string(r.status) << " DoF " << r.failed_dof;
    for (int i = 0; i < 7; ++i) {
      const JerkProfile& p = otg.profile(i);
      const JerkExtrema e = p.extrema(otg.brake_phases(i));
      EXPECT_LE(std::max(-e.v_min, e.v_max), limits[i].velocity * (1.0 + 1e-9)) << k;
      EXPECT_LE(std::max(-e.a_min, e.a_max), limits[i].acceleration * (1.0 + 1e-9)) << k;
      const KinematicState end = p.end();
      double scale = 1.0;
      for (int q = 0; q <= p.size(); ++q)
        scale = std::max(scale, std::abs(p.at(p.duration_until(q)).p));
      EXPECT_LE(std::abs(end.p - target[i].p), 1e-9 * scale) << k;
      EXPECT_LE(std::abs(end.v - target[i].v), 1e-9 * std::max(1.0, std::abs(target[i].v))) << k;
      EXPECT_LE(std::abs(end.a - target[i].a), 1e-9 * std::max(1.0, std::abs(target[i].a))) << k;
    }
  }
}

TEST(JerkLimitedGenerator, VelocityInterfaceReachesVelocitiesTogether) {
  JerkLimitedGenerator otg(seven_limits());
  std::vector<KinematicState> current(7), target(7);
  for (int i = 0; i < 7; ++i) {
    current[i] = {0.0, 0.3 * i - 1.0, 1.0 - 0.25 * i};
    target[i] = {0.0, 1.5 - 0.4 * i, 0.0};
  }
  const OtgResult r = otg.calculate_velocity(current, target);
  ASSERT_EQ(r.status, OtgStatus::working);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(otg.profile(i).duration(), r.duration, 1e-9);
    EXPECT_NEAR(otg.profile(i).end().v, target[i].v, 1e-9);
    EXPECT_NEAR(otg.profile(i).end().a, 0.0, 1e-9);
  }
}

TEST(JerkLimitedGenerator, InvalidInputIsAnError) {
  EXPECT_THROW(JerkLimitedGenerator(std::vector<JerkLimits>{}), Error);
  for (const JerkLimits bad :
       {JerkLimits{0.0, 1.0, 1.0}, JerkLimits{1.0, -1.0, 1.0}, JerkLimits{1.0, 1.0, std::nan("")},
        JerkLimits{1.0, 1.0, HUGE_VAL}}) {
    EXPECT_THROW(JerkLimitedGenerator(std::vector<JerkLimits>{bad}), Error);
  }
  try {
    JerkLimitedGenerator(std::vector<JerkLimits>{{1.0, 1.0, 1.0}, {1.0, 0.0, 1.0}});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("DoF 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("acceleration"), std::string::npos) << e.what();
  }
  JerkLimitedGenerator otg(std::vector<JerkLimits>(1, JerkLimits{1.0, 2.0, 10.0}));
  const std::vector<KinematicState> ok = {{0.0, 0.0, 0.0}};
  const auto calc = [&otg, &ok](KinematicState c, KinematicState t) {
    const std::vector<KinematicState> cs = {c}, ts = {t};
    return otg.calculate(cs, ts);
  };
  EXPECT_THROW(calc({std::nan(""), 0.0, 0.0}, {1.0, 0.0, 0.0}), Error);
  EXPECT_THROW(calc({0.0, 0.0, 0.0}, {HUGE_VAL, 0.0, 0.0}), Error);
  EXPECT_THROW(calc({0.0, 0.0, 0.0}, {1.0, 1.5, 0.0}), Error);    // target v above its limit
  EXPECT_THROW(calc({0.0, 0.0, 0.0}, {1.0, 0.0, -2.5}), Error);   // target a above its limit
  EXPECT_THROW(calc({0.0, 0.0, 0.0}, {1.0, 0.95, -1.5}), Error);  // must overshoot to reach it
  EXPECT_THROW(otg.calculate(ok, std::vector<KinematicState>(2)), Error);  // sizes
  EXPECT_THROW(otg.calculate_velocity(ok, std::vector<KinematicState>{{0.0, 2.0, 0.0}}), Error);
  // a start beyond the limits is not an error: it is braked
  EXPECT_EQ(calc({0.0, 3.0, 4.0}, {1.0, 0.0, 0.0}).status, OtgStatus::working);
}

TEST(JerkLimitedGenerator, CalculatesWithoutAllocating) {
  JerkLimitedGenerator otg(seven_limits());
  test::JerkCaseGenerator cases(9);
  std::vector<KinematicState> current(7), target(7), state(7);
  std::vector<JerkSample> samples(7);
  std::vector<JerkLimits> limits = seven_limits();
  // warm up once (nothing is lazily allocated, but be fair to the counter)
  otg.calculate(current, target);
  std::uint64_t allocations = 0;
  for (int k = 0; k < 200; ++k) {
    for (int i = 0; i < 7; ++i) {
      test::JerkCase c = cases.next();
      // scale the drawn states into this generator's limits
      const double sv = limits[i].velocity / c.limits.velocity;
      const double sa = limits[i].acceleration / c.limits.acceleration;
      current[i] = {c.start.p, 0.2 * c.start.v * sv, 0.2 * c.start.a * sa};
      target[i] = {c.target.p, 0.2 * c.target.v * sv, 0.2 * c.target.a * sa};
    }
    const std::uint64_t before = test::malloc_calls();
    otg.calculate(current, target);
    otg.calculate_velocity(current, target);
    otg.at(0.1, samples);
    otg.step(0.001, state);
    allocations += test::malloc_calls() - before;
  }
  EXPECT_EQ(allocations, 0u);
  // the counter does see allocations
  const std::uint64_t before = test::malloc_calls();
  JerkLimitedGenerator another(seven_limits());
  EXPECT_GT(test::malloc_calls() - before, 0u);
}

}  // namespace
}  // namespace mjarm
