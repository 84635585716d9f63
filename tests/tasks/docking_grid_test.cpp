#include <gtest/gtest.h>

#include <csignal>
#include <numbers>

#include "mjarm/interrupt.hpp"
#include "mjarm/tasks/docking/grid.hpp"
#include "support/error_message.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

/// Two offsets along x, the test's quick motion (see docking_test.cpp), two threads.
DockingGridOptions small_grid() {
  DockingGridOptions g;
  g.base.motion.start_height = 0.03;
  g.base.motion.approach_time = 0.6;
  g.base.motion.insertion_speed = 0.02;
  g.base.motion.hold_time = 1.2;
  g.x = {-0.006, 0.006};
  g.y = {0.0};
  g.yaw = {15.0 * std::numbers::pi / 180.0};
  g.jobs = 2;
  return g;
}

TEST(DockingGrid, RunsEveryOffsetInParallelAndSummarizes) {
  std::vector<int> reported;
  const DockingGridResult r = run_docking_grid(small_grid(), [&](int done, int planned) {
    EXPECT_EQ(planned, 2);
    reported.push_back(done);
  });
  EXPECT_FALSE(r.interrupted);
  EXPECT_EQ(r.controller, "se3");
  ASSERT_EQ(r.runs.size(), 2u);
  // matrix order, whatever thread finished first
  EXPECT_DOUBLE_EQ(r.runs[0].offset.dx, -0.006);
  EXPECT_DOUBLE_EQ(r.runs[1].offset.dx, 0.006);
  EXPECT_EQ(r.seated, 2);
  double peak = 0.0;
  for (const DockingGridRun& run : r.runs) peak = std::max(peak, run.metrics.peak_force);
  EXPECT_DOUBLE_EQ(r.max_peak_force, peak);
  EXPECT_TRUE(r.failures.empty());
  ASSERT_FALSE(reported.empty());
  EXPECT_EQ(reported.back(), 2);
  EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
  // the same as one run alone: the threads share nothing but the model
  DockingOptions alone = small_grid().base;
  alone.offset = r.runs[1].offset;
  const DockingReport single = run_docking(alone);
  EXPECT_EQ(single.metrics.peak_force, r.runs[1].metrics.peak_force);
  EXPECT_EQ(single.metrics.steady_lateral, r.runs[1].metrics.steady_lateral);
}

TEST(DockingGrid, AnInterruptStopsItAndKeepsTheRunsDone) {
  DockingGridOptions g = small_grid();
  g.jobs = 1;
  const InterruptGuard guard;
  const DockingGridResult r = run_docking_grid(g, [](int done, int) {
    if (done == 1) std::raise(SIGINT);  // after the first run
  });
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.planned, 2);
  EXPECT_LE(r.runs.size(), 1u);
}

TEST(DockingGrid, BadGridsAreNamed) {
  DockingGridOptions g = small_grid();
  g.y.clear();
  EXPECT_TRUE(contains(error_of([&] { run_docking_grid(g); }), "the y axis is empty"));
  g = small_grid();
  g.yaw = {std::nan("")};
  EXPECT_TRUE(contains(error_of([&] { run_docking_grid(g); }), "yaw value is not finite"));
  g = small_grid();
  g.x = {0.2};
  EXPECT_TRUE(contains(error_of([&] { run_docking_grid(g); }), "±0.05 m"));
  g = small_grid();
  g.jobs = -1;
  EXPECT_TRUE(contains(error_of([&] { run_docking_grid(g); }), "jobs"));
  g = small_grid();
  g.base.record = "somewhere";
  EXPECT_TRUE(contains(error_of([&] { run_docking_grid(g); }), "not to the grid"));
  g = small_grid();
  g.base.controller.se3_stiffness[0] = 0.0;
  EXPECT_TRUE(contains(error_of([&] { run_docking_grid(g); }), "se3_stiffness[0]"));
}

}  // namespace
}  // namespace mjarm
