#pragma once
/// @file
/// A sweep's results in SQLite (`results.sqlite`, Debian's libsqlite3): the `trials` table, one
/// row per trial with typed columns (trial, point, seed, every varied parameter, status, verdict,
/// success, message, end time, every metric, the recording and videos kept), the `shards` table
/// (host, start, wall time of each) and the `sweep` table (plan, hash, scenario, mjarm version,
/// hosts, times). Merging rebuilds the database from the shard files into a temporary file and
/// renames it into place: the database is whole or the previous one, and merging twice gives the
/// same rows.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjarm/sweep/sweep_folder.hpp"

namespace mjarm {

struct SweepMerge {
  std::int64_t shards = 0;   ///< shard files merged
  std::int64_t trials = 0;   ///< rows in `trials`
  std::int64_t missing = 0;  ///< shards without a file yet
  double seconds = 0.0;      ///< wall time of the merge [s]
};

/// Merges every shard file of @p folder into `results.sqlite`.
/// @throws Error naming the file of a damaged shard or one of another plan (run it again with
///         `resume`), or when the database cannot be written
SweepMerge merge_sweep(const SweepFolder& folder);

/// A table read back: column names and rows of values (null for NULL).
struct ResultTable {
  std::vector<std::string> columns;
  std::vector<std::vector<nlohmann::ordered_json>> rows;

  /// The index of column @p name, or -1.
  int column(const std::string& name) const;
};

/// The `trials` table of @p folder's database, in trial order.
/// @throws Error when there is no database (merge first) or it cannot be read
ResultTable read_trials(const SweepFolder& folder);

/// The `sweep` table's one row as a JSON object.
nlohmann::ordered_json read_sweep_row(const SweepFolder& folder);

/// @p table as CSV: a header, then one line per row (text quoted when it needs to be, NULL as an
/// empty cell).
std::string table_csv(const ResultTable& table);

/// @p table as a JSON array of objects.
nlohmann::ordered_json table_json(const ResultTable& table);

}  // namespace mjarm
