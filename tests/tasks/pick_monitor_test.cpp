#include "mjarm/tasks/pick_monitor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

const Eigen::Vector3d kStart(0.5, 0.0, 1.0);
const Eigen::Vector3d kTarget(0.6, 0.0, 1.0);  // approach along +x
const Eigen::Vector3d kUx = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kUz = Eigen::Vector3d::UnitZ();
constexpr double kDt = 0.002;

/// Feeds `offset(t)` (tip minus target) at t = k·dt, k = 0..steps; returns the events.
std::vector<PickEvent> feed(PickMonitor& monitor, const std::function<Eigen::Vector3d(double)>& offset,
                            int steps) {
  std::vector<PickEvent> events;
  for (int k = 0; k <= steps; ++k) {
    const double t = k * kDt;
    events.push_back(monitor.observe(t, kTarget + offset(t)));
  }
  return events;
}

int count(const std::vector<PickEvent>& events, PickEvent which) {
  int n = 0;
  for (PickEvent e : events) n += e == which;
  return n;
}

TEST(PickMonitor, ApproachOvershootAndHold) {
  // along the approach: 10 mm short, closing at 0.1 m/s until 0.1 s, then 0.5 mm past the target
  // until 0.15 s, then 0.2 mm past it for good; a 0.3 mm sideways offset throughout
  PickMonitor monitor(kStart, kTarget);
  auto offset = [](double t) -> Eigen::Vector3d {
    double along = 0.0;
    if (t < 0.1 - 1e-12) along = -0.01 + 0.1 * t;
    else if (t < 0.15 - 1e-12) along = 0.0005;
    else along = 0.0002;
    return along * kUx + 0.0003 * kUz;
  };
  const auto events = feed(monitor, offset, 400);
  const PickMetrics& m = monitor.metrics();
  ASSERT_TRUE(m.held);
  // ‖(−0.01 + 0.1t, 0.0003)‖ ≤ 1 mm from t = 0.1 − √(1e-6 − 9e-8)/0.1 = 0.090461 s: first sample 0.092
  EXPECT_NEAR(m.first_entry_time, 0.092, 1e-12);
  EXPECT_EQ(m.time_to_tolerance, m.first_entry_time);
  EXPECT_NEAR(m.hold_end_time, 0.292, 1e-12);
  EXPECT_EQ(m.exits, 0);
  EXPECT_NEAR(m.overshoot, 0.0005, 1e-15);  // the sideways 0.3 mm is not overshoot
  // whole hold: samples 0.092 … 0.292 (101); the largest is the entry sample, √(0.8² + 0.3²) mm
  EXPECT_NEAR(m.hold_max, std::hypot(0.0008, 0.0003), 1e-15);
  // mean: 4 samples on the ramp, 25 at 0.583 mm, 72 at 0.361 mm
  double sum = 0.0;
  for (int k = 46; k <= 49; ++k) sum += std::hypot(-0.01 + 0.1 * k * kDt, 0.0003);
  sum += 25 * std::hypot(0.0005, 0.0003) + 72 * std::hypot(0.0002, 0.0003);
  EXPECT_NEAR(m.hold_mean, sum / 101.0, 1e-15);
  // steady state: the last 100 ms (0.192 … 0.292, 51 samples), all at 0.361 mm
  EXPECT_NEAR(m.steady_state_mean, std::hypot(0.0002, 0.0003), 1e-15);
  EXPECT_NEAR(m.steady_state_max, std::hypot(0.0002, 0.0003), 1e-15);
  EXPECT_EQ(count(events, PickEvent::entered), 1);
  EXPECT_EQ(count(events, PickEvent::held), 1);
  // after the hold, samples are ignored
  EXPECT_EQ(m.samples, 147);
  EXPECT_EQ(events.back(), PickEvent::none);
}

TEST(PickMonitor, LeavingRestartsTheHold) {
  // inside 0.05–0.10 s, out (1.5 mm past) 0.10–0.20 s, inside again from 0.20 s
  PickMonitor monitor(kStart, kTarget, {1e-3, 0.2, 0.1});
  auto offset = [](double t) -> Eigen::Vector3d {
    if (t < 0.05 - 1e-12) return -0.005 * kUx;
    if (t < 0.10 - 1e-12) return -0.0004 * kUx;
    if (t < 0.20 - 1e-12) return 0.0015 * kUx;
    return 0.0001 * kUx;
  };
  const auto events = feed(monitor, offset, 300);
  const PickMetrics& m = monitor.metrics();
  ASSERT_TRUE(m.held);
  EXPECT_NEAR(m.first_entry_time, 0.05, 1e-12);
  EXPECT_NEAR(m.time_to_tolerance, 0.20, 1e-12);
  EXPECT_NEAR(m.hold_end_time, 0.40, 1e-12);
  EXPECT_EQ(m.exits, 1);
  EXPECT_NEAR(m.overshoot, 0.0015, 1e-15);
  EXPECT_NEAR(m.hold_mean, 0.0001, 1e-15);  // only the completed stay counts
  EXPECT_NEAR(m.hold_max, 0.0001, 1e-15);
  EXPECT_NEAR(m.steady_state_mean, 0.0001, 1e-15);
  EXPECT_NEAR(m.steady_state_max, 0.0001, 1e-15);
  EXPECT_EQ(count(events, PickEvent::entered), 2);
  EXPECT_EQ(count(events, PickEvent::left), 1);
}

TEST(PickMonitor, NeverEnteringReportsNothingHeld) {
  PickMonitor monitor(kStart, kTarget);
  const auto events = feed(monitor, [](double) { return Eigen::Vector3d(-0.002, 0, 0); }, 500);
  const PickMetrics& m = monitor.metrics();
  EXPECT_FALSE(m.held);
  EXPECT_TRUE(std::isnan(m.first_entry_time));
  EXPECT_TRUE(std::isnan(m.time_to_tolerance));
  EXPECT_TRUE(std::isnan(m.steady_state_mean));
  EXPECT_TRUE(std::isnan(m.steady_state_max));
  EXPECT_TRUE(std::isnan(m.hold_mean));
  EXPECT_EQ(m.overshoot, 0.0);
  EXPECT_NEAR(m.final_error, 0.002, 1e-15);
  EXPECT_EQ(count(events, PickEvent::none), 501);
}

TEST(PickMonitor, ANanTipCountsAsOutside) {
  PickMonitor monitor(kStart, kTarget);
  EXPECT_EQ(monitor.observe(0.0, kTarget), PickEvent::entered);
  const double nan = std::nan("");
  EXPECT_EQ(monitor.observe(0.002, Eigen::Vector3d(nan, 0, 0)), PickEvent::left);
  EXPECT_FALSE(monitor.inside());
  EXPECT_EQ(monitor.metrics().overshoot, 0.0);
}

TEST(PickMonitor, StartOnTheTargetMeasuresOvershootInAnyDirection) {
  PickMonitor monitor(kTarget, kTarget);
  EXPECT_TRUE(monitor.approach_direction().isZero());
  feed(monitor, [](double t) { return Eigen::Vector3d(0, 0, t < 0.01 ? -0.0007 : 0.0001); }, 200);
  EXPECT_TRUE(monitor.metrics().held);
  EXPECT_EQ(monitor.metrics().time_to_tolerance, 0.0);
  EXPECT_NEAR(monitor.metrics().overshoot, 0.0007, 1e-15);
}

TEST(PickMonitor, SteadyStateIsTheEndOfTheHold) {
  // the error halves every 10 ms after entering at 0.8 mm: the steady window sees only the tail
  PickMonitor monitor(kStart, kTarget, {1e-3, 0.2, 0.05});
  auto offset = [](double t) -> Eigen::Vector3d {
    return t < 0.1 - 1e-12 ? Eigen::Vector3d(-0.002, 0, 0)
                           : Eigen::Vector3d(-0.0008 * std::exp2(-(t - 0.1) / 0.01), 0, 0);
  };
  feed(monitor, offset, 200);
  const PickMetrics& m = monitor.metrics();
  ASSERT_TRUE(m.held);
  EXPECT_NEAR(m.time_to_tolerance, 0.1, 1e-12);
  // window 0.25 … 0.30 s: 26 samples, largest at 0.25 s
  EXPECT_NEAR(m.steady_state_max, 0.0008 * std::exp2(-15.0), 1e-12);
  double sum = 0.0;
  for (int k = 125; k <= 150; ++k) sum += 0.0008 * std::exp2(-(k * kDt - 0.1) / 0.01);
  EXPECT_NEAR(m.steady_state_mean, sum / 26.0, 1e-15);
  EXPECT_NEAR(m.hold_max, 0.0008, 1e-15);
  EXPECT_GT(m.hold_mean, 10 * m.steady_state_mean);
}

TEST(PickMonitor, OrientationErrorIsTrackedOverTheHold) {
  PickMonitor monitor(kStart, kTarget, {1e-3, 0.01, 0.01});
  monitor.observe(0.0, kTarget, 0.3);  // entered
  monitor.observe(0.005, kTarget, 0.02);
  EXPECT_EQ(monitor.observe(0.01, kTarget, 0.01), PickEvent::held);
  EXPECT_EQ(monitor.metrics().orientation_error_max, 0.3);
}

TEST(PickMonitor, RejectsBadInput) {
  const double nan = std::nan("");
  EXPECT_THROW(PickMonitor(Eigen::Vector3d(nan, 0, 0), kTarget), Error);
  EXPECT_THROW(PickMonitor(kStart, Eigen::Vector3d(0, nan, 0)), Error);
  EXPECT_THROW(PickMonitor(kStart, kTarget, {0.0, 0.2, 0.1}), Error);
  EXPECT_THROW(PickMonitor(kStart, kTarget, {1e-3, -1.0, 0.1}), Error);
  EXPECT_THROW(PickMonitor(kStart, kTarget, {1e-3, INFINITY, 0.1}), Error);
  EXPECT_THROW(PickMonitor(kStart, kTarget, {1e-3, 0.2, 0.0}), Error);
  EXPECT_THROW(PickMonitor(kStart, kTarget, {1e-3, 0.2, 0.3}), Error);
}

}  // namespace
}  // namespace mjarm
