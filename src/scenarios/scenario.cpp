#include "mjarm/scenarios/scenario.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/json_or_null.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;

std::string replaced(std::string_view text, char from, char to) {
  std::string out(text);
  std::replace(out.begin(), out.end(), from, to);
  return out;
}

}  // namespace

std::string parameter_name(std::string_view path) { return replaced(path, '_', '-'); }

namespace detail {

std::string parameter_path(std::string_view name) { return replaced(name, '-', '_'); }

std::vector<FieldInfo> as_parameters(std::vector<FieldInfo> table) {
  for (FieldInfo& info : table) info.path = parameter_name(info.path);
  return table;
}

void check_parameter_name(const std::vector<FieldInfo>& table, std::string_view name,
                          std::string_view where) {
  const std::string wanted = parameter_name(name);
  std::vector<std::string> names;
  for (const FieldInfo& info : table) {
    if (info.path == wanted) return;
    names.push_back(info.path);
  }
  throw Error(std::string(where) + ": " + unknown_name_message("parameter", wanted, names));
}

}  // namespace detail

Json outcome_json(const Scenario& scenario, const TrialOutcome& outcome) {
  Json metrics = Json::object();
  const std::vector<MetricInfo>& infos = scenario.metrics();
  for (std::size_t i = 0; i < infos.size() && i < outcome.metrics.size(); ++i)
    metrics[infos[i].name] = number_or_null(outcome.metrics[i]);
  Json videos = Json::array();
  for (const auto& v : outcome.videos) videos.push_back(v.string());
  return Json{
      {"scenario", scenario.name()},
      {"parameters", outcome.parameters},
      {"status", to_string(outcome.status)},
      {"verdict", outcome.verdict},
      {"success", outcome.success},
      {"message", outcome.message},
      {"end_time", outcome.end_time},
      {"metrics", std::move(metrics)},
      {"outputs", Json{{"recording", outcome.recording.empty() ? Json(nullptr)
                                                               : Json(outcome.recording.string())},
                       {"recording_error", text_or_null(outcome.recording_error)},
                       {"videos", std::move(videos)},
                       {"video_error", text_or_null(outcome.video_error)}}}};
}

Json parameter_json(const FieldInfo& p) {
  Json entry{{"name", p.path}, {"kind", to_string(p.kind)}, {"unit", p.unit}};
  if (p.kind == FieldKind::number || p.kind == FieldKind::integer || p.kind == FieldKind::numbers)
    entry["range"] = p.range.text(p.kind == FieldKind::integer);
  if (!p.names.empty()) entry["names"] = p.names;
  if (p.length >= 0) entry["length"] = p.length;
  entry["optional"] = p.optional;
  entry["default"] = p.value;
  entry["doc"] = p.doc;
  return entry;
}

Json scenario_json(const Scenario& scenario) {
  Json metrics = Json::array();
  for (const MetricInfo& m : scenario.metrics())
    metrics.push_back(
        {{"name", m.name}, {"unit", m.unit}, {"better", to_string(m.better)}, {"doc", m.doc}});
  Json parameters = Json::array();
  for (const FieldInfo& p : scenario.parameters()) parameters.push_back(parameter_json(p));
  return Json{{"name", scenario.name()},       {"doc", scenario.doc()},
              {"camera", scenario.camera()},   {"verdicts", scenario.verdicts()},
              {"metrics", std::move(metrics)}, {"parameters", std::move(parameters)}};
}

}  // namespace mjarm
