// The motion benchmarks' protocol: every case runs and reports consistent figures, the stop
// request ends a run, the 5-waypoint path plans, and bad settings are refused. (No timing is
// asserted: benchmarks are commands.)
#include "mjarm/planning/motion_benchmark.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

TEST(MotionBenchmark, EveryProfileCaseRuns) {
  ProfileBenchmarkOptions options;
  options.calls = 512;
  options.block = 64;
  options.recalculations = 16;
  options.thread_cpu_clock = true;
  int progress = 0;
  options.progress = [&](int done, int total) {
    progress = done;
    EXPECT_EQ(total, 7);
  };
  const ProfileBenchmarkResult r = run_profile_benchmark(options);
  EXPECT_FALSE(r.interrupted);
  ASSERT_EQ(r.cases.size(), 7u);
  EXPECT_EQ(progress, 7);
  for (const ProfileBenchmarkCase& c : r.cases) {
    EXPECT_EQ(c.calls, &c == &r.cases.back() ? 16 : 512) << c.name;
    EXPECT_GT(c.mean_ns, 0.0) << c.name;
    EXPECT_LE(c.median_ns, c.p99_ns) << c.name;
    EXPECT_EQ(c.allocations_per_call, -1.0);  // no counter given
  }
  EXPECT_EQ(r.cases.back().target_ns, kFilterRecalculationTargetNs);
  EXPECT_EQ(r.cases.front().target_ns, kProfileEvaluationTargetNs);
}

TEST(MotionBenchmark, AStopRequestEndsTheRun) {
  ProfileBenchmarkOptions options;
  options.calls = 1 << 20;
  options.stop = [] { return true; };
  const ProfileBenchmarkResult r = run_profile_benchmark(options);
  EXPECT_TRUE(r.interrupted);
  ASSERT_EQ(r.cases.size(), 1u);
  EXPECT_EQ(r.cases[0].calls, options.block);
}

TEST(MotionBenchmark, TheFiveWaypointPathPlans) {
  PlanBenchmarkOptions options;
  options.plans = 1;
  const PlanBenchmarkResult r = run_plan_benchmark(options);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.waypoints, 5);
  EXPECT_EQ(r.plans, 1);
  EXPECT_GT(r.duration, 1.0);
  EXPECT_GT(r.samples, 100);
  EXPECT_EQ(r.median_ms, r.max_ms);
  const std::vector<Pose> path = motion_benchmark_waypoints(Eigen::Matrix3d::Identity());
  ASSERT_EQ(path.size(), 5u);
  EXPECT_EQ(path[4].p, Eigen::Vector3d(0.40, -0.15, 0.50));
}

TEST(MotionBenchmark, BadSettingsAreRefused) {
  ProfileBenchmarkOptions few;
  few.calls = 10;  // fewer than a block
  EXPECT_THROW(run_profile_benchmark(few), Error);
  ProfileBenchmarkOptions block;
  block.block = 0;
  EXPECT_THROW(run_profile_benchmark(block), Error);
  ProfileBenchmarkOptions recalc;
  recalc.recalculations = 3;
  EXPECT_THROW(run_profile_benchmark(recalc), Error);
  PlanBenchmarkOptions none;
  none.plans = 0;
  EXPECT_THROW(run_plan_benchmark(none), Error);
}

}  // namespace
}  // namespace mjarm
