#pragma once
/// @file
/// A sweep's plan: its trials (points × seeds, numbered point-major), grouped into shards of
/// contiguous trials, frozen with a hash. A trial's parameter values come from its number alone,
/// so a shard needs only the plan and its index, wherever it runs (docs/sweep.md).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjarm/sweep/sweep_file.hpp"

namespace mjarm {

/// Contiguous trials [first, first + count) run and written together.
struct SweepShard {
  std::int64_t index = 0;
  std::int64_t first = 0;
  std::int64_t count = 0;
};

/// A frozen sweep.
struct SweepPlan {
  SweepFile file;
  std::int64_t points = 0;      ///< grid points × random samples
  std::int64_t trials = 0;      ///< points × seeds
  std::int64_t shard_size = 1;  ///< trials per shard (the last may have fewer)
  std::string version;          ///< mjarm's, which ran it
  std::string hash;             ///< 16 hex digits over everything above
  bool seeded = false;          ///< the scenario has a seed: every trial gets its own
  /// The random design's values, one row per sample, one column per range.
  std::vector<std::vector<double>> samples;

  std::int64_t shards() const noexcept { return (trials + shard_size - 1) / shard_size; }
  SweepShard shard(std::int64_t index) const noexcept;
};

/// The plan of @p file with @p shard_size trials per shard (≥ 1; the trials' count at most).
/// @throws Error for a shard size < 1
SweepPlan make_sweep_plan(SweepFile file, std::int64_t shard_size);

/// How many trials a shard gets, from one trial's measured cost.
struct ShardSizing {
  double trial_seconds = 0.0;  ///< the first trial's wall time [s]
  std::int64_t shard_size = 1;
};

/// Runs the first trial of @p file once (its result is not kept) and sizes the shards so that
/// one takes about @p shard_seconds, and the sweep has at least @p min_shards of them (to keep
/// every worker busy), within [1, trials].
/// @throws Error for shard_seconds ≤ 0 or min_shards < 1, or when the trial throws
ShardSizing choose_shard_size(const SweepFile& file, double shard_seconds, std::int64_t min_shards);

/// The parameter values of trial @p trial (0 ≤ trial < trials): the fixed values, the point's
/// axis and random values, and the seed when the scenario draws.
nlohmann::ordered_json trial_values(const SweepPlan& plan, std::int64_t trial);

/// The point of trial @p trial and its seed.
std::int64_t trial_point(const SweepPlan& plan, std::int64_t trial) noexcept;
std::uint64_t trial_seed(const SweepPlan& plan, std::int64_t trial) noexcept;

/// The names of the parameters the plan varies (axes, then random ranges), in order.
std::vector<std::string> varied_parameters(const SweepPlan& plan);

/// The plan as JSON (the file, its size, shard size, version and hash).
nlohmann::ordered_json sweep_plan_json(const SweepPlan& plan);

/// The plan from `sweep_plan_json`'s output, its hash checked.
/// @throws Error naming @p source when the document is not a plan, or its hash does not match
///         its content (edited by hand, or truncated)
SweepPlan sweep_plan_from_json(const nlohmann::ordered_json& json, const std::string& source);

/// 16 hex digits: FNV-1a (64 bits) of @p text. The same on every platform.
std::string text_hash(const std::string& text);

}  // namespace mjarm
