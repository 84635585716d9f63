#pragma once
/// @file
/// The Slurm backend: a sweep's missing shards as job arrays, through Slurm's command-line tools
/// (`sbatch`, `squeue`, `scancel`, `scontrol`), never libslurm, whose ABI changes between
/// releases. Each array task runs `mjarm sweep shard DIR --index K` and records its exit status;
/// a dependent job merges when every task has ended (docs/sweep.md).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "mjarm/sweep/sweep_folder.hpp"

namespace mjarm {

struct SlurmOptions {
  std::filesystem::path executable;  ///< the mjarm every task runs (an absolute path)
  std::string partition;             ///< empty: the cluster's default
  std::string account;
  std::string qos;
  std::string time_limit = "01:00:00";  ///< each task's --time
  int cpus_per_task = 1;
  int throttle = 0;  ///< at most this many tasks of an array at once (the array's %); 0: no limit
  std::vector<std::string> sbatch_args;  ///< passed to every sbatch as they are (--hold, …)
  bool dry_run = false;                  ///< write the scripts, submit nothing
};

struct SlurmSubmission {
  std::vector<std::filesystem::path> scripts;  ///< the array scripts, then the merge script
  std::vector<std::string> jobs;               ///< the array jobs' ids (none in a dry run)
  std::string merge_job;                       ///< the merge job's id
  std::int64_t shards = 0;                     ///< shards submitted
  std::int64_t max_array_size = 0;             ///< the cluster's MaxArraySize
};

/// Writes one array script per at most MaxArraySize missing (or damaged) shards of @p plan into
/// `DIR/slurm/`, submits them, then a merge job that runs once they all ended
/// (`--dependency=afterany`) and fails naming the shards that did not finish. The job ids are kept
/// in `DIR/slurm/jobs.json` for `slurm_jobs` and `cancel_slurm_jobs`.
/// @throws Error when there is nothing to run, `sbatch` or `scontrol` is missing or fails (with
///         its message), or the options are out of range; before anything is submitted when it
///         can be told then
SlurmSubmission submit_sweep_slurm(const SweepFolder& folder, const SweepPlan& plan,
                                   const SlurmOptions& options);

/// One of the folder's jobs as `squeue` lists it.
struct SlurmJob {
  std::string id;     ///< "1234_7" for an array task
  std::string state;  ///< PENDING, RUNNING, …
};

/// The folder's submitted jobs still queued or running; empty when none is (or none was
/// submitted).
/// @throws Error when `squeue` fails
std::vector<SlurmJob> slurm_jobs(const SweepFolder& folder);

/// Cancels the folder's jobs (`scancel`); their running shards stop and write nothing.
void cancel_slurm_jobs(const SweepFolder& folder);

/// Waits until none of the folder's jobs is queued or running, calling @p progress with the
/// finished shards every poll; returns early (false) on Ctrl-C, the jobs left running.
bool wait_for_slurm_jobs(const SweepFolder& folder, const SweepPlan& plan,
                         const std::function<void(std::int64_t shards_done)>& progress = {});

/// Why shard @p index has no file after its task ended: its exit status and the last lines of its
/// log, or "no task ran it" when it left neither.
std::string slurm_shard_failure(const SweepFolder& folder, std::int64_t index);

}  // namespace mjarm
