#include "mjarm/ik/ik_benchmark.hpp"

#include <gtest/gtest.h>

#include <ctime>
#include <vector>

#include "ik/local_ik_support.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using std::chrono::milliseconds;

/// The protocol's 5 ms budget makes its success rate a figure of the machine (a slower CPU, a
/// loaded one, a sanitized build solve fewer in time): `mjarm bench ik` measures it. The tests
/// judge the protocol on outcomes that are the same on any machine: a restart cap decides every
/// solve (the solver's iterates do not depend on time; the most restarts any sample here needs
/// is 84), and the budget lies far beyond what the cap's restarts take.
constexpr int kBenchmarkRestartCap = 200;
constexpr std::chrono::seconds kBenchmarkBudget{60};

using test::chain_of;

void expect_consistent(const IkBenchmarkResult& r, int samples) {
  EXPECT_EQ(r.samples, samples);
  EXPECT_LE(r.successes, r.samples);
  EXPECT_DOUBLE_EQ(r.success_rate, static_cast<double>(r.successes) / r.samples);
  EXPECT_GT(r.median_time_ms, 0.0);
  EXPECT_LE(r.median_time_ms, r.p99_time_ms);
  EXPECT_LE(r.p99_time_ms, r.max_time_ms);
  EXPECT_LE(r.mean_time_ms, r.max_time_ms);
  EXPECT_GT(r.mean_iterations, 0.0);
}

TEST(IkBenchmark, TracIkProtocolOnPandaMidRangeSeeds) {
  const Chain chain = chain_of("panda");
  IkBenchmarkOptions options;
  options.samples = 200;
  options.timeout = kBenchmarkBudget;
  options.max_restarts = kBenchmarkRestartCap;
  options.clock = IkBenchmarkClock::thread_cpu;
  int calls = 0, last = 0;
  options.progress = [&](int done, int total) {
    EXPECT_EQ(done, last + 1);
    EXPECT_EQ(total, 200);
    last = done;
    ++calls;
  };
  const IkBenchmarkResult r = run_ik_benchmark(chain, options);
  expect_consistent(r, 200);
  EXPECT_GE(r.success_rate, 0.99);
  EXPECT_EQ(calls, 200);
  EXPECT_EQ(r.solver, "global_ik(alternate, speed)");
  EXPECT_EQ(r.robot, "panda");
  EXPECT_EQ(r.frame, "attachment_site");
  EXPECT_DOUBLE_EQ(r.timeout_ms, 60000.0);
  EXPECT_EQ(r.seed_mode, IkSeedMode::mid_range);
  // the solver's own status agrees with the independent check on every sample it solved
  EXPECT_GE(r.solver_converged, r.successes);
}

TEST(IkBenchmark, TracIkProtocolRandomSeedsOnEveryArm) {
  for (const char* robot : {"panda", "iiwa14", "ur5e"}) {
    IkBenchmarkOptions options;
    options.samples = 100;
    options.seed = 17;
    options.seed_mode = IkSeedMode::random;
    options.timeout = kBenchmarkBudget;
    options.max_restarts = kBenchmarkRestartCap;
    options.clock = IkBenchmarkClock::thread_cpu;
    const IkBenchmarkResult r = run_ik_benchmark(chain_of(robot), options);
    expect_consistent(r, 100);
    EXPECT_GE(r.success_rate, 0.99) << robot;
  }
}

TEST(IkBenchmark, JudgesByItsOwnKinematicsNotTheSolversWord) {
  // a solver that claims success but returns its seed: every sample must fail
  const Chain chain = chain_of("panda");
  IkBenchmarkSolver liar{"liar", [&](const Pose&, const Eigen::VectorXd& q_seed) {
                           IkResult r;
                           r.q = q_seed;
                           r.status = IkStatus::converged;
                           return r;
                         }};
  IkBenchmarkOptions options;
  options.samples = 50;
  const IkBenchmarkResult r = run_ik_benchmark(chain, liar, options);
  EXPECT_EQ(r.successes, 0);
  EXPECT_EQ(r.solver_converged, 50);
  EXPECT_EQ(r.solver, "liar");
  EXPECT_EQ(r.mean_iterations, 0.0);

  // an exact answer outside the limits fails too
  IkBenchmarkSolver outside{"outside", [&](const Pose&, const Eigen::VectorXd&) {
                              IkResult r;
                              r.q = chain.upper() + Eigen::VectorXd::Constant(7, 1e-9);
                              return r;
                            }};
  EXPECT_EQ(run_ik_benchmark(chain, outside, options).successes, 0);
}

TEST(IkBenchmark, WallClockRunAndCpuBudgetCharging) {
  const Chain chain = chain_of("iiwa14");
  IkBenchmarkOptions options;
  options.samples = 30;
  options.timeout = kBenchmarkBudget;
  options.max_restarts = kBenchmarkRestartCap;
  const IkBenchmarkResult wall = run_ik_benchmark(chain, options);
  expect_consistent(wall, 30);
  EXPECT_EQ(wall.clock, IkBenchmarkClock::wall);
  EXPECT_EQ(wall.successes, 30);  // the cap decides, not the clock: none lost to descheduling

  // a solver burning 3 ms of CPU against a 1 ms CPU budget: every sample fails, charged 1 ms
  GlobalIkOptions roomy;
  roomy.timeout = std::chrono::seconds(10);
  GlobalIk ik(chain, roomy);
  IkBenchmarkSolver slow{"slow", [&](const Pose& X_WT, const Eigen::VectorXd& q_seed) {
                           IkResult r = ik.solve(X_WT, q_seed);
                           const auto until = std::clock() + 3 * CLOCKS_PER_SEC / 1000;
                           while (std::clock() < until) {
                           }
                           return r;
                         }};
  options.samples = 5;
  options.timeout = milliseconds(1);
  options.clock = IkBenchmarkClock::thread_cpu;
  const IkBenchmarkResult r = run_ik_benchmark(chain, slow, options);
  EXPECT_EQ(r.successes, 0);
  EXPECT_EQ(r.solver_converged, 5);
  EXPECT_DOUBLE_EQ(r.max_time_ms, 1.0);
  EXPECT_DOUBLE_EQ(r.median_time_ms, 1.0);
}

TEST(IkBenchmark, SeedModesShareTheTargetsAndDifferInSeeds) {
  const Chain chain = chain_of("ur5e");
  std::vector<Pose> targets[2];
  std::vector<Eigen::VectorXd> seeds[2];
  for (int run = 0; run < 2; ++run) {
    IkBenchmarkSolver recorder{"recorder", [&, run](const Pose& X, const Eigen::VectorXd& s) {
                                 targets[run].push_back(X);
                                 seeds[run].push_back(s);
                                 IkResult r;
                                 r.q = s;
                                 return r;
                               }};
    IkBenchmarkOptions options;
    options.samples = 20;
    options.seed = 99;
    options.seed_mode = run == 0 ? IkSeedMode::mid_range : IkSeedMode::random;
    run_ik_benchmark(chain, recorder, options);
  }
  ASSERT_EQ(targets[0].size(), 20u);
  for (int k = 0; k < 20; ++k) {
    EXPECT_TRUE(targets[0][k].is_approx(targets[1][k], 0.0));
    EXPECT_EQ(seeds[0][k], chain.center());
    EXPECT_TRUE(chain.within_limits(seeds[1][k]));
    EXPECT_GT((seeds[1][k] - chain.center()).norm(), 1e-3);
  }
  EXPECT_FALSE(targets[0][0].is_approx(targets[0][1], 1e-3));
}

TEST(IkBenchmark, HugeTimeoutsDoNotFailEverySample) {
  // a timeout beyond int64 nanoseconds (1e308 ms) reported 0 % success: the deadline overflowed
  const Chain chain = chain_of("panda");
  for (const IkBenchmarkClock clock : {IkBenchmarkClock::wall, IkBenchmarkClock::thread_cpu}) {
    IkBenchmarkOptions options;
    options.samples = 5;
    options.timeout = std::chrono::duration<double>(1e305);
    options.clock = clock;
    const IkBenchmarkResult r = run_ik_benchmark(chain, options);
    EXPECT_EQ(r.successes, 5) << to_string(clock);
  }
}

// a stop request (Ctrl-C in `mjarm bench ik`) ends the run with the figures of the samples done
TEST(IkBenchmark, AStopRequestEndsTheRunWithTheSamplesDone) {
  const Chain chain(Robot::bundled("panda"), "attachment_site");
  IkBenchmarkOptions options;
  options.samples = 1000;
  options.timeout = kBenchmarkBudget;
  options.max_restarts = kBenchmarkRestartCap;
  int asked = 0;
  options.stop = [&] { return ++asked > 20; };
  const IkBenchmarkResult r = run_ik_benchmark(chain, options);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.samples, 20);
  EXPECT_EQ(r.successes, 20);
  EXPECT_DOUBLE_EQ(r.success_rate, static_cast<double>(r.successes) / 20.0);
  EXPECT_GT(r.mean_time_ms, 0.0);
  options.stop = [] { return true; };
  const IkBenchmarkResult none = run_ik_benchmark(chain, options);
  EXPECT_TRUE(none.interrupted);
  EXPECT_EQ(none.samples, 0);
  EXPECT_EQ(none.mean_time_ms, 0.0);
}

TEST(IkBenchmark, BadInputsThrow) {
  const Chain chain = chain_of("panda");
  IkBenchmarkOptions options;
  options.samples = 0;
  EXPECT_THROW(run_ik_benchmark(chain, options), Error);
  options.samples = 10;
  EXPECT_THROW(run_ik_benchmark(chain, IkBenchmarkSolver{"empty", {}}, options), Error);
  options.timeout = milliseconds(0);
  EXPECT_THROW(run_ik_benchmark(chain, options), Error);
  options.timeout = milliseconds(5);
  options.max_restarts = -1;
  EXPECT_THROW(run_ik_benchmark(chain, options), Error);
  options.max_restarts = kBenchmarkRestartCap;
  options.tolerance.bound[0] = -1.0;
  EXPECT_THROW(run_ik_benchmark(chain, options), Error);
}

}  // namespace
}  // namespace mjarm
