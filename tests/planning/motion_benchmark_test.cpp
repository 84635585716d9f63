// The motion benchmarks' protocol: every case runs and reports consistent figures, the stop
// request ends a run, the 5-waypoint path plans, and bad settings are refused. (No timing is
// asserted: benchmarks are commands.)
#include "mjarm/planning/motion_benchmark.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

TEST(MotionBenchmark, EveryProfileCaseRuns) {
  ProfileBenchmarkOptions options;
  options.calls = 512;
  options.block = 64;
  options.recalculations = 16;
  options.thread_cpu_clock = true;
  std::int64_t progress = 0;
  options.progress = [&](std::int64_t done, std::int64_t total) {
    EXPECT_GT(done, progress);  // counted in calls, after each block
    progress = done;
    EXPECT_EQ(total, 6 * 512 + 16);
  };
  const ProfileBenchmarkResult r = run_profile_benchmark(options);
  EXPECT_FALSE(r.interrupted);
  ASSERT_EQ(r.cases.size(), 7u);
  EXPECT_EQ(progress, 6 * 512 + 16);
  for (const ProfileBenchmarkCase& c : r.cases) {
    EXPECT_EQ(c.calls, &c == &r.cases.back() ? 16 : 512) << c.name;
    EXPECT_GT(c.mean_ns, 0.0) << c.name;
    EXPECT_LE(c.median_ns, c.p99_ns) << c.name;
    EXPECT_EQ(c.allocations_per_call, -1.0);  // no counter given
  }
  EXPECT_EQ(r.cases.back().target_ns, kFilterRecalculationTargetNs);
  EXPECT_EQ(r.cases.front().target_ns, kProfileEvaluationTargetNs);
}

// the profiles shared with bench_trajectory: the seeded cases as the file comment states them
TEST(MotionBenchmark, SharedProfilesAndInstants) {
  const MotionBenchmarkProfiles m;
  EXPECT_NEAR(m.trapezoid.at(m.trapezoid.duration()).position, 0.5, 1e-12);
  EXPECT_EQ(m.quintic_start.q.size(), MotionBenchmarkProfiles::kJoints);
  EXPECT_DOUBLE_EQ(m.quintic.duration(), 1.3);
  EXPECT_DOUBLE_EQ(m.se3.duration(), 0.8);
  EXPECT_DOUBLE_EQ(m.ramp.duration(), 0.4);
  Eigen::VectorXd q(7), qd(7), qdd(7);
  m.quintic.at(0.0, q, qd, qdd);
  EXPECT_TRUE(q.isApprox(m.quintic_start.q, 1e-12));
  EXPECT_TRUE(qd.isApprox(m.quintic_start.qd, 1e-12));
  m.synced.at(m.synced.duration(), q, qd, qdd);
  EXPECT_LE(qd.cwiseAbs().maxCoeff(), 1e-12);
  const auto t = motion_benchmark_instants(2.0);
  for (const double x : t) {
    EXPECT_GE(x, -0.1);
    EXPECT_LE(x, 2.1);
  }
  EXPECT_EQ(t, motion_benchmark_instants(2.0));  // seeded
  const MotionBenchmarkPath path = motion_benchmark_path(Robot::bundled("panda_torque"));
  EXPECT_EQ(path.waypoints.size(), 5u);
  EXPECT_EQ(path.q_home.size(), path.chain.size());
}

// the clocks and the percentile every benchmark protocol uses
TEST(MotionBenchmark, TimingHelpers) {
  const double c0 = thread_cpu_seconds(), w0 = steady_seconds();
  volatile double sink = 0.0;
  for (int i = 0; i < 200000; ++i) sink = sink + std::sqrt(static_cast<double>(i));
  EXPECT_GT(thread_cpu_seconds(), c0);
  EXPECT_GE(steady_seconds(), w0);
  EXPECT_GE(benchmark_seconds(true), c0);
  EXPECT_GE(benchmark_seconds(false), w0);
  const std::vector<double> sorted{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_EQ(nearest_rank(sorted, 0.5), 5.0);
  EXPECT_EQ(nearest_rank(sorted, 0.99), 10.0);
  EXPECT_EQ(nearest_rank(sorted, 0.01), 1.0);
  EXPECT_EQ(nearest_rank({}, 0.5), 0.0);
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
