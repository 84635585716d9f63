#include "mjarm/teleop/viewer_schedule.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

struct Totals {
  int polls = 0;
  int frames = 0;
  long ticks = 0;
};

// runs the schedule on a fake clock advancing by `dt` per loop iteration until `duration`
Totals run(ViewerSchedule& schedule, double start, double duration, double dt,
           bool paused = false) {
  Totals totals;
  const long steps = std::lround(duration / dt);
  for (long k = 0; k <= steps; ++k) {
    const ScheduleStep step = schedule.update(start + k * dt, paused);
    totals.polls += step.poll_input;
    totals.frames += step.render;
    totals.ticks += step.ticks;
  }
  return totals;
}

TEST(ViewerSchedule, RendersAt60HzPollsAt20HzAndKeepsPhysicsOnTheWallClock) {
  ViewerSchedule schedule(ViewerRates{}, 0.002, 10.0);
  // a fast loop (1 kHz) over 3 s of wall clock
  const Totals t = run(schedule, 10.0, 3.0, 0.001);
  EXPECT_NEAR(t.frames, 181, 1);  // 60 Hz over [0, 3] s, both ends included
  EXPECT_NEAR(t.polls, 61, 1);
  EXPECT_NEAR(t.ticks, 1500, 1);  // 3 s of simulated time in 2 ms ticks
  EXPECT_DOUBLE_EQ(schedule.dropped(), 0.0);
  EXPECT_EQ(schedule.frames(), t.frames);
  EXPECT_EQ(schedule.polls(), t.polls);
  EXPECT_EQ(schedule.ticks(), t.ticks);
}

TEST(ViewerSchedule, RatesDoNotDependOnHowOftenTheLoopRuns) {
  // a loop iterating at 240 Hz and one at 7 kHz see the same frames, polls and ticks
  ViewerSchedule a(ViewerRates{}, 0.002, 0.0);
  ViewerSchedule b(ViewerRates{}, 0.002, 0.0);
  const Totals ta = run(a, 0.0, 2.0, 1.0 / 240.0);
  const Totals tb = run(b, 0.0, 2.0, 1.0 / 7000.0);
  EXPECT_NEAR(ta.frames, tb.frames, 1);
  EXPECT_NEAR(ta.polls, tb.polls, 1);
  EXPECT_NEAR(ta.ticks, tb.ticks, 1);
}

TEST(ViewerSchedule, SlowMachineSlowsDownInsteadOfPilingUpABacklog) {
  ViewerRates rates;
  rates.max_catch_up = 0.05;
  ViewerSchedule schedule(rates, 0.002, 0.0);
  // each loop iteration takes 0.2 s of wall clock (physics and drawing too slow)
  const Totals t = run(schedule, 0.0, 2.0, 0.2);
  // at most max_catch_up of simulated time per iteration: 25 ticks each, never more
  EXPECT_EQ(t.ticks, 10 * 25);
  const double simulated = t.ticks * 0.002;
  EXPECT_LT(simulated, 2.0);
  EXPECT_NEAR(simulated + schedule.dropped(), 2.0, 1e-9);  // nothing lost track of
  // frames and polls are not made up in bursts: one each per iteration at most
  EXPECT_EQ(t.frames, 11);
  EXPECT_EQ(t.polls, 11);
  // when the machine becomes fast again, the dropped time is not paid back
  const Totals fast = run(schedule, 2.0 + 0.001, 1.0, 0.001);
  EXPECT_NEAR(fast.ticks, 500, 2);
}

TEST(ViewerSchedule, PauseAccruesNoSimulatedTime) {
  ViewerSchedule schedule(ViewerRates{}, 0.002, 0.0);
  const Totals paused = run(schedule, 0.0, 1.0, 0.001, true);
  EXPECT_EQ(paused.ticks, 0);
  EXPECT_GT(paused.frames, 55);  // drawing and input go on while paused
  EXPECT_GT(paused.polls, 18);
  // resuming does not replay the paused second
  const Totals resumed = run(schedule, 1.001, 0.5, 0.001);
  EXPECT_NEAR(resumed.ticks, 250, 1);
}

TEST(ViewerSchedule, SpeedScalesSimulatedTime) {
  ViewerRates rates;
  rates.speed = 0.5;
  ViewerSchedule slow(rates, 0.002, 0.0);
  EXPECT_NEAR(run(slow, 0.0, 2.0, 0.001).ticks, 500, 1);
  rates.speed = 2.0;
  ViewerSchedule fast(rates, 0.002, 0.0);
  EXPECT_NEAR(run(fast, 0.0, 2.0, 0.001).ticks, 2000, 1);
}

TEST(ViewerSchedule, PeriodLongerThanTheCatchUpCapStillTicks) {
  ViewerRates rates;
  rates.max_catch_up = 0.01;
  ViewerSchedule schedule(rates, 0.05, 0.0);  // one tick is 50 ms of simulated time
  EXPECT_NEAR(run(schedule, 0.0, 1.0, 0.001).ticks, 20, 1);
  EXPECT_NEAR(schedule.dropped(), 0.0, 1e-9);
}

TEST(ViewerSchedule, NextDueIsTheEarlierOfFrameAndPoll) {
  ViewerSchedule schedule(ViewerRates{}, 0.002, 0.0);
  const ScheduleStep first = schedule.update(0.0, false);
  EXPECT_TRUE(first.poll_input);
  EXPECT_TRUE(first.render);
  EXPECT_EQ(first.ticks, 0);
  EXPECT_NEAR(schedule.next_due(), 1.0 / 60.0, 1e-12);
  // a long stall: one frame and one poll, then the next ones a period later (no burst)
  const ScheduleStep late = schedule.update(5.0, false);
  EXPECT_TRUE(late.render);
  EXPECT_TRUE(late.poll_input);
  EXPECT_NEAR(schedule.next_due(), 5.0 + 1.0 / 60.0, 1e-12);
  const ScheduleStep again = schedule.update(5.0, false);
  EXPECT_FALSE(again.render);
  EXPECT_FALSE(again.poll_input);
}

TEST(ViewerSchedule, ClockGoingBackwardsCountsAsNoTime) {
  ViewerRates rates;
  rates.max_catch_up = 1.0;
  ViewerSchedule schedule(rates, 0.002, 1.0);
  EXPECT_NEAR(schedule.update(1.5, false).ticks, 250, 1);
  const ScheduleStep back = schedule.update(0.5, false);
  EXPECT_EQ(back.ticks, 0);
  EXPECT_EQ(schedule.update(std::numeric_limits<double>::quiet_NaN(), false).ticks, 0);
  EXPECT_NEAR(schedule.update(1.6, false).ticks, 50, 1);  // from 1.5, not from 0.5
}

TEST(ViewerSchedule, ChangingThePeriodAndClearingTheBacklog) {
  ViewerSchedule schedule(ViewerRates{}, 0.002, 0.0);
  schedule.update(0.0107, false);  // 5 ticks, 0.7 ms owed
  schedule.set_control_period(0.01);
  EXPECT_DOUBLE_EQ(schedule.control_period(), 0.01);
  EXPECT_EQ(schedule.update(0.0207, false).ticks, 1);
  schedule.set_control_period(-1.0);  // ignored
  EXPECT_DOUBLE_EQ(schedule.control_period(), 0.01);
  schedule.update(0.0287, false);  // 8 ms owed
  schedule.clear_backlog();
  EXPECT_EQ(schedule.update(0.0307, false).ticks, 0);  // 2 ms owed, not 10
}

TEST(ViewerSchedule, RejectsBadRates) {
  ViewerRates rates;
  rates.render_hz = 0.0;
  EXPECT_THROW(ViewerSchedule(rates, 0.002, 0.0), Error);
  rates = ViewerRates{};
  rates.input_hz = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ViewerSchedule(rates, 0.002, 0.0), Error);
  rates = ViewerRates{};
  rates.speed = -1.0;
  EXPECT_THROW(ViewerSchedule(rates, 0.002, 0.0), Error);
  EXPECT_THROW(ViewerSchedule(ViewerRates{}, 0.0, 0.0), Error);
  EXPECT_THROW(ViewerSchedule(ViewerRates{}, 0.002, std::nan("")), Error);
  try {
    rates = ViewerRates{};
    rates.max_catch_up = -0.1;
    ViewerSchedule bad(rates, 0.002, 0.0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("max_catch_up"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjarm
