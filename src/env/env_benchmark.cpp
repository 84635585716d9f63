#include "mjarm/env/env_benchmark.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <span>
#include <thread>

#include "mjarm/env/environment.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/env/vector_environment.hpp"
#include "mjarm/error.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

double clock_seconds(clockid_t clock) noexcept {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double wall_seconds() noexcept {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::array<double, 3> load_average() {
  std::array<double, 3> load{-1.0, -1.0, -1.0};
  std::ifstream in("/proc/loadavg");
  in >> load[0] >> load[1] >> load[2];
  return load;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// @p rows actions drawn uniformly within @p spec's bounds ([−1, 1] where a side is unbounded).
std::vector<double> random_actions(const ArraySpec& spec, std::size_t rows, std::uint64_t seed) {
  Random rng(seed);
  const std::size_t width = static_cast<std::size_t>(spec.size());
  std::vector<double> actions(rows * width);
  for (std::size_t k = 0; k < actions.size(); ++k) {
    const Eigen::Index j = static_cast<Eigen::Index>(k % width);
    const double lo = std::isfinite(spec.minimum[j]) ? spec.minimum[j] : -1.0;
    const double hi = std::isfinite(spec.maximum[j]) ? spec.maximum[j] : 1.0;
    actions[k] = uniform(rng, std::min(lo, hi), std::max(lo, hi));
  }
  return actions;
}

/// A copy of the state that the physics carries from step to step.
struct PhysicsState {
  double time = 0.0;
  std::vector<double> qpos, qvel, act, warmstart;

  explicit PhysicsState(const mjModel& m)
      : qpos(static_cast<std::size_t>(m.nq)),
        qvel(static_cast<std::size_t>(m.nv)),
        act(static_cast<std::size_t>(m.na)),
        warmstart(static_cast<std::size_t>(m.nv)) {}
  void take(const mjData& d) noexcept {
    time = d.time;
    std::copy(d.qpos, d.qpos + qpos.size(), qpos.begin());
    std::copy(d.qvel, d.qvel + qvel.size(), qvel.begin());
    std::copy(d.act, d.act + act.size(), act.begin());
    std::copy(d.qacc_warmstart, d.qacc_warmstart + warmstart.size(), warmstart.begin());
  }
  void put(mjData& d) const noexcept {
    d.time = time;
    std::copy(qpos.begin(), qpos.end(), d.qpos);
    std::copy(qvel.begin(), qvel.end(), d.qvel);
    std::copy(act.begin(), act.end(), d.act);
    std::copy(warmstart.begin(), warmstart.end(), d.qacc_warmstart);
  }
  bool same_position(const mjData& d) const noexcept {
    return std::memcmp(qpos.data(), d.qpos, sizeof(double) * qpos.size()) == 0 &&
           std::memcmp(qvel.data(), d.qvel, sizeof(double) * qvel.size()) == 0;
  }
};

/// Steps per chunk: the environment and its bare replay alternate every chunk, so both see the
/// same conditions on a shared machine. A stop request is asked once per chunk.
constexpr int kChunkSteps = 50;

/// Progress and the stop request, asked as the work goes (see `EnvBenchmarkOptions`).
struct BenchmarkPace {
  const EnvBenchmarkOptions& options;
  std::int64_t total = 0;
  std::int64_t done = 0;
  bool stopped = false;

  /// Counts @p steps environment steps done; true when the benchmark is to stop now.
  bool advance(std::int64_t steps) {
    done += steps;
    if (options.progress) options.progress(done, total);
    stopped = stopped || (options.stop && options.stop());
    return stopped;
  }
};

/// One round of the overhead measurement: chunks of up to kChunkSteps environment steps (within
/// one episode; the reset that starts an episode is timed with its first chunk), each followed
/// by its bare replay from the chunk's start state. A stop ends it after the chunk under way.
EnvOverheadRound overhead_round(Environment& env, const std::vector<double>& actions, int steps,
                                int warmup, std::uint64_t seed, BenchmarkPace& pace) {
  const mjModel& m = env.simulation().model();
  const std::size_t width = static_cast<std::size_t>(env.action_spec().size());
  const std::size_t rows = actions.size() / width;
  const std::size_t nu = static_cast<std::size_t>(m.nu);
  auto action = [&](int k) {
    return std::span<const double>(actions).subspan((static_cast<std::size_t>(k) % rows) * width,
                                                    width);
  };
  PhysicsState start(m), end(m);
  std::vector<double> ctrl(static_cast<std::size_t>(kChunkSteps) * nu);
  DataPtr bare = env.task().robot().make_data();
  const int physics = env.physics_steps_per_step();

  // warm up, then the timed steps (resets included)
  EnvOverheadRound round;
  TimeStep ts = env.reset(seed);
  for (int k = 0; k < warmup; ++k) {
    ts = ts.last() ? env.reset() : env.step(action(k));
    if ((k + 1) % kChunkSteps == 0 && pace.advance(kChunkSteps)) return round;
  }
  if (pace.advance(warmup % kChunkSteps)) return round;
  ts = env.reset(seed + 1);
  round.episodes = 1;
  round.replay_identical = true;
  for (int k = 0; k < steps;) {
    // the environment
    const double wall0 = wall_seconds();
    const double cpu0 = clock_seconds(CLOCK_THREAD_CPUTIME_ID);
    if (ts.last()) {
      ts = env.reset();
      ++round.episodes;
    }
    start.take(env.simulation().data());
    int chunk = 0;
    while (chunk < kChunkSteps && k < steps && !ts.last()) {
      ts = env.step(action(k));
      const double* c = env.simulation().data().ctrl;
      std::copy(c, c + nu, ctrl.begin() + static_cast<std::ptrdiff_t>(chunk * nu));
      ++chunk;
      ++k;
    }
    round.env_cpu_s += clock_seconds(CLOCK_THREAD_CPUTIME_ID) - cpu0;
    round.env_wall_s += wall_seconds() - wall0;
    end.take(env.simulation().data());

    // the same physics as bare mj_step calls, the inputs held over each step
    mjData* d = bare.get();
    mj_resetData(&m, d);
    start.put(*d);
    const double cpu1 = clock_seconds(CLOCK_THREAD_CPUTIME_ID);
    for (int j = 0; j < chunk; ++j) {
      std::copy(ctrl.begin() + static_cast<std::ptrdiff_t>(j * nu),
                ctrl.begin() + static_cast<std::ptrdiff_t>((j + 1) * nu), d->ctrl);
      for (int p = 0; p < physics; ++p) mj_step(&m, d);
    }
    round.bare_cpu_s += clock_seconds(CLOCK_THREAD_CPUTIME_ID) - cpu1;
    round.replay_identical = round.replay_identical && end.same_position(*d);
    round.steps = k;
    if (pace.advance(chunk)) break;
  }
  if (round.steps > 0) round.overhead = round.env_cpu_s / round.bare_cpu_s - 1.0;
  return round;
}

/// One timed vectorized run; the warmup continues from where the last run of @p batch ended. A
/// stop ends it after the batch step under way.
VectorRun vector_run(VectorEnvironment& batch, const std::vector<double>& actions, int steps,
                     int warmup, BenchmarkPace& pace) {
  const std::size_t width = static_cast<std::size_t>(batch.action_spec().size() * batch.size());
  const std::size_t rows = actions.size() / width;
  auto row = [&](int k) {
    return std::span<const double>(actions).subspan((static_cast<std::size_t>(k) % rows) * width,
                                                    width);
  };
  VectorRun run;
  run.threads = batch.threads();
  batch.reset();
  for (int k = 0; k < warmup; ++k) {
    batch.step(row(k));
    if (pace.advance(batch.size())) return run;
  }
  std::vector<double> free_at(static_cast<std::size_t>(batch.threads()), 0.0);
  const double cpu0 = clock_seconds(CLOCK_PROCESS_CPUTIME_ID);
  const double wall0 = wall_seconds();
  for (int k = 0; k < steps; ++k) {
    batch.step(row(warmup + k));
    // the environments handed out in index order to the first free of T threads
    std::fill(free_at.begin(), free_at.end(), 0.0);
    for (double c : batch.last_env_cpu_seconds()) {
      run.work_cpu_s += c;
      *std::min_element(free_at.begin(), free_at.end()) += c;
    }
    run.critical_cpu_s += *std::max_element(free_at.begin(), free_at.end());
    run.batch_steps = k + 1;
    if (pace.advance(batch.size())) break;
  }
  run.wall_s = wall_seconds() - wall0;
  run.cpu_s = clock_seconds(CLOCK_PROCESS_CPUTIME_ID) - cpu0;
  run.steps_per_second = static_cast<double>(run.batch_steps) * batch.size() / run.wall_s;
  return run;
}

bool same_arrays(const VectorEnvironment& a, const VectorEnvironment& b) {
  auto same = [](auto x, auto y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size_bytes()) == 0;
  };
  return same(a.observations(), b.observations()) && same(a.rewards(), b.rewards()) &&
         same(a.discounts(), b.discounts()) && same(a.step_types(), b.step_types());
}

}  // namespace

void EnvBenchmarkOptions::check() const { check_fields(*this); }

EnvBenchmarkResult run_env_benchmark(const EnvBenchmarkOptions& options) {
  options.check();
  EnvironmentOptions env_options;
  env_options.action_space = options.action_space;
  env_options.control_period = options.control_period;
  env_options.seed = options.seed;
  const std::unique_ptr<EnvTask> task = make_env_task(options.task);
  Environment env(task->clone(), env_options);

  EnvBenchmarkResult r;
  r.task = options.task;
  r.model = task->robot().name();
  r.action_space = options.action_space;
  r.control_period = options.control_period;
  r.physics_steps_per_step = env.physics_steps_per_step();
  r.steps = options.steps;
  r.envs = options.envs;
  r.batch_steps = options.batch_steps;
  r.hardware_threads = static_cast<int>(std::thread::hardware_concurrency());
  const int thread_counts = options.max_threads > 1 ? 2 : 1;
  const int batch_warmup = std::max(1, options.warmup / 10);
  BenchmarkPace pace{options};
  pace.total = static_cast<std::int64_t>(options.rounds) *
               (static_cast<std::int64_t>(options.steps) + options.warmup +
                static_cast<std::int64_t>(thread_counts) * options.envs *
                    (options.batch_steps + batch_warmup));

  // 1. overhead on one thread
  const std::vector<double> actions = random_actions(
      env.action_spec(), static_cast<std::size_t>(options.steps + options.warmup), options.seed);
  for (int k = 0; k < options.rounds && !pace.stopped; ++k) {
    const EnvOverheadRound round =
        overhead_round(env, actions, options.steps, options.warmup,
                       options.seed + 2 * static_cast<std::uint64_t>(k), pace);
    if (round.steps > 0) r.rounds.push_back(round);
  }
  if (pace.stopped) r.status = EnvBenchmarkStatus::interrupted;
  std::vector<double> env_us, bare_us, overheads;
  r.replay_identical = !r.rounds.empty();
  for (const EnvOverheadRound& round : r.rounds) {
    env_us.push_back(1e6 * round.env_cpu_s / round.steps);
    bare_us.push_back(1e6 * round.bare_cpu_s / round.steps);
    overheads.push_back(round.overhead);
    r.replay_identical = r.replay_identical && round.replay_identical;
  }
  if (!r.rounds.empty()) {
    r.env_us_per_step = median(env_us);
    r.bare_us_per_step = median(bare_us);
    r.overhead = median(overheads);
  }
  if (r.status == EnvBenchmarkStatus::interrupted) return r;

  // 2. scaling of the vectorized batch, alternating thread counts
  std::vector<int> counts{1};
  if (options.max_threads > 1) counts.push_back(options.max_threads);
  std::vector<std::unique_ptr<VectorEnvironment>> batches;
  for (int t : counts)
    batches.push_back(
        std::make_unique<VectorEnvironment>(task->clone(), env_options, options.envs, t));
  const std::vector<double> batch_actions =
      random_actions(env.action_spec(),
                     static_cast<std::size_t>(options.batch_steps + batch_warmup) *
                         static_cast<std::size_t>(options.envs),
                     options.seed + 1000);
  r.load_before = load_average();
  bool compared = false, identical = true;
  for (int k = 0; k < options.rounds && !pace.stopped; ++k) {
    for (std::size_t b = 0; b < batches.size() && !pace.stopped; ++b) {
      const VectorRun run =
          vector_run(*batches[b], batch_actions, options.batch_steps, batch_warmup, pace);
      if (run.batch_steps > 0) r.vector_runs.push_back(run);
    }
    // a round cut short leaves the batches at different steps: nothing to compare
    for (std::size_t b = 1; b < batches.size() && !pace.stopped; ++b) {
      identical = identical && same_arrays(*batches[0], *batches[b]);
      compared = true;
    }
  }
  r.threads_identical = compared && identical;
  if (pace.stopped) r.status = EnvBenchmarkStatus::interrupted;
  r.load_after = load_average();
  for (int t : counts) {
    const VectorRun* best = nullptr;
    for (const VectorRun& run : r.vector_runs) {
      if (run.threads == t && (best == nullptr || run.steps_per_second > best->steps_per_second))
        best = &run;
    }
    if (best != nullptr) r.best.push_back(*best);
  }
  if (r.best.size() == 2) r.speedup = r.best[1].steps_per_second / r.best[0].steps_per_second;
  std::vector<double> work_1, work_t, parallelism;
  for (const VectorRun& run : r.vector_runs) {
    if (run.threads == 1) work_1.push_back(run.work_cpu_s);
    if (counts.size() == 2 && run.threads == counts.back() && run.critical_cpu_s > 0.0) {
      work_t.push_back(run.work_cpu_s);
      parallelism.push_back(run.work_cpu_s / run.critical_cpu_s);
    }
  }
  if (!parallelism.empty()) r.cpu_speedup = median(parallelism);
  if (!work_1.empty() && !work_t.empty() && median(work_1) > 0.0)
    r.cpu_cost_ratio = median(work_t) / median(work_1);
  return r;
}

}  // namespace mjarm
