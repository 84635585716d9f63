#pragma once
/// @file
/// The local backend: a sweep's missing shards on this machine, on a bounded pool of threads.

#include <cstdint>
#include <functional>

#include "mjarm/sweep/sweep_folder.hpp"

namespace mjarm {

struct LocalSweepOptions {
  int jobs = 0;  ///< worker threads; 0: one per core
  /// Called after every trial with the trials done (this run and before) and the plan's count,
  /// from one worker at a time; may be empty.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
};

struct LocalSweepResult {
  std::int64_t shards_run = 0;   ///< shards this run finished and wrote
  std::int64_t shards_left = 0;  ///< shards still missing (an interrupt stopped them)
  std::int64_t trials_run = 0;   ///< trials of the shards written
  int jobs = 1;                  ///< worker threads used
  bool interrupted = false;      ///< Ctrl-C stopped it: finished shards are kept
  double seconds = 0.0;          ///< wall time [s]
};

/// Runs every shard of @p plan that has no valid file in @p folder (a damaged one is run again),
/// `jobs` at a time, each written whole as it finishes (`run_sweep_shard`).
/// @throws Error for jobs < 0, or as `run_sweep_shard`
LocalSweepResult run_sweep_local(const SweepFolder& folder, const SweepPlan& plan,
                                 const LocalSweepOptions& options = {});

}  // namespace mjarm
