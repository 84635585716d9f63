#include "mjarm/trajectory/otg/profile.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mjarm {
namespace {

JerkProfile sample_jerk_profile() {
  JerkProfile p;
  p.reset({0.5, -0.2, 0.4});
  p.append(2.0, 0.3);
  p.append(0.0, 0.2);
  p.append(-2.0, 0.9);
  p.append(0.0, 0.1);
  p.append(2.0, 0.35);
  return p;
}

TEST(JerkProfile, StateAtIsTheIntegralOfItsJerk) {
  const JerkProfile p = sample_jerk_profile();
  EXPECT_NEAR(p.duration(), 1.85, 1e-15);
  // a fine explicit integration of the same jerk agrees with the closed form everywhere
  KinematicState s = p.start();
  const int steps = 185000;
  const double h = p.duration() / steps;
  for (int k = 0; k < steps; ++k) {
    const double t = (k + 0.5) * h;
    s = integrate_jerk(s, p.at(t).j, h);
    if (k % 9250 == 9249) {
      const JerkSample x = p.at((k + 1) * h);
      EXPECT_NEAR(s.p, x.p, 1e-9);
      EXPECT_NEAR(s.v, x.v, 1e-9);
      EXPECT_NEAR(s.a, x.a, 1e-9);
    }
  }
}

TEST(JerkProfile, ClampsBeforeAndExtrapolatesAfter) {
  const JerkProfile p = sample_jerk_profile();
  const JerkSample before = p.at(-1.0);
  EXPECT_EQ(before.p, 0.5);
  EXPECT_EQ(before.v, -0.2);
  EXPECT_EQ(p.at(std::nan("")).a, 0.4);
  const KinematicState e = p.end();
  const JerkSample after = p.at(p.duration() + 0.5);
  EXPECT_NEAR(after.a, e.a, 1e-15);
  EXPECT_NEAR(after.v, e.v + 0.5 * e.a, 1e-14);
  EXPECT_EQ(after.j, 0.0);
}

TEST(JerkProfile, ExtremaMatchADenseScan) {
  const JerkProfile p = sample_jerk_profile();
  const JerkExtrema e = p.extrema();
  double v_min = 1e9, v_max = -1e9, a_min = 1e9, a_max = -1e9;
  for (int k = 0; k <= 200000; ++k) {
    const JerkSample x = p.at(p.duration() * k / 200000.0);
    v_min = std::min(v_min, x.v);
    v_max = std::max(v_max, x.v);
    a_min = std::min(a_min, x.a);
    a_max = std::max(a_max, x.a);
  }
  // the analytic extrema bound the scan and are attained to the scan's resolution
  EXPECT_LE(e.v_min, v_min);
  EXPECT_GE(e.v_max, v_max);
  EXPECT_NEAR(e.v_min, v_min, 1e-9);
  EXPECT_NEAR(e.v_max, v_max, 1e-9);
  EXPECT_NEAR(e.a_min, a_min, 1e-12);
  EXPECT_NEAR(e.a_max, a_max, 1e-12);
  // the interior velocity peak (a crosses zero inside phase 3) is one of them
  EXPECT_GT(e.v_max, std::max(p.start().v, p.end().v));
}

TEST(JerkProfile, WithinChecksEveryLimit) {
  const JerkProfile p = sample_jerk_profile();
  const JerkExtrema e = p.extrema();
  const double v = std::max(-e.v_min, e.v_max), a = std::max(-e.a_min, e.a_max);
  EXPECT_TRUE(p.within({v, a, 2.0}, 1e-12));
  EXPECT_FALSE(p.within({0.999 * v, a, 2.0}, 1e-12));
  EXPECT_FALSE(p.within({v, 0.999 * a, 2.0}, 1e-12));
  EXPECT_FALSE(p.within({v, a, 1.999}, 1e-12));
}

TEST(JerkProfile, HoldsAtMostItsCapacity) {
  JerkProfile p;
  p.reset({});
  for (int i = 0; i < JerkProfile::kMaxPhases; ++i) EXPECT_TRUE(p.append(1.0, 0.1));
  EXPECT_FALSE(p.append(1.0, 0.1));
  EXPECT_EQ(p.size(), JerkProfile::kMaxPhases);
}

}  // namespace
}  // namespace mjarm
