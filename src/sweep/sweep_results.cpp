#include "mjarm/sweep/sweep_results.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <set>

#include "folder_lock.hpp"
#include "mjarm/error.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "sweep/sqlite_database.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

const char* sql_type(FieldKind kind) {
  switch (kind) {
    case FieldKind::number:
      return "REAL";
    case FieldKind::integer:
    case FieldKind::flag:
      return "INTEGER";
    default:
      return "TEXT";
  }
}

/// Syncs @p path (a file or a folder) to disk.
void sync_path(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw Error("cannot sync '" + path.string() + "'");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw Error("cannot sync '" + path.string() + "'");
}

std::string placeholders(std::size_t n) {
  std::string text;
  for (std::size_t i = 0; i < n; ++i) text += i > 0 ? ", ?" : "?";
  return text;
}

}  // namespace

int ResultTable::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

SweepMerge merge_sweep(const SweepFolder& folder) {
  const auto t0 = std::chrono::steady_clock::now();
  const SweepPlan plan = read_sweep_plan(folder);
  const FolderLock lock(folder.dir, "sweep folder");  // one run or merge at a time
  const Scenario& scenario = find_scenario(plan.file.scenario);

  // the columns: the varied parameters typed as the scenario declares them, then the metrics
  const std::vector<std::string> varied = varied_parameters(plan);
  const std::vector<FieldInfo> table = scenario.parameters();
  std::string trials_sql =
      "CREATE TABLE trials (trial INTEGER PRIMARY KEY, point INTEGER, seed INTEGER";
  for (const std::string& name : varied) {
    const auto info = std::find_if(table.begin(), table.end(),
                                   [&](const FieldInfo& i) { return i.path == name; });
    trials_sql += ", " + sql_name(name) + " " + sql_type(info->kind);
  }
  trials_sql += ", status TEXT, verdict TEXT, success INTEGER, message TEXT, end_time REAL";
  std::vector<std::string> metrics;
  for (const MetricInfo& m : scenario.metrics()) {
    metrics.push_back(m.name);
    trials_sql += ", " + sql_name(m.name) + " REAL";
  }
  trials_sql += ", recording TEXT, videos TEXT)";

  const fs::path partial = folder.dir / "results.sqlite.partial";
  std::error_code ec;
  fs::remove(partial, ec);
  SweepMerge merge;
  // a merge that fails leaves the previous database and no partial file
  struct RemovePartial {
    const fs::path& path;
    bool done = false;
    ~RemovePartial() {
      std::error_code ignored;
      if (!done) fs::remove(path, ignored);
    }
  } cleanup{partial};
  SqliteDatabase db(partial, true);
  {
    db.execute("PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF; BEGIN;");
    db.execute(trials_sql);
    db.execute(
        "CREATE TABLE shards (shard INTEGER PRIMARY KEY, first INTEGER, count INTEGER, host "
        "TEXT, started TEXT, seconds REAL)");
    db.execute(
        "CREATE TABLE sweep (hash TEXT, scenario TEXT, version TEXT, trials INTEGER, shards "
        "INTEGER, shards_merged INTEGER, hosts TEXT, first_started TEXT, last_started TEXT, "
        "shard_seconds REAL, plan TEXT)");
    const std::size_t n_columns = 3 + varied.size() + 5 + metrics.size() + 2;
    SqliteStatement insert =
        db.prepare("INSERT INTO trials VALUES (" + placeholders(n_columns) + ")");
    SqliteStatement insert_shard = db.prepare("INSERT INTO shards VALUES (?, ?, ?, ?, ?, ?)");
    std::set<std::string> hosts;
    std::string first_started, last_started;
    double shard_seconds = 0.0;
    // every shard file read once; a damaged one fails the merge after the others were read
    std::vector<std::string> damaged;
    for (std::int64_t k = 0; k < plan.shards(); ++k) {
      std::error_code ec;
      if (!fs::exists(folder.shard(k), ec)) {
        ++merge.missing;
        continue;
      }
      ShardFile shard;
      try {
        shard = read_shard_file(folder, plan, k);
      } catch (const Error& e) {
        damaged.push_back(e.what());
        continue;
      }
      for (const Json& row : shard.rows) {
        const std::int64_t trial = row["trial"].get<std::int64_t>();
        const Json values = trial_values(plan, trial);
        int c = 1;
        insert.bind(c++, trial);
        insert.bind(c++, row["point"]);
        insert.bind(c++, row["seed"]);
        for (const std::string& name : varied) insert.bind(c++, values[name]);
        for (const char* key : {"status", "verdict", "success", "message", "end_time"})
          insert.bind(c++, row[key]);
        for (std::size_t m = 0; m < metrics.size(); ++m)
          insert.bind(c++, m < row["metrics"].size() ? row["metrics"][m] : Json(nullptr));
        insert.bind(c++, row["recording"]);
        insert.bind(c++, row["videos"].empty() ? Json(nullptr) : row["videos"]);
        insert.step();
        insert.reset();
        ++merge.trials;
      }
      int c = 1;
      for (const Json& value : {Json(k), Json(shard.shard.first), Json(shard.shard.count),
                                Json(shard.host), Json(shard.started), Json(shard.seconds)})
        insert_shard.bind(c++, value);
      insert_shard.step();
      insert_shard.reset();
      hosts.insert(shard.host);
      if (first_started.empty() || shard.started < first_started) first_started = shard.started;
      last_started = std::max(last_started, shard.started);
      shard_seconds += shard.seconds;
      ++merge.shards;
    }
    if (!damaged.empty())
      throw Error(std::to_string(damaged.size()) + " damaged shard file" +
                  (damaged.size() > 1 ? "s" : "") + " (" + damaged.front() +
                  (damaged.size() > 1 ? "; …" : "") +
                  "): run them again with mjarm sweep resume; nothing merged");
    std::string host_list;
    for (const std::string& h : hosts) host_list += (host_list.empty() ? "" : ",") + h;
    SqliteStatement sweep = db.prepare("INSERT INTO sweep VALUES (" + placeholders(11) + ")");
    int c = 1;
    for (const Json& value :
         {Json(plan.hash), Json(plan.file.scenario), Json(plan.version), Json(plan.trials),
          Json(plan.shards()), Json(merge.shards), Json(host_list), Json(first_started),
          Json(last_started), Json(shard_seconds), Json(sweep_plan_json(plan).dump())})
      sweep.bind(c++, value);
    sweep.step();
  }  // the statements are finalized before the database closes
  db.execute("COMMIT;");
  db.close();
  sync_path(partial);
  fs::rename(partial, folder.results(), ec);
  if (ec)
    throw Error("cannot move the results into '" + folder.results().string() +
                "': " + ec.message());
  cleanup.done = true;
  sync_path(folder.dir);
  merge.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return merge;
}

namespace {

ResultTable read_table(const SweepFolder& folder, const std::string& sql) {
  std::error_code ec;
  if (!fs::exists(folder.results(), ec))
    throw Error("'" + folder.dir.string() +
                "' has no results yet (results.sqlite): run mjarm "
                "sweep merge first");
  SqliteDatabase db(folder.results(), false);
  SqliteStatement select = db.prepare(sql);
  ResultTable table;
  for (int c = 0; c < select.columns(); ++c) table.columns.push_back(select.column_name(c));
  while (select.step()) {
    std::vector<Json> row;
    for (int c = 0; c < select.columns(); ++c) row.push_back(select.column(c));
    table.rows.push_back(std::move(row));
  }
  return table;
}

std::string csv_cell(const Json& value) {
  if (value.is_null()) return {};
  const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

ResultTable read_trials(const SweepFolder& folder) {
  return read_table(folder, "SELECT * FROM trials ORDER BY trial");
}

Json read_sweep_row(const SweepFolder& folder) {
  const ResultTable t = read_table(folder, "SELECT * FROM sweep");
  Json row = Json::object();
  if (t.rows.empty()) return row;
  for (std::size_t c = 0; c < t.columns.size(); ++c) row[t.columns[c]] = t.rows[0][c];
  return row;
}

std::string table_csv(const ResultTable& table) {
  std::string text;
  for (std::size_t c = 0; c < table.columns.size(); ++c)
    text += (c > 0 ? "," : "") + csv_cell(table.columns[c]);
  text += '\n';
  for (const auto& row : table.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) text += (c > 0 ? "," : "") + csv_cell(row[c]);
    text += '\n';
  }
  return text;
}

Json table_json(const ResultTable& table) {
  Json rows = Json::array();
  for (const auto& row : table.rows) {
    Json object = Json::object();
    for (std::size_t c = 0; c < row.size(); ++c) object[table.columns[c]] = row[c];
    rows.push_back(std::move(object));
  }
  return rows;
}

}  // namespace mjarm
