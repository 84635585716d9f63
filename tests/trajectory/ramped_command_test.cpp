// The gripper command ramp: a smoothstep from where it is to each new target, every move with the
// same peak rate, landing exactly; retargeting mid-ramp keeps the value continuous; bad input.
#include "mjarm/trajectory/ramped_command.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

TEST(RampedCommand, AJumpBecomesASmoothstepThatLandsExactly) {
  RampedCommand c(0.4);  // 0 → 1 in 0.4 s
  c.reset(0.0);
  EXPECT_TRUE(c.settled());
  const double dt = 0.001;
  double peak_rate = 0.0;
  int ticks = 0;
  c.update(1.0, 0.0);  // takes the target, advances nothing
  EXPECT_EQ(c.value(), 0.0);
  EXPECT_NEAR(c.ramp_duration(), 0.4, 1e-15);
  while (!c.settled()) {
    const double before = c.value();
    c.update(1.0, dt);
    ++ticks;
    const double t = ticks * dt;
    if (t < 0.4 - 1e-12) {
      EXPECT_NEAR(c.value(), smoothstep(t / 0.4).s, 1e-12) << t;
      EXPECT_NEAR(c.rate(), smoothstep(t / 0.4).ds / 0.4, 1e-9) << t;
    }
    EXPECT_GE(c.value(), before);  // monotone
    peak_rate = std::max(peak_rate, c.rate());
    ASSERT_LT(ticks, 1000);
  }
  EXPECT_EQ(ticks, 400);
  EXPECT_EQ(c.value(), 1.0);
  EXPECT_EQ(c.rate(), 0.0);
  EXPECT_NEAR(peak_rate, 1.5 / 0.4, 1e-3);  // smoothstep's peak slope 1.5 over 0.4 s
  // half the travel takes half the time, at the same peak rate
  c.update(0.5, 0.0);
  EXPECT_NEAR(c.ramp_duration(), 0.2, 1e-15);
}

TEST(RampedCommand, RetargetingMidRampKeepsTheValueContinuous) {
  RampedCommand c(0.5, 0.0, 1.0, SmoothRamp::Kind::smootherstep);
  c.reset(0.0);
  for (int k = 0; k < 100; ++k) c.update(1.0, 0.002);  // 0.2 s into a 0.5 s ramp
  const double mid = c.value();
  EXPECT_GT(mid, 0.2);
  EXPECT_LT(mid, 0.8);
  c.update(0.0, 0.002);  // open again: a new ramp from where it is
  EXPECT_LT(std::abs(c.value() - mid), 1e-4);
  EXPECT_NEAR(c.ramp_duration(), 0.5 * mid, 1e-12);
  for (int k = 0; k < 1000 && !c.settled(); ++k) c.update(0.0, 0.002);
  EXPECT_EQ(c.value(), 0.0);
}

TEST(RampedCommand, TargetsAreClampedAndBadInputRefusedOrIgnored) {
  RampedCommand c(0.3);
  c.reset(0.2);
  c.update(7.0, 1.0);  // clamped to the range
  EXPECT_EQ(c.value(), 1.0);
  c.update(std::nan(""), 1.0);  // NaN: the last target is kept
  EXPECT_EQ(c.target(), 1.0);
  EXPECT_EQ(c.value(), 1.0);
  c.update(0.0, std::nan(""));  // a bad dt advances nothing
  c.update(0.0, -1.0);
  EXPECT_EQ(c.value(), 1.0);
  c.reset(std::nan(""));
  EXPECT_EQ(c.value(), 0.0);
  // no allocation per update
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 200; ++k) c.update(k % 50 < 25 ? 1.0 : 0.0, 0.004);
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {0.0, -0.1, inf, std::nan("")}) EXPECT_THROW(RampedCommand{bad}, Error) << bad;
  EXPECT_THROW(RampedCommand(0.3, 1.0, 1.0), Error);
  EXPECT_THROW(RampedCommand(0.3, 1.0, 0.0), Error);
  EXPECT_THROW(RampedCommand(0.3, -inf, 0.0), Error);
}

}  // namespace
}  // namespace mjarm
