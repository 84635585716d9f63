#include "mjarm/sweep/sweep_file.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "yaml_json.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;

/// Reads one JSON document in the shape of a sweep file, naming `source` and the key path.
class SweepReader {
 public:
  explicit SweepReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& message) const {
    throw Error(source_ + ": " + (where.empty() ? "" : where + ": ") + message);
  }

  void only_keys(const Json& object, const std::vector<std::string>& known,
                 const std::string& where) const {
    if (!object.is_object()) fail(where, "must be a mapping, got " + object.dump());
    for (auto it = object.begin(); it != object.end(); ++it)
      if (std::find(known.begin(), known.end(), it.key()) == known.end())
        fail(where, unknown_name_message("key", it.key(), known));
  }

  double number(const Json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "must be a number, got " + j.dump());
    return j.get<double>();
  }

  std::int64_t whole(const Json& j, const std::string& where, std::int64_t least) const {
    if (!j.is_number_integer() || j.get<std::int64_t>() < least)
      fail(where, "must be a whole number ≥ " + std::to_string(least) + ", got " + j.dump());
    return j.get<std::int64_t>();
  }

 private:
  std::string source_;
};

/// The scenario's parameter called @p name (dashes or underscores), by its canonical name.
const FieldInfo& parameter_info(const std::vector<FieldInfo>& table, const std::string& name,
                                const SweepReader& reader, const std::string& where) {
  const std::string wanted = parameter_name(name);
  for (const FieldInfo& info : table)
    if (info.path == wanted) return info;
  std::vector<std::string> names;
  for (const FieldInfo& info : table) names.push_back(info.path);
  reader.fail(where, unknown_name_message("parameter", wanted, names));
}

/// The values of a `{from, to, num, log}` axis.
std::vector<Json> range_values(const Json& spec, const FieldInfo& info, const SweepReader& reader,
                               const std::string& where) {
  reader.only_keys(spec, {"from", "to", "num", "log"}, where);
  if (info.kind != FieldKind::number && info.kind != FieldKind::integer)
    reader.fail(where, "a range needs a number parameter; " + info.path + " is " +
                           to_string(info.kind) + ": list its values");
  for (const char* key : {"from", "to", "num"})
    if (!spec.contains(key)) reader.fail(where, std::string("a range needs '") + key + "'");
  const double from = reader.number(spec["from"], where + ".from");
  const double to = reader.number(spec["to"], where + ".to");
  const std::int64_t num = reader.whole(spec["num"], where + ".num", 1);
  const bool log = spec.value("log", false);
  if (!std::isfinite(from) || !std::isfinite(to)) reader.fail(where, "from and to must be finite");
  if (log && !(from > 0.0 && to > 0.0))
    reader.fail(where, "a log range needs from and to > 0, got " + spec.dump());
  if (num > 1'000'000)
    reader.fail(where + ".num", "at most 1000000 values, got " + std::to_string(num));
  if (num == 1 && from != to) reader.fail(where, "one value (num: 1) needs from = to");
  std::vector<Json> values;
  for (std::int64_t k = 0; k < num; ++k) {
    const double u = num == 1 ? 0.0 : static_cast<double>(k) / static_cast<double>(num - 1);
    double x = log ? from * std::pow(to / from, u) : from + u * (to - from);
    if (k == num - 1) x = to;  // the end exactly, not up to rounding
    if (info.kind == FieldKind::integer)
      values.emplace_back(static_cast<std::int64_t>(std::llround(x)));
    else
      values.emplace_back(x);
  }
  return values;
}

/// Checks @p value for parameter @p name through the scenario, with the fixed values.
void check_value(const Scenario& scenario, const Json& fixed, const std::string& name,
                 const Json& value, const SweepReader& reader, const std::string& where) {
  Json values = fixed;
  values[name] = value;
  try {
    scenario.resolve(values);
  } catch (const Error& e) {
    reader.fail(where, e.what());
  }
}

std::int64_t checked_product(std::int64_t a, std::int64_t b) {
  if (a != 0 && b > std::numeric_limits<std::int64_t>::max() / a)
    return std::numeric_limits<std::int64_t>::max();
  return a * b;
}

}  // namespace

SweepFile sweep_file_from_json(const Json& doc, const std::string& source) {
  const SweepReader reader(source);
  reader.only_keys(doc, {"scenario", "parameters", "axes", "zip", "random", "seeds", "record"}, "");
  SweepFile file;
  file.source = source;
  if (!doc.contains("scenario") || !doc["scenario"].is_string())
    reader.fail("", "'scenario' must name a scenario");
  const Scenario* scenario = nullptr;
  try {
    scenario = &find_scenario(doc["scenario"].get<std::string>());
  } catch (const Error& e) {
    reader.fail("scenario", e.what());
  }
  file.scenario = std::string(scenario->name());
  const std::vector<FieldInfo> table = scenario->parameters();
  const bool seeded = std::any_of(table.begin(), table.end(),
                                  [](const FieldInfo& info) { return info.path == "seed"; });
  std::set<std::string> taken;  // every parameter the file sets, once
  const auto take = [&](const std::string& name, const std::string& where) {
    if (name == "seed" && seeded)
      reader.fail(where, "the seed is set by 'seeds:', not as a parameter");
    if (!taken.insert(name).second) reader.fail(where, name + " is set twice");
  };

  // ---- fixed parameters
  if (doc.contains("parameters")) {
    const Json& given = doc["parameters"];
    if (!given.is_object()) reader.fail("parameters", "must be a mapping, got " + given.dump());
    for (auto it = given.begin(); it != given.end(); ++it) {
      const std::string where = "parameters." + it.key();
      const std::string name = parameter_info(table, it.key(), reader, where).path;
      take(name, where);
      file.parameters[name] = it.value();
    }
    try {
      scenario->resolve(file.parameters);
    } catch (const Error& e) {
      reader.fail("parameters", e.what());
    }
  }

  // ---- the grid's axes
  if (doc.contains("axes")) {
    const Json& axes = doc["axes"];
    if (!axes.is_object()) reader.fail("axes", "must be a mapping, got " + axes.dump());
    for (auto it = axes.begin(); it != axes.end(); ++it) {
      const std::string where = "axes." + it.key();
      const FieldInfo& info = parameter_info(table, it.key(), reader, where);
      take(info.path, where);
      SweepAxis axis{info.path, {}};
      if (it.value().is_array()) {
        axis.values.assign(it.value().begin(), it.value().end());
      } else if (it.value().is_object()) {
        axis.values = range_values(it.value(), info, reader, where);
      } else {
        reader.fail(where, "must be a list of values or {from, to, num}, got " + it.value().dump());
      }
      if (axis.values.empty()) reader.fail(where, "an axis needs at least one value");
      // a range's values lie between its ends: checking the ends checks them all
      const bool range = it.value().is_object();
      for (std::size_t k = 0; k < axis.values.size(); ++k)
        if (!range || k == 0 || k + 1 == axis.values.size())
          check_value(*scenario, file.parameters, info.path, axis.values[k], reader,
                      where + "[" + std::to_string(k) + "]");
      file.axes.push_back(std::move(axis));
    }
  }

  // ---- zipped axes: each group advances together
  std::vector<int> group_of(file.axes.size(), -1);
  std::vector<std::vector<std::size_t>> zipped;
  if (doc.contains("zip")) {
    const Json& zip = doc["zip"];
    if (!zip.is_array()) reader.fail("zip", "must be a list of lists of axes, got " + zip.dump());
    for (std::size_t g = 0; g < zip.size(); ++g) {
      const std::string where = "zip[" + std::to_string(g) + "]";
      if (!zip[g].is_array() || zip[g].size() < 2)
        reader.fail(where, "must list two axes or more, got " + zip[g].dump());
      std::vector<std::size_t> group;
      for (const Json& name : zip[g]) {
        const std::string wanted = name.is_string() ? parameter_name(name.get<std::string>()) : "";
        const auto axis = std::find_if(file.axes.begin(), file.axes.end(),
                                       [&](const SweepAxis& a) { return a.name == wanted; });
        if (axis == file.axes.end()) reader.fail(where, name.dump() + " is not an axis");
        const auto index = static_cast<std::size_t>(axis - file.axes.begin());
        if (group_of[index] >= 0) reader.fail(where, wanted + " is zipped twice");
        if (axis->values.size() != file.axes[group.empty() ? index : group.front()].values.size())
          reader.fail(where, "zipped axes need the same number of values: " +
                                 file.axes[group.front()].name + " has " +
                                 std::to_string(file.axes[group.front()].values.size()) + ", " +
                                 wanted + " " + std::to_string(axis->values.size()));
        group_of[index] = static_cast<int>(zipped.size());
        group.push_back(index);
      }
      zipped.push_back(std::move(group));
    }
  }
  std::vector<bool> emitted(zipped.size(), false);
  for (std::size_t a = 0; a < file.axes.size(); ++a) {
    if (group_of[a] < 0) {
      file.groups.push_back({a});
    } else if (!emitted[static_cast<std::size_t>(group_of[a])]) {
      emitted[static_cast<std::size_t>(group_of[a])] = true;
      file.groups.push_back(zipped[static_cast<std::size_t>(group_of[a])]);
    }
  }

  // ---- the random design
  if (doc.contains("random")) {
    const Json& random = doc["random"];
    reader.only_keys(random, {"samples", "seed", "ranges"}, "random");
    if (!random.contains("samples") || !random.contains("ranges"))
      reader.fail("random", "needs 'samples' and 'ranges'");
    file.random.samples = reader.whole(random["samples"], "random.samples", 1);
    if (file.random.samples > 1'000'000)
      reader.fail("random.samples", "at most 1000000, got " + random["samples"].dump());
    if (random.contains("seed"))
      file.random.seed = static_cast<std::uint64_t>(reader.whole(random["seed"], "random.seed", 0));
    const Json& ranges = random["ranges"];
    if (!ranges.is_object() || ranges.empty())
      reader.fail("random.ranges", "must map parameters to {from, to}, got " + ranges.dump());
    for (auto it = ranges.begin(); it != ranges.end(); ++it) {
      const std::string where = "random.ranges." + it.key();
      const FieldInfo& info = parameter_info(table, it.key(), reader, where);
      take(info.path, where);
      reader.only_keys(it.value(), {"from", "to", "log"}, where);
      if (info.kind != FieldKind::number && info.kind != FieldKind::integer)
        reader.fail(where, "a range needs a number parameter; " + info.path + " is " +
                               to_string(info.kind));
      if (!it.value().contains("from") || !it.value().contains("to"))
        reader.fail(where, "a range needs 'from' and 'to'");
      SweepRange range{info.path, reader.number(it.value()["from"], where + ".from"),
                       reader.number(it.value()["to"], where + ".to"),
                       it.value().value("log", false), info.kind == FieldKind::integer};
      if (!(range.from < range.to)) reader.fail(where, "needs from < to, got " + it.value().dump());
      if (range.log && !(range.from > 0.0))
        reader.fail(where, "a log range needs from > 0, got " + it.value().dump());
      for (const double end : {range.from, range.to})
        check_value(*scenario, file.parameters, info.path,
                    range.integer ? Json(std::llround(end)) : Json(end), reader, where);
      file.random.ranges.push_back(std::move(range));
    }
  }

  // ---- seeds and records
  if (doc.contains("seeds")) {
    const Json& seeds = doc["seeds"];
    if (seeds.is_object()) {
      reader.only_keys(seeds, {"first", "count"}, "seeds");
      if (seeds.contains("first"))
        file.first_seed =
            static_cast<std::uint64_t>(reader.whole(seeds["first"], "seeds.first", 0));
      if (!seeds.contains("count")) reader.fail("seeds", "needs 'count'");
      file.seeds = reader.whole(seeds["count"], "seeds.count", 1);
    } else {
      file.seeds = reader.whole(seeds, "seeds", 1);
    }
    if (!seeded && (file.seeds != 1 || file.first_seed != 1))
      reader.fail("seeds",
                  file.scenario + " draws nothing (no seed parameter): one trial per point");
  }
  if (doc.contains("record")) {
    const Json& record = doc["record"];
    const std::string word = record.is_string() ? record.get<std::string>() : record.dump();
    if (const auto value = enum_from_name<RecordTrials>(word))
      file.record = *value;
    else
      reader.fail("record", unknown_name_message("choice", word, enum_names<RecordTrials>()));
  }

  // ---- the size, before any work
  std::int64_t trials = std::max<std::int64_t>(file.random.samples, 1);
  for (const auto& group : file.groups)
    trials =
        checked_product(trials, static_cast<std::int64_t>(file.axes[group.front()].values.size()));
  trials = checked_product(trials, file.seeds);
  if (trials > kMaxSweepTrials)
    reader.fail("", "the sweep has " +
                        (trials == std::numeric_limits<std::int64_t>::max()
                             ? std::string("more than 9.2e18")
                             : std::to_string(trials)) +
                        " trials; at most " + std::to_string(kMaxSweepTrials));
  return file;
}

SweepFile parse_sweep_file(const std::string& text, const std::string& source) {
  const Json doc = yaml_to_json(text, source);
  if (doc.is_null()) throw Error(source + ": the sweep file is empty");
  return sweep_file_from_json(doc, source);
}

SweepFile read_sweep_file(const std::filesystem::path& path) {
  return parse_sweep_file(read_user_file(path, "sweep file"), path.string());
}

Json sweep_file_json(const SweepFile& file) {
  Json axes = Json::object();
  for (const SweepAxis& axis : file.axes) axes[axis.name] = axis.values;
  Json zip = Json::array();
  for (const auto& group : file.groups) {
    if (group.size() < 2) continue;
    Json names = Json::array();
    for (const std::size_t a : group) names.push_back(file.axes[a].name);
    zip.push_back(std::move(names));
  }
  Json doc{
      {"scenario", file.scenario}, {"parameters", file.parameters}, {"axes", axes}, {"zip", zip}};
  if (file.random.samples > 0) {
    Json ranges = Json::object();
    for (const SweepRange& r : file.random.ranges)
      ranges[r.name] = {{"from", r.from}, {"to", r.to}, {"log", r.log}};
    doc["random"] = {
        {"samples", file.random.samples}, {"seed", file.random.seed}, {"ranges", ranges}};
  }
  doc["seeds"] = {{"first", file.first_seed}, {"count", file.seeds}};
  doc["record"] = to_string(file.record);
  return doc;
}

}  // namespace mjarm
