#pragma once
/// @file
/// A sweep's folder: its frozen plan (`plan.json`, and the sweep file as given, `sweep.yaml`),
/// one file per finished shard (`shards/shard-NNNNNN.json`, written atomically: whole or
/// absent), the recordings and videos of the trials that keep them (`records/trial-NNNNNNNN/`),
/// and the merged results (`results.sqlite`). Every backend runs shards through
/// `run_sweep_shard`, so a trial's row depends on the plan and its number only.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjarm/sweep/sweep_plan.hpp"

namespace mjarm {

/// Where a sweep's files are.
struct SweepFolder {
  std::filesystem::path dir;

  std::filesystem::path plan() const { return dir / "plan.json"; }
  std::filesystem::path sweep_file() const { return dir / "sweep.yaml"; }
  std::filesystem::path shards() const { return dir / "shards"; }
  std::filesystem::path shard(std::int64_t index) const;
  std::filesystem::path record(std::int64_t trial) const;
  std::filesystem::path results() const { return dir / "results.sqlite"; }
};

/// Freezes @p plan in @p dir: a new or empty folder gets `plan.json` and the sweep file's
/// @p text; a folder holding the same plan (same hash) is taken as it is (its finished shards
/// kept).
/// @throws Error when @p dir holds another sweep (naming both hashes: "resume it, or choose
///         another folder"), holds files that are not a sweep's, or cannot be written
void prepare_sweep_folder(const SweepFolder& folder, const SweepPlan& plan,
                          const std::string& text);

/// The plan frozen in @p folder.
/// @throws Error when there is none, or it is damaged (see `sweep_plan_from_json`)
SweepPlan read_sweep_plan(const SweepFolder& folder);

/// What a shard file says, checked against the plan.
struct ShardFile {
  SweepShard shard;
  std::string host;
  double seconds = 0.0;                      ///< wall time the shard took [s]
  std::string started;                       ///< UTC, ISO 8601
  std::vector<nlohmann::ordered_json> rows;  ///< one per trial, in order
};

/// The state of every shard of @p plan in @p folder.
struct ShardStates {
  std::vector<std::int64_t> done;     ///< a valid file
  std::vector<std::int64_t> missing;  ///< no file
  /// A file that is not a whole shard of this plan (truncated, edited, another sweep's), with why.
  std::vector<std::pair<std::int64_t, std::string>> damaged;

  /// The shards to run (again): the missing and the damaged, in order.
  std::vector<std::int64_t> to_run() const;
};

ShardStates shard_states(const SweepFolder& folder, const SweepPlan& plan);

/// Reads shard @p index's file.
/// @throws Error naming the file when it is missing, not a whole shard, or of another plan
ShardFile read_shard_file(const SweepFolder& folder, const SweepPlan& plan, std::int64_t index);

/// Runs the trials of shard @p index in order and writes its file atomically. A trial that
/// throws (input its scenario refuses at run time) is a row with status and verdict "error".
/// Trials that keep a recording (the plan's `record`) get one, and a video, in
/// `records/trial-N/`; a failure is run again with them (the same trial: the same outcome).
/// @param on_trial called after each trial (a progress bar); may be empty
/// @return false when Ctrl-C stopped it: nothing is written then
bool run_sweep_shard(const SweepFolder& folder, const SweepPlan& plan, std::int64_t index,
                     const std::function<void()>& on_trial = {});

}  // namespace mjarm
