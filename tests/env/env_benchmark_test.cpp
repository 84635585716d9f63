// The environment benchmark's protocol on a small budget: the replay reproduces the
// environment's physics bit for bit, the thread counts agree, the figures are consistent.
// (Timings are reported by `mjarm bench env`, never asserted.)

#include "mjarm/env/env_benchmark.hpp"

#include <gtest/gtest.h>

#include "env/env_test_support.hpp"

namespace mjarm {
namespace {

TEST(EnvBenchmark, ReplaysTheSamePhysicsAndComparesThreadCounts) {
  EnvBenchmarkOptions o;
  o.steps = 120;  // more than one chunk of the interleaved replay
  o.warmup = 5;
  o.rounds = 1;
  o.envs = 3;
  o.batch_steps = 6;
  int calls = 0;
  o.progress = [&](int done, int total) {
    ++calls;
    EXPECT_LE(done, total);
  };
  const EnvBenchmarkResult r = run_env_benchmark(o);
  EXPECT_EQ(r.status, EnvBenchmarkStatus::ok);
  EXPECT_EQ(r.physics_steps_per_step, 10);
  ASSERT_EQ(r.rounds.size(), 1u);
  EXPECT_TRUE(r.rounds[0].replay_identical);
  EXPECT_TRUE(r.replay_identical);
  EXPECT_GT(r.rounds[0].bare_cpu_s, 0.0);
  EXPECT_GT(r.env_us_per_step, 0.0);
  EXPECT_EQ(r.vector_runs.size(), 2u);
  ASSERT_EQ(r.best.size(), 2u);
  EXPECT_EQ(r.best[1].threads, 2);
  EXPECT_TRUE(r.threads_identical);
  EXPECT_GT(r.speedup, 0.0);
  // the CPU-clock scaling: the critical path of a step is at least half its work on 2 threads
  // and at most all of it
  for (const VectorRun& run : r.vector_runs) {
    EXPECT_GT(run.critical_cpu_s, 0.0);
    EXPECT_LE(run.critical_cpu_s, run.work_cpu_s * (1.0 + 1e-12));
    if (run.threads == 2) {
      EXPECT_GE(run.critical_cpu_s, 0.5 * run.work_cpu_s * (1.0 - 1e-12));
    } else {
      EXPECT_DOUBLE_EQ(run.critical_cpu_s, run.work_cpu_s);
    }
  }
  EXPECT_GE(r.cpu_speedup, 1.0);  // work / critical path: from 1 to the thread count
  EXPECT_LE(r.cpu_speedup, 2.0 + 1e-12);
  EXPECT_GT(r.cpu_cost_ratio, 0.0);
  EXPECT_EQ(calls, 3);
}

TEST(EnvBenchmark, StopsWhenAskedAndChecksItsOptions) {
  EnvBenchmarkOptions o;
  o.steps = 20;
  o.rounds = 3;
  o.stop = [] { return true; };
  const EnvBenchmarkResult r = run_env_benchmark(o);
  EXPECT_EQ(r.status, EnvBenchmarkStatus::interrupted);
  EXPECT_EQ(r.rounds.size(), 1u);
  EXPECT_TRUE(r.vector_runs.empty());
  o.steps = 0;
  test::expect_error_containing([&] { run_env_benchmark(o); }, {"steps must be ≥ 1"});
}

}  // namespace
}  // namespace mjarm
