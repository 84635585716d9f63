#include "mjarm/sweep/sweep_plan.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "mjarm/error.hpp"
#include "mjarm/random.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "mjarm/version.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;

std::int64_t grid_points(const SweepFile& f) {
  std::int64_t n = 1;
  for (const auto& group : f.groups)
    n *= static_cast<std::int64_t>(f.axes[group.front()].values.size());
  return n;
}

/// The Latin hypercube: for each range, a shuffled stratum per sample and one uniform draw in it.
std::vector<std::vector<double>> latin_hypercube(const SweepRandom& r) {
  const auto n = static_cast<std::size_t>(r.samples);
  std::vector<std::vector<double>> rows(n, std::vector<double>(r.ranges.size()));
  Random rng(r.seed);
  std::vector<std::size_t> strata(n);
  for (std::size_t c = 0; c < r.ranges.size(); ++c) {
    std::iota(strata.begin(), strata.end(), std::size_t{0});
    for (std::size_t i = n; i > 1; --i)  // Fisher–Yates with the platform-independent draw
      std::swap(strata[i - 1], strata[uniform_index(rng, i)]);
    const SweepRange& range = r.ranges[c];
    for (std::size_t s = 0; s < n; ++s) {
      const double u = (static_cast<double>(strata[s]) + uniform(rng)) / static_cast<double>(n);
      double x = range.log ? range.from * std::pow(range.to / range.from, u)
                           : range.from + u * (range.to - range.from);
      if (range.integer) x = std::round(x);
      rows[s][c] = x;
    }
  }
  return rows;
}

/// The plan's content without its hash: what the hash covers.
Json hashed_part(const SweepPlan& p) {
  return Json{{"sweep", sweep_file_json(p.file)},
              {"points", p.points},
              {"trials", p.trials},
              {"shard_size", p.shard_size},
              {"version", p.version}};
}

}  // namespace

std::string text_hash(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char digits[17];
  std::snprintf(digits, sizeof digits, "%016llx", static_cast<unsigned long long>(h));
  return digits;
}

SweepShard SweepPlan::shard(std::int64_t index) const noexcept {
  const std::int64_t first = index * shard_size;
  return {index, first, std::min(shard_size, trials - first)};
}

SweepPlan make_sweep_plan(SweepFile file, std::int64_t shard_size) {
  if (shard_size < 1)
    throw Error("sweep: the shard size must be ≥ 1, got " + std::to_string(shard_size));
  SweepPlan plan;
  plan.file = std::move(file);
  plan.points = grid_points(plan.file) * std::max<std::int64_t>(plan.file.random.samples, 1);
  plan.trials = plan.points * plan.file.seeds;
  plan.shard_size = std::min(shard_size, plan.trials);
  plan.version = version();
  plan.samples = latin_hypercube(plan.file.random);
  for (const FieldInfo& info : find_scenario(plan.file.scenario).parameters())
    plan.seeded = plan.seeded || info.path == "seed";
  plan.hash = text_hash(hashed_part(plan).dump());
  return plan;
}

ShardSizing choose_shard_size(const SweepFile& file, double shard_seconds,
                              std::int64_t min_shards) {
  if (!(shard_seconds > 0.0) || min_shards < 1)
    throw Error("sweep: the shard time must be > 0 and the shards ≥ 1");
  const SweepPlan plan = make_sweep_plan(file, 1);
  const auto t0 = std::chrono::steady_clock::now();
  find_scenario(file.scenario).run(trial_values(plan, 0));
  ShardSizing sizing;
  sizing.trial_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double by_time = std::floor(shard_seconds / std::max(sizing.trial_seconds, 1e-6));
  const std::int64_t by_count = std::max<std::int64_t>(1, plan.trials / min_shards);
  sizing.shard_size = std::clamp<std::int64_t>(
      std::min<std::int64_t>(static_cast<std::int64_t>(std::min(by_time, 1e15)), by_count), 1,
      plan.trials);
  return sizing;
}

std::int64_t trial_point(const SweepPlan& plan, std::int64_t trial) noexcept {
  return trial / plan.file.seeds;
}

std::uint64_t trial_seed(const SweepPlan& plan, std::int64_t trial) noexcept {
  return plan.file.first_seed + static_cast<std::uint64_t>(trial % plan.file.seeds);
}

Json trial_values(const SweepPlan& plan, std::int64_t trial) {
  const SweepFile& f = plan.file;
  Json values = f.parameters;
  const std::int64_t samples = std::max<std::int64_t>(f.random.samples, 1);
  const std::int64_t point = trial_point(plan, trial);
  std::int64_t grid = point / samples;
  // the last group varies fastest
  for (auto group = f.groups.rbegin(); group != f.groups.rend(); ++group) {
    const auto size = static_cast<std::int64_t>(f.axes[group->front()].values.size());
    const auto k = static_cast<std::size_t>(grid % size);
    grid /= size;
    for (const std::size_t a : *group) values[f.axes[a].name] = f.axes[a].values[k];
  }
  if (f.random.samples > 0) {
    const auto& row = plan.samples[static_cast<std::size_t>(point % samples)];
    for (std::size_t c = 0; c < f.random.ranges.size(); ++c)
      values[f.random.ranges[c].name] =
          f.random.ranges[c].integer ? Json(std::llround(row[c])) : Json(row[c]);
  }
  if (plan.seeded) values["seed"] = trial_seed(plan, trial);
  return values;
}

std::vector<std::string> varied_parameters(const SweepPlan& plan) {
  std::vector<std::string> names;
  for (const SweepAxis& a : plan.file.axes) names.push_back(a.name);
  for (const SweepRange& r : plan.file.random.ranges) names.push_back(r.name);
  return names;
}

Json sweep_plan_json(const SweepPlan& plan) {
  Json doc = hashed_part(plan);
  doc["hash"] = plan.hash;
  return doc;
}

SweepPlan sweep_plan_from_json(const Json& doc, const std::string& source) {
  for (const char* key : {"sweep", "shard_size", "version", "hash"})
    if (!doc.is_object() || !doc.contains(key))
      throw Error(source + ": not a sweep plan (no '" + key + "')");
  if (!doc["shard_size"].is_number_integer() || !doc["hash"].is_string() ||
      !doc["version"].is_string())
    throw Error(source + ": not a sweep plan (shard_size, version or hash of the wrong type)");
  SweepPlan plan = make_sweep_plan(sweep_file_from_json(doc["sweep"], source),
                                   doc["shard_size"].get<std::int64_t>());
  plan.version = doc["version"].get<std::string>();
  plan.hash = text_hash(hashed_part(plan).dump());
  if (plan.hash != doc["hash"].get<std::string>() || sweep_plan_json(plan) != doc)
    throw Error(source + ": the plan's hash " + doc["hash"].get<std::string>() +
                " does not match its content (" + plan.hash + "): edited or damaged");
  return plan;
}

}  // namespace mjarm
