// WorkerPool: every index runs exactly once on any thread count; a job's exception comes back
// to the caller after the others ran.

#include "mjarm/env/worker_pool.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>

#include "env/env_test_support.hpp"

namespace mjarm {
namespace {

TEST(WorkerPool, RunsEveryIndexOnce) {
  for (int threads : {1, 2, 4}) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (int round = 0; round < 50; ++round) {
      std::vector<std::atomic<int>> hits(37);
      auto job = [&](int i) { hits[static_cast<std::size_t>(i)].fetch_add(1); };
      pool.run(37, job);
      for (const auto& h : hits) ASSERT_EQ(h.load(), 1) << threads;
    }
    auto nothing = [](int) { FAIL(); };
    pool.run(0, nothing);
  }
}

TEST(WorkerPool, RethrowsTheFirstExceptionAfterEveryJobRan) {
  WorkerPool pool(2);
  std::atomic<int> ran{0};
  auto job = [&](int i) {
    ran.fetch_add(1);
    if (i == 3) throw std::runtime_error("job 3 failed");
  };
  EXPECT_THROW(pool.run(10, job), std::runtime_error);
  EXPECT_EQ(ran.load(), 10);
  auto fine = [&](int) { ran.fetch_add(1); };
  EXPECT_NO_THROW(pool.run(5, fine));  // the pool stays usable
  EXPECT_EQ(ran.load(), 15);
}

// the CPU time of each thread's share: one entry per thread, the caller's first; a run where the
// caller does all the work (one job) puts (nearly) all of it in entry 0
TEST(WorkerPool, ReportsEachThreadsCpuTime) {
  WorkerPool pool(2);
  volatile double sink = 0.0;
  auto busy = [&](int) {
    double x = 0.0;
    for (int k = 0; k < 2000000; ++k) x += std::sqrt(static_cast<double>(k));
    sink = sink + x;
  };
  pool.run(8, busy);
  ASSERT_EQ(pool.last_cpu_seconds().size(), 2u);
  const double total = pool.last_cpu_seconds()[0] + pool.last_cpu_seconds()[1];
  EXPECT_GT(total, 0.0);
  for (double c : pool.last_cpu_seconds()) EXPECT_GE(c, 0.0);
  WorkerPool single(1);
  single.run(2, busy);
  ASSERT_EQ(single.last_cpu_seconds().size(), 1u);
  EXPECT_GT(single.last_cpu_seconds()[0], 0.0);
}

TEST(WorkerPool, ThreadCountsOutOfRangeAreErrors) {
  test::expect_error_containing([] { WorkerPool pool(0); }, {"from 1 to 256, got 0"});
  test::expect_error_containing([] { WorkerPool pool(300); }, {"got 300"});
}

}  // namespace
}  // namespace mjarm
