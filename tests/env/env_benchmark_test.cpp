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
  std::int64_t last = 0, total_seen = 0;
  o.progress = [&](std::int64_t done, std::int64_t total) {
    EXPECT_GT(done, last);  // counted in environment steps, forward only
    EXPECT_LE(done, total);
    last = done;
    total_seen = total;
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
  // every step counted: the round with its warmup, each run's batch steps (and warmup) × envs
  EXPECT_EQ(total_seen, 120 + 5 + 2 * 3 * (6 + 1));
  EXPECT_EQ(last, total_seen);
  EXPECT_EQ(r.rounds[0].steps, 120);
  EXPECT_EQ(r.vector_runs[0].batch_steps, 6);
}

TEST(EnvBenchmark, StopsWhenAskedAndChecksItsOptions) {
  EnvBenchmarkOptions o;
  o.steps = 20;
  o.rounds = 3;
  o.stop = [] { return true; };  // before the first timed step: nothing to report
  EnvBenchmarkResult r = run_env_benchmark(o);
  EXPECT_EQ(r.status, EnvBenchmarkStatus::interrupted);
  EXPECT_TRUE(r.rounds.empty());
  EXPECT_TRUE(r.vector_runs.empty());
  o.steps = 0;
  test::expect_error_containing([&] { run_env_benchmark(o); }, {"steps must be ≥ 1"});
}

// issue 29, item 12: the stop request was asked only between runs, so a run of a million steps
// went on for minutes after Ctrl-C; it is asked every chunk, and the figures cover the steps done
TEST(EnvBenchmark, AStopRequestEndsTheRoundUnderWayWithTheStepsDone) {
  EnvBenchmarkOptions o;
  o.steps = 1000000;
  o.warmup = 0;
  o.rounds = 2;
  int asked = 0;
  o.stop = [&] { return ++asked > 3; };  // asked at the start, then per chunk: the 3rd stops
  EnvBenchmarkResult r = run_env_benchmark(o);
  EXPECT_EQ(r.status, EnvBenchmarkStatus::interrupted);
  ASSERT_EQ(r.rounds.size(), 1u);
  EXPECT_EQ(r.rounds[0].steps, 150);  // three chunks of 50
  EXPECT_TRUE(r.rounds[0].replay_identical);
  EXPECT_GT(r.env_us_per_step, 0.0);
  EXPECT_TRUE(r.vector_runs.empty());

  // in a vectorized run: stopped after the batch step under way
  o.steps = 10;
  o.rounds = 1;
  o.envs = 2;
  o.batch_steps = 100000;
  asked = 0;
  // asked at the round's start and its one chunk, the batch warmup, then per batch step
  o.stop = [&] { return ++asked > 7; };
  r = run_env_benchmark(o);
  EXPECT_EQ(r.status, EnvBenchmarkStatus::interrupted);
  ASSERT_EQ(r.rounds.size(), 1u);
  EXPECT_EQ(r.rounds[0].steps, 10);
  ASSERT_EQ(r.vector_runs.size(), 1u);
  EXPECT_EQ(r.vector_runs[0].batch_steps, 5);
  EXPECT_GT(r.vector_runs[0].steps_per_second, 0.0);
  EXPECT_FALSE(r.threads_identical);  // not compared: the other thread count never ran
}

}  // namespace
}  // namespace mjarm
