// FrameSchedule: video frames at video rate from simulation time.

#include "mjarm/render/frame_schedule.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

// steps a clock of period dt for duration T and counts the frames due
std::int64_t frames_over(double fps, double dt, double duration) {
  FrameSchedule schedule(fps);
  std::int64_t total = schedule.frames_due(0.0);
  const auto steps = static_cast<std::int64_t>(std::llround(duration / dt));
  for (std::int64_t k = 1; k <= steps; ++k) total += schedule.frames_due(static_cast<double>(k) * dt);
  EXPECT_EQ(total, schedule.frames());
  return total;
}

TEST(FrameSchedule, OneFramePerPeriodWhateverTheStep) {
  // 2 s of simulated time at 30 frames/s: frames 0 … 60
  EXPECT_EQ(frames_over(30.0, 0.002, 2.0), 61);
  EXPECT_EQ(frames_over(30.0, 0.001, 2.0), 61);
  EXPECT_EQ(frames_over(30.0, 0.0013, 2.6), 79);  // dt not dividing 1/30
  EXPECT_EQ(frames_over(25.0, 0.01, 1.0), 26);    // k·dt with rounding error must not skip
}

TEST(FrameSchedule, StepsLongerThanAFrameOweSeveralFrames) {
  FrameSchedule schedule(50.0);
  EXPECT_EQ(schedule.frames_due(0.0), 1);
  EXPECT_EQ(schedule.frames_due(0.1), 5);  // frames at 0.02 … 0.1
  EXPECT_EQ(schedule.frames_due(0.1), 0);  // already counted
  EXPECT_EQ(schedule.frames_due(0.05), 0);  // time going back owes nothing
  EXPECT_NEAR(schedule.next_time(), 0.12, 1e-12);
}

TEST(FrameSchedule, StartTimeAndBadInput) {
  FrameSchedule schedule(10.0, 1.0);
  EXPECT_EQ(schedule.frames_due(0.5), 0);
  EXPECT_EQ(schedule.frames_due(1.0), 1);
  EXPECT_EQ(schedule.frames_due(NAN), 0);
  EXPECT_THROW(FrameSchedule{0.0}, Error);
  EXPECT_THROW(FrameSchedule{-30.0}, Error);
  EXPECT_THROW(FrameSchedule{INFINITY}, Error);
  EXPECT_THROW((FrameSchedule{30.0, NAN}), Error);
}

}  // namespace
}  // namespace mjarm
