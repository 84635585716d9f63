#include "mjarm/sweep/sweep_folder.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/json_or_null.hpp"
#include "mjarm/plot/recording.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "mjarm/web/recorded_model.hpp"
#include "mjarm/web/replay_html.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

std::string numbered(const char* prefix, std::int64_t n, int digits) {
  char text[48];
  std::snprintf(text, sizeof text, "%s%0*lld", prefix, digits, static_cast<long long>(n));
  return text;
}

void write_file(const fs::path& path, const std::string& text, const std::string& what) {
  FileWriter out(path, FileWriter::Mode::replace, what);
  out.write(text);
  out.commit();
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

/// One trial's row, as the shard file keeps it: its files relative to the sweep's folder (the
/// same row wherever the folder is mounted).
Json row_of(const SweepPlan& plan, std::int64_t trial, const TrialOutcome& o, const fs::path& dir) {
  Json metrics = Json::array();
  for (const double m : o.metrics) metrics.push_back(std::isfinite(m) ? Json(m) : Json(nullptr));
  Json videos = Json::array();
  for (const fs::path& v : o.videos) videos.push_back(v.lexically_relative(dir).string());
  return Json{
      {"trial", trial},
      {"point", trial_point(plan, trial)},
      {"seed", plan.seeded ? Json(trial_seed(plan, trial)) : Json(nullptr)},
      {"status", to_string(o.status)},
      {"verdict", o.verdict},
      {"success", o.success},
      {"message", o.message},
      {"end_time", o.end_time},
      {"metrics", metrics},
      {"recording",
       o.recording.empty() ? Json(nullptr) : Json(o.recording.lexically_relative(dir).string())},
      {"recording_error", text_or_null(o.recording_error)},
      {"videos", videos},
      {"video_error", text_or_null(o.video_error)}};
}

/// The row of a trial its scenario refused at run time.
Json error_row(const SweepPlan& plan, std::int64_t trial, const std::string& why,
               std::size_t metrics) {
  TrialOutcome o;
  o.verdict = "error";
  o.message = why;
  o.metrics.assign(metrics, std::nan(""));
  Json row = row_of(plan, trial, o, {});
  row["status"] = "error";
  return row;
}

}  // namespace

fs::path SweepFolder::shard(std::int64_t index) const {
  return shards() / (numbered("shard-", index, 6) + ".json");
}

fs::path SweepFolder::record(std::int64_t trial) const {
  return dir / "records" / numbered("trial-", trial, 8);
}

void prepare_sweep_folder(const SweepFolder& folder, const SweepPlan& plan,
                          const std::string& text) {
  std::error_code ec;
  if (fs::exists(folder.plan(), ec)) {
    const SweepPlan frozen = read_sweep_plan(folder);
    if (frozen.hash != plan.hash)
      throw Error("'" + folder.dir.string() + "' holds another sweep (plan " + frozen.hash + ", " +
                  frozen.file.scenario + ", " + std::to_string(frozen.trials) +
                  " trials), not this one (plan " + plan.hash +
                  "): resume it (mjarm sweep resume), or choose another folder");
    return;
  }
  if (fs::exists(folder.dir, ec) && !fs::is_empty(folder.dir, ec))
    throw Error("'" + folder.dir.string() +
                "' is not empty and holds no sweep (no plan.json): choose a new or empty folder");
  fs::create_directories(folder.shards(), ec);
  if (ec)
    throw Error("cannot create the sweep folder '" + folder.shards().string() +
                "': " + ec.message());
  write_file(folder.sweep_file(), text, "sweep file");
  write_file(folder.plan(), sweep_plan_json(plan).dump(1) + "\n", "sweep plan");
}

SweepPlan read_sweep_plan(const SweepFolder& folder) {
  std::error_code ec;
  if (!fs::exists(folder.plan(), ec))
    throw Error("'" + folder.dir.string() + "' holds no sweep (no plan.json)");
  const std::string text = slurp(folder.plan());
  if (!Json::accept(text)) throw Error(folder.plan().string() + ": not valid JSON (damaged?)");
  return sweep_plan_from_json(Json::parse(text), folder.plan().string());
}

ShardFile read_shard_file(const SweepFolder& folder, const SweepPlan& plan, std::int64_t index) {
  const fs::path path = folder.shard(index);
  const auto refuse = [&](const std::string& why) -> void {
    throw Error("shard file '" + path.string() + "': " + why);
  };
  std::error_code ec;
  if (!fs::exists(path, ec)) refuse("missing");
  const std::string text = slurp(path);
  if (!Json::accept(text)) refuse("not valid JSON (truncated?)");
  const Json doc = Json::parse(text);
  if (!doc.is_object() || !doc.contains("plan") || !doc.contains("rows") || !doc["rows"].is_array())
    refuse("not a shard file");
  if (doc["plan"] != plan.hash)
    refuse("of another plan (" + doc["plan"].dump() + "; this sweep's is " + plan.hash + ")");
  ShardFile file;
  file.shard = plan.shard(index);
  if (doc.value("shard", Json()) != index || doc.value("first", Json()) != file.shard.first ||
      doc.value("count", Json()) != file.shard.count)
    refuse("not shard " + std::to_string(index) + " of this plan");
  if (static_cast<std::int64_t>(doc["rows"].size()) != file.shard.count)
    refuse("has " + std::to_string(doc["rows"].size()) + " rows, not " +
           std::to_string(file.shard.count));
  for (std::int64_t k = 0; k < file.shard.count; ++k) {
    const Json& row = doc["rows"][static_cast<std::size_t>(k)];
    if (!row.is_object() || row.value("trial", Json()) != file.shard.first + k)
      refuse("row " + std::to_string(k) + " is not trial " + std::to_string(file.shard.first + k));
    file.rows.push_back(row);
  }
  file.host = doc.value("host", "");
  file.seconds = doc.value("seconds", 0.0);
  file.started = doc.value("started", "");
  return file;
}

std::vector<std::int64_t> ShardStates::to_run() const {
  std::vector<std::int64_t> shards = missing;
  for (const auto& [index, why] : damaged) shards.push_back(index);
  std::sort(shards.begin(), shards.end());
  return shards;
}

ShardStates shard_states(const SweepFolder& folder, const SweepPlan& plan) {
  ShardStates states;
  for (std::int64_t k = 0; k < plan.shards(); ++k) {
    std::error_code ec;
    if (!fs::exists(folder.shard(k), ec)) {
      states.missing.push_back(k);
      continue;
    }
    try {
      read_shard_file(folder, plan, k);
      states.done.push_back(k);
    } catch (const Error& e) {
      states.damaged.emplace_back(k, e.what());
    }
  }
  return states;
}

namespace {

// a recorded trial's replay page beside its recording (docs/replay.md), where this build holds
// the page; a page that cannot be written is said in the trial's recording error
void write_trial_replay(const SweepFolder& folder, std::int64_t trial, TrialOutcome& o) {
  if (!replay_html_available()) return;
  try {
    const plot::Recording recording =
        plot::Recording::load(o.recording, plot::TableRows::header_only);
    write_replay_html(recorded_model(recording), recording, folder.record(trial) / "replay.html");
  } catch (const Error& e) {
    o.recording_error = std::string("replay page: ") + e.what();
  }
}

}  // namespace

bool run_sweep_shard(const SweepFolder& folder, const SweepPlan& plan, std::int64_t index,
                     const std::function<void()>& on_trial) {
  if (index < 0 || index >= plan.shards())
    throw Error("sweep: no shard " + std::to_string(index) + "; the plan has " +
                std::to_string(plan.shards()) + " (0 to " + std::to_string(plan.shards() - 1) +
                ")");
  const Scenario& scenario = find_scenario(plan.file.scenario);
  const SweepShard shard = plan.shard(index);
  const std::string started = utc_now();
  const auto t0 = std::chrono::steady_clock::now();
  Json rows = Json::array();
  for (std::int64_t trial = shard.first; trial < shard.first + shard.count; ++trial) {
    if (interrupt_requested()) return false;
    const Json values = trial_values(plan, trial);
    const auto outputs_of = [&] {
      ScenarioOutputs outputs;
      outputs.record = folder.record(trial) / "recording";
      outputs.video = folder.record(trial) / "video.mp4";
      fs::create_directories(folder.record(trial));
      return outputs;
    };
    Json row;
    try {
      const bool record_all = plan.file.record == RecordTrials::all;
      TrialOutcome o = scenario.run(values, record_all ? outputs_of() : ScenarioOutputs{});
      if (!o.success && plan.file.record == RecordTrials::failures &&
          o.status != RunStatus::interrupted)
        o = scenario.run(values, outputs_of());  // the same trial again, kept this time
      if (o.status == RunStatus::interrupted) return false;
      if (!o.recording.empty() && o.recording_error.empty()) write_trial_replay(folder, trial, o);
      row = row_of(plan, trial, o, folder.dir);
    } catch (const Error& e) {
      row = error_row(plan, trial, e.what(), scenario.metrics().size());
    }
    rows.push_back(std::move(row));
    if (on_trial) on_trial();
  }
  if (interrupt_requested()) return false;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Json doc{{"plan", plan.hash},    {"shard", index},      {"first", shard.first},
                 {"count", shard.count}, {"host", host_name()}, {"started", started},
                 {"seconds", seconds},   {"rows", rows}};
  std::error_code ec;
  fs::create_directories(folder.shards(), ec);
  write_file(folder.shard(index), doc.dump() + "\n", "shard file");
  return true;
}

}  // namespace mjarm
