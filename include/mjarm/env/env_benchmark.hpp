#pragma once
/// @file
/// The environment benchmark: what an environment step costs beyond the physics it runs, and
/// how a vectorized batch scales from one thread to several.
///
/// Protocol.
/// 1. Overhead, one thread, thread CPU time (CLOCK_THREAD_CPUTIME_ID, so that other processes
///    on a shared machine do not count). An `Environment` (task, action space, control period)
///    takes `steps` steps with actions drawn uniformly within the action bounds (seeded, drawn
///    before the clock starts), resetting (timed too) whenever an episode ends, after `warmup`
///    untimed steps. The state at each episode's start and the actuator inputs of every step
///    are kept; then the same physics is replayed with bare `mj_step` calls on a fresh
///    `mjData` — each episode from its start state, each control step's inputs held over its
///    physics steps — and only the `mj_step` calls are timed. The replay must end in the
///    environment's final state bit for bit (reported). Overhead = environment time / bare
///    time − 1: everything an environment step adds to its physics (action checks, the QP
///    and controller, the simulation's bookkeeping and divergence checks, observation, reward,
///    resets). `rounds` rounds alternate the two; the median is reported.
/// 2. Scaling, wall clock. A `VectorEnvironment` of `envs` environments takes `batch_steps`
///    batch steps (seeded random actions, automatic resets) on 1 thread and on `max_threads`
///    threads, alternating, `rounds` times; the best rate of each thread count is kept (the
///    least disturbed by other processes), the speedup is their ratio, and the process CPU time
///    of each run is reported with the load average before and after (/proc/loadavg), because
///    on a shared machine the wall-clock scaling depends on what else runs (a worker that
///    gets no core leaves the caller's thread to step the whole batch). The CPU clock gives a
///    figure that does not: the thread CPU time of each environment's part of each batch step
///    (`VectorEnvironment::last_env_cpu_seconds`), measured in the run of each thread count.
///    Work = their sum; critical path = for each batch step, the time the last of T threads
///    finishes when the environments are handed out in index order to whichever thread is free
///    first (the pool's rule) with every thread on a core of its own, summed over the steps.
///    CPU speedup = the median over the max-thread runs of work / critical path: the speedup
///    free cores would give at the CPU cost per environment step measured in the threaded run
///    (the batch's imbalance included; the pool's wake-up latency and the waits for a core left
///    out). CPU cost ratio = the median work of the max-thread runs / that of the one-thread
///    runs: what threading adds to each environment step's CPU time (caches shared by the
///    threads), which on a loaded machine also carries the run-to-run spread of the CPU clock.
///    The final batch arrays of the thread counts are compared bit for bit.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mjarm/env/action_space.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// Settings of `run_env_benchmark`.
struct EnvBenchmarkOptions {
  std::string task = "reach";
  ActionSpace action_space = ActionSpace::ee_pose_deltas;
  double control_period = 0.02;  ///< [s]: 10 physics steps of 2 ms on the bundled models
  int steps = 5000;              ///< timed environment steps per round (≥ 1)
  int warmup = 100;              ///< untimed steps before each timed run (≥ 0)
  int rounds = 3;                ///< rounds of each measurement (≥ 1)
  int envs = 8;                  ///< environments of the vectorized batch (≥ 1)
  int batch_steps = 250;         ///< timed batch steps per run (≥ 1)
  int max_threads = 2;           ///< thread count compared with one (≥ 1)
  std::uint64_t seed = 1;        ///< seed of the actions and of the environments
  /// Called as the work goes with (environment steps done, environment steps in all): the
  /// overhead rounds' steps (warmups included), then each vectorized run's batch steps × envs;
  /// may be empty.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
  /// Asked every chunk of 50 environment steps of an overhead round (and of its warmup) and
  /// every batch step of a vectorized run whether to stop (e.g. `interrupt_requested`); may be
  /// empty. A stop ends the benchmark at once: the run under way is kept with the steps it took.
  std::function<bool()> stop;

  /// @throws Error naming the first setting out of range.
  void check() const;
};

constexpr auto declared_fields(const EnvBenchmarkOptions*) {
  using S = EnvBenchmarkOptions;
  return declare<S>(
      "env benchmark", field("task", &S::task, "environment task"),
      field("action_space", &S::action_space, "action space"),
      field("control_period", &S::control_period, "s", Range::positive(), "control step"),
      field("steps", &S::steps, "", Range::at_least(1), "timed environment steps per round"),
      field("warmup", &S::warmup, "", Range::at_least(0), "untimed steps before each timed run"),
      field("rounds", &S::rounds, "", Range::at_least(1), "rounds of each measurement"),
      field("envs", &S::envs, "", Range::at_least(1), "environments of the vectorized batch"),
      field("batch_steps", &S::batch_steps, "", Range::at_least(1), "timed batch steps per run"),
      field("max_threads", &S::max_threads, "", Range::closed(1, 256),
            "thread count compared with one"),
      field("seed", &S::seed, "seed of the actions and of the environments"));
}

/// How a benchmark ended.
enum class EnvBenchmarkStatus {
  ok,          ///< every run completed
  interrupted  ///< the stop request said so; the figures cover the steps done
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const EnvBenchmarkStatus*) {
  using E = EnvBenchmarkStatus;
  return std::array{EnumName{E::ok, "ok"}, EnumName{E::interrupted, "interrupted"}};
}

/// One round of the overhead measurement.
struct EnvOverheadRound {
  int steps = 0;                  ///< timed steps taken (fewer than asked when interrupted)
  double env_cpu_s = 0.0;         ///< thread CPU time of the environment steps [s]
  double bare_cpu_s = 0.0;        ///< thread CPU time of the same physics as bare mj_step calls [s]
  double env_wall_s = 0.0;        ///< wall time of the environment steps [s]
  double overhead = 0.0;          ///< env_cpu_s / bare_cpu_s − 1
  int episodes = 0;               ///< episodes started in the timed steps
  bool replay_identical = false;  ///< the replay ended in the environment's state bit for bit
};

constexpr auto declared_fields(const EnvOverheadRound*) {
  using S = EnvOverheadRound;
  return declare<S>(
      "overhead round", field("steps", &S::steps, "", Range::at_least(0), "timed steps taken"),
      field("env_cpu_s", &S::env_cpu_s, "s", Range::non_negative(),
            "thread CPU time of the environment steps"),
      field("bare_cpu_s", &S::bare_cpu_s, "s", Range::non_negative(),
            "thread CPU time of the same physics as bare mj_step calls"),
      field("env_wall_s", &S::env_wall_s, "s", Range::non_negative(),
            "wall time of the environment steps"),
      field("overhead", &S::overhead, "", Range::finite(), "env_cpu_s / bare_cpu_s − 1"),
      field("episodes", &S::episodes, "", Range::at_least(0),
            "episodes started in the timed steps"),
      field("replay_identical", &S::replay_identical,
            "the replay ended in the environment's state bit for bit"));
}

/// One vectorized run.
struct VectorRun {
  int threads = 1;
  int batch_steps = 0;            ///< timed batch steps taken (fewer than asked when interrupted)
  double wall_s = 0.0;            ///< wall time of the timed batch steps [s]
  double cpu_s = 0.0;             ///< process CPU time over the same stretch [s]
  double steps_per_second = 0.0;  ///< environment steps (batch steps × envs) per wall second
  double work_cpu_s = 0.0;        ///< Σ over batch steps of every environment's CPU time [s]
  double critical_cpu_s = 0.0;    ///< Σ over batch steps of the scheduled critical path [s]
};

constexpr auto declared_fields(const VectorRun*) {
  using S = VectorRun;
  return declare<S>(
      "vector run", field("threads", &S::threads, "", Range::at_least(1), "threads"),
      field("batch_steps", &S::batch_steps, "", Range::at_least(0), "timed batch steps taken"),
      field("wall_s", &S::wall_s, "s", Range::non_negative(), "wall time of the timed batch steps"),
      field("cpu_s", &S::cpu_s, "s", Range::non_negative(),
            "process CPU time over the same stretch"),
      field("steps_per_second", &S::steps_per_second, "1/s", Range::non_negative(),
            "environment steps per wall second"),
      field("work_cpu_s", &S::work_cpu_s, "s", Range::non_negative(),
            "Σ over batch steps of every environment's CPU time"),
      field("critical_cpu_s", &S::critical_cpu_s, "s", Range::non_negative(),
            "Σ over batch steps of the scheduled critical path"));
}

/// Figures of one benchmark.
struct EnvBenchmarkResult {
  EnvBenchmarkStatus status = EnvBenchmarkStatus::ok;
  std::string task;
  std::string model;
  ActionSpace action_space = ActionSpace::ee_pose_deltas;
  double control_period = 0.0;  ///< [s]
  int physics_steps_per_step = 0;
  int steps = 0;  ///< timed steps asked per round (each round says how many it took)
  std::vector<EnvOverheadRound> rounds;  ///< every round with at least one timed step
  double env_us_per_step = 0.0;   ///< median over rounds, thread CPU [µs]
  double bare_us_per_step = 0.0;  ///< median over rounds, thread CPU [µs]
  double overhead = 0.0;          ///< median over rounds
  bool replay_identical = false;  ///< in every round
  int envs = 0;
  int batch_steps = 0;                  ///< timed batch steps asked per run
  std::vector<VectorRun> vector_runs;   ///< every run with at least one timed step, in order
  std::vector<VectorRun> best;          ///< the best run of each thread count (1, then max)
  double speedup = 0.0;                 ///< best rate at max threads / best rate at 1 thread
  /// median over the max-thread runs of work_cpu_s / critical_cpu_s (see the protocol)
  double cpu_speedup = 0.0;
  /// median work_cpu_s at max threads / median work_cpu_s at 1 thread
  double cpu_cost_ratio = 0.0;
  /// batch arrays equal bit for bit across thread counts (after every round finished; false when
  /// none finished)
  bool threads_identical = false;
  std::array<double, 3> load_before{};  ///< 1, 5, 15-minute load averages before the scaling runs
  std::array<double, 3> load_after{};
  int hardware_threads = 0;  ///< std::thread::hardware_concurrency()
};

/// Runs the protocol above. @throws Error for bad options or an unknown task.
EnvBenchmarkResult run_env_benchmark(const EnvBenchmarkOptions& options);

}  // namespace mjarm
