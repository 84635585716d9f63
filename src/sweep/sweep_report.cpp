#include "mjarm/sweep/sweep_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/json_or_null.hpp"
#include "mjarm/scenarios/registry.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;
constexpr int kBins = 5;  // a random range's values in this many equal-width bins

MetricSummary summarize(const MetricInfo& info, std::vector<double> values) {
  MetricSummary s{info.name, info.unit, static_cast<std::int64_t>(values.size()),
                  std::numeric_limits<double>::quiet_NaN(),
                  std::numeric_limits<double>::quiet_NaN()};
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  s.median = n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  s.p95 = values[static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n))) - 1];
  return s;
}

Json rate_json(const SuccessRate& r) {
  return Json{{"successes", r.successes},
              {"trials", r.trials},
              {"rate", r.rate},
              {"low", r.low},
              {"high", r.high}};
}

Json metrics_json(const std::vector<MetricSummary>& metrics) {
  Json out = Json::object();
  for (const MetricSummary& m : metrics)
    out[m.name] = {{"unit", m.unit},
                   {"count", m.count},
                   {"median", number_or_null(m.median)},
                   {"p95", number_or_null(m.p95)}};
  return out;
}

}  // namespace

SuccessRate wilson_interval(std::int64_t successes, std::int64_t trials, double z) {
  SuccessRate r;
  r.successes = successes;
  r.trials = trials;
  if (trials <= 0) return r;
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2 = z * z;
  const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z / (1 + z2 / n) * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n));
  r.rate = p;
  r.low = std::max(0.0, centre - half);
  r.high = std::min(1.0, centre + half);
  return r;
}

SweepReport sweep_report(const SweepFolder& folder) {
  const SweepPlan plan = read_sweep_plan(folder);
  const Scenario& scenario = find_scenario(plan.file.scenario);
  const ResultTable t = read_trials(folder);
  SweepReport report;
  report.scenario = plan.file.scenario;
  report.hash = plan.hash;
  report.planned = plan.trials;
  const int success = t.column("success");
  const int verdict = t.column("verdict");
  std::vector<int> metric_columns;
  for (const MetricInfo& m : scenario.metrics()) metric_columns.push_back(t.column(m.name));

  // the summary of the rows @p in chooses
  const auto summary = [&](const auto& in) {
    std::int64_t ok = 0, n = 0;
    std::vector<std::vector<double>> values(metric_columns.size());
    for (const auto& row : t.rows) {
      if (!in(row)) continue;
      ++n;
      ok += row[static_cast<std::size_t>(success)] == 1 ? 1 : 0;
      for (std::size_t m = 0; m < metric_columns.size(); ++m) {
        const Json& v = row[static_cast<std::size_t>(metric_columns[m])];
        if (v.is_number()) values[m].push_back(v.get<double>());
      }
    }
    std::vector<MetricSummary> metrics;
    for (std::size_t m = 0; m < metric_columns.size(); ++m)
      metrics.push_back(summarize(scenario.metrics()[m], std::move(values[m])));
    return std::pair{wilson_interval(ok, n), metrics};
  };

  std::tie(report.success, report.metrics) = summary([](const auto&) { return true; });
  for (const auto& row : t.rows)
    ++report.verdicts[row[static_cast<std::size_t>(verdict)].get<std::string>()];

  for (const SweepAxis& axis : plan.file.axes) {
    const int c = t.column(axis.name);
    std::vector<Json> seen;  // the axis's values, once each, in order
    for (const Json& v : axis.values) {
      // a range rounded to whole numbers can repeat a value
      if (std::find(seen.begin(), seen.end(), v) != seen.end()) continue;
      seen.push_back(v);
      auto [rate, metrics] = summary([&](const auto& row) {
        const Json& cell = row[static_cast<std::size_t>(c)];
        // numbers and flags come back from SQLite as numbers, arrays as their JSON text
        if (v.is_boolean()) return cell == (v.get<bool>() ? 1 : 0);
        if (v.is_array()) return cell == v.dump();
        if (v.is_number() && cell.is_number()) return cell.get<double>() == v.get<double>();
        return cell == v;
      });
      report.groups.push_back({axis.name, v, rate, std::move(metrics)});
    }
  }
  for (const SweepRange& range : plan.file.random.ranges) {
    const int c = t.column(range.name);
    for (int b = 0; b < kBins; ++b) {
      const auto edge = [&](int k) {
        const double u = static_cast<double>(k) / kBins;
        return range.log ? range.from * std::pow(range.to / range.from, u)
                         : range.from + u * (range.to - range.from);
      };
      const double low = edge(b), high = edge(b + 1);
      auto [rate, metrics] = summary([&](const auto& row) {
        const Json& cell = row[static_cast<std::size_t>(c)];
        if (!cell.is_number()) return false;
        const double x = cell.get<double>();
        return x >= low && (x < high || (b == kBins - 1 && x <= high));
      });
      report.groups.push_back({range.name, Json::array({low, high}), rate, std::move(metrics)});
    }
  }
  return report;
}

Json sweep_report_json(const SweepReport& r) {
  Json groups = Json::array();
  for (const ReportGroup& g : r.groups)
    groups.push_back({{"parameter", g.parameter},
                      {"value", g.value},
                      {"success", rate_json(g.success)},
                      {"metrics", metrics_json(g.metrics)}});
  Json verdicts = Json::object();
  for (const auto& [name, count] : r.verdicts) verdicts[name] = count;
  return Json{{"scenario", r.scenario}, {"hash", r.hash},
              {"planned", r.planned},   {"success", rate_json(r.success)},
              {"verdicts", verdicts},   {"metrics", metrics_json(r.metrics)},
              {"groups", groups}};
}

}  // namespace mjarm
