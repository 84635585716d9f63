#pragma once
/// @file
/// The soak: the learning environments, a recorded teleoperation session's replay and a batch of
/// seeded pick-and-place trials, round after round in one process for a wall-clock length, with
/// the process's memory, file descriptors and threads sampled after every round. It fails on
/// growth (growth_check.hpp), on drift (a round whose results differ bit for bit from the first
/// round's for the same seeds) and on any MuJoCo warning or divergence. docs/hardening.md.
///
/// One round, in order:
/// 1. Environments: every task of the registry (`env_task_names`, or `tasks`) in every action space, a new
///    `Environment` each, `episodes` whole episodes of seeded uniform random actions; then a
///    `VectorEnvironment` of `vector_envs` environments of `vector_task` on `vector_threads`
///    threads for one episode length of batch steps (automatic resets). A fingerprint of each
///    run's rewards, final observation and step count is compared with round 1's.
/// 2. Replay: the session recorded once at the start (the scripted bimanual lift on
///    `dual_arm_box`, `run_bimanual_lift`) replayed headless (`SessionReplay`, as
///    `mjarm replay`); the final qpos, qvel, act and time must equal the first replay's bit for
///    bit, and the digest the recorded one.
/// 3. Sweep: `trials` pick-and-place trials (`run_pick_place_trials`, seeds seed … seed +
///    trials − 1, `trial_threads` workers); each trial's outcome, placement error, cycle time,
///    final time and tick count must equal round 1's bit for bit.
///
/// Warnings: the sum of every simulation's `mjData::warning` counters (read before each reset,
/// which zeroes them) and the MuJoCo warnings mjarm's log handler printed
/// (`mujoco_warning_count`, so the trials' simulations count too); divergence: an episode that
/// ended `diverged`, a replay that faulted, a trial that failed `diverged` or `bad_command`.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/soak/growth_check.hpp"
#include "mjarm/soak/process_sample.hpp"

namespace mjarm {

/// Faults the soak makes on purpose, to show that its checks catch them (tests). Nothing is
/// injected by default.
struct SoakInjection {
  /// Heap memory taken and written each round, kept until the soak ends [KiB] (≥ 0).
  std::int64_t leak_kib_per_round = 0;
  /// /dev/null descriptors opened each round, closed when the soak ends (≥ 0).
  int fds_per_round = 0;
  /// From this round on (1-based; 0: never) every part is perturbed: the first random action of
  /// each environment run (of the batch: row 0) is mirrored within its bounds, the replayed
  /// session's targets of the first hand move by 1 mm, the trials' largest object mass by 1 mg.
  int drift_from_round = 0;
};

constexpr auto declared_fields(const SoakInjection*) {
  using S = SoakInjection;
  return declare<S>("soak injection",
                    field("leak_kib_per_round", &S::leak_kib_per_round, "KiB", Range::at_least(0),
                          "heap memory taken and kept each round"),
                    field("fds_per_round", &S::fds_per_round, "", Range::at_least(0),
                          "descriptors opened and kept each round"),
                    field("drift_from_round", &S::drift_from_round, "", Range::at_least(0),
                          "from this round on every part is perturbed; 0: never"));
}

/// Settings of `run_soak`.
struct SoakOptions {
  double minutes = 60.0;  ///< no round starts after this wall-clock length [min] (> 0)
  int rounds = 0;         ///< at most this many rounds (≥ 0; 0: `minutes` alone ends it)
  std::uint64_t seed = 1;
  std::vector<std::string> tasks;       ///< environment tasks to run (empty: every task)
  int episodes = 2;                     ///< per task and action space per round (≥ 1)
  std::string vector_task = "reach";    ///< task of the vectorized batch
  int vector_envs = 4;                  ///< 1 … 64
  int vector_threads = 2;               ///< 1 … 64
  int trials = 4;                       ///< pick-and-place trials per round (≥ 1)
  int trial_threads = 2;                ///< 1 … 64
  GrowthLimits limits;
  SoakInjection inject;
  /// Called as the work goes (between episodes, every 100 replay ticks, after each trial) with
  /// the round under way (1-based) and the seconds elapsed; may be empty.
  std::function<void(int round, double elapsed_s)> progress;
  /// Asked as often as `progress` is called whether to stop (e.g. `interrupt_requested`); may be
  /// empty. A stop ends the soak at once; the round cut short is not sampled. (The trials stop
  /// at their next control tick on an interrupt by themselves: see `run_pick_place_trials`.)
  std::function<bool()> stop;

  /// @throws Error naming the first setting out of range.
  void check() const;
};

/// `tasks` and `vector_task` are checked against the task registry.
constexpr auto declared_fields(const SoakOptions*) {
  using S = SoakOptions;
  return declare<S>(
      "soak",
      field("minutes", &S::minutes, "min", Range::positive(),
            "no round starts after this wall-clock length"),
      field("rounds", &S::rounds, "", Range::at_least(0), "at most this many rounds; 0: no bound"),
      field("seed", &S::seed, "seed of the rounds"),
      field("episodes", &S::episodes, "", Range::at_least(1),
            "per task and action space per round"),
      field("vector_task", &S::vector_task, "task of the vectorized batch"),
      field("vector_envs", &S::vector_envs, "", Range::closed(1, 64),
            "environments of the vectorized batch"),
      field("vector_threads", &S::vector_threads, "", Range::closed(1, 64),
            "threads of the vectorized batch"),
      field("trials", &S::trials, "", Range::at_least(1), "pick-and-place trials per round"),
      field("trial_threads", &S::trial_threads, "", Range::closed(1, 64), "threads of the trials"),
      field("limits", &S::limits, "bounds of the growth rule"),
      field("inject", &S::inject, "faults made on purpose"));
}

/// How a soak ended.
enum class SoakStatus {
  ok,          ///< every check held
  failed,      ///< growth, drift, a warning or a divergence (see `SoakResult::failures`)
  interrupted  ///< the stop request ended it; the checks cover the rounds done
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const SoakStatus*) {
  using E = SoakStatus;
  return std::array{EnumName{E::ok, "ok"}, EnumName{E::failed, "failed"},
                    EnumName{E::interrupted, "interrupted"}};
}

/// Work done, summed over the rounds (the round cut short included).
struct SoakCounts {
  std::int64_t env_runs = 0;       ///< `Environment`s built and run
  std::int64_t env_episodes = 0;   ///< whole episodes (single environments)
  std::int64_t env_steps = 0;      ///< single-environment steps
  std::int64_t vector_steps = 0;   ///< environment steps of the vectorized batches
  std::int64_t replays = 0;        ///< replays run to their end
  std::int64_t replay_ticks = 0;   ///< control ticks replayed
  std::int64_t trials = 0;         ///< pick-and-place trials finished
  std::int64_t trial_successes = 0;
};

constexpr auto declared_fields(const SoakCounts*) {
  using S = SoakCounts;
  return declare<S>(
      "soak counts", field("env_runs", &S::env_runs, "Environments built and run"),
      field("env_episodes", &S::env_episodes, "whole episodes (single environments)"),
      field("env_steps", &S::env_steps, "single-environment steps"),
      field("vector_steps", &S::vector_steps, "environment steps of the vectorized batches"),
      field("replays", &S::replays, "replays run to their end"),
      field("replay_ticks", &S::replay_ticks, "control ticks replayed"),
      field("trials", &S::trials, "pick-and-place trials finished"),
      field("trial_successes", &S::trial_successes, "pick-and-place trials that succeeded"));
}

/// What a soak measured.
struct SoakResult {
  SoakStatus status = SoakStatus::ok;
  int rounds = 0;          ///< rounds finished (and sampled)
  double elapsed_s = 0.0;  ///< wall clock [s]
  double setup_s = 0.0;    ///< of which recording the session [s]
  SoakCounts counts;
  ProcessSample start;              ///< before anything was built
  std::vector<SoakSample> samples;  ///< one per finished round
  GrowthReport growth;
  std::int64_t mujoco_warnings = 0;  ///< the environments' and replays' mjData::warning counters
  std::int64_t logged_warnings = 0;  ///< warnings mjarm's log handler printed (all parts)
  std::int64_t divergences = 0;
  std::int64_t drifts = 0;  ///< results that differed from round 1's
  /// One line each (at most 20 of each kind): what drifted, warned or diverged, and where.
  std::vector<std::string> drift_notes, warning_notes;
  /// Why the soak failed, one line a reason (empty when it did not).
  std::vector<std::string> failures;
  int recorded_ticks = 0;  ///< ticks of the recorded session
  std::string replay_digest;
};

/// Runs the soak (see the file's comment). Deterministic for a seed except for the process
/// figures and times.
/// @throws Error for bad options, or when the parts cannot be built (a bundled model missing).
SoakResult run_soak(const SoakOptions& options);

}  // namespace mjarm
