#include "mjarm/sweep/sweep_plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "mjarm/sweep/sweep_report.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;

std::string value_label(const Json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) {
    char text[64];
    std::snprintf(text, sizeof text, "[%.4g, %.4g)", v[0].get<double>(), v[1].get<double>());
    return text;
  }
  if (v.is_number_float()) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v.get<double>());
    return text;
  }
  return v.dump();
}

/// A table cell equal to axis value @p v (SQLite gives flags as 0/1 and arrays as JSON text).
bool cell_is(const Json& cell, const Json& v) {
  if (v.is_boolean()) return cell == (v.get<bool>() ? 1 : 0);
  if (v.is_array()) return cell == v.dump();
  if (v.is_number() && cell.is_number()) return cell.get<double>() == v.get<double>();
  return cell == v;
}

std::string with_unit(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + " [" + unit + "]";
}

}  // namespace

std::vector<plot::PlotInfo> plot_sweep(const SweepFolder& folder, const std::filesystem::path& out,
                                       const SweepPlotOptions& options) {
  const SweepPlan plan = read_sweep_plan(folder);
  const Scenario& scenario = find_scenario(plan.file.scenario);
  const SweepReport report = sweep_report(folder);
  const ResultTable table = read_trials(folder);
  std::vector<plot::PlotInfo> drawn;
  const std::string title = plan.file.scenario + " sweep (plan " + plan.hash + ")";

  // success against every varied parameter
  for (const std::string& name : varied_parameters(plan)) {
    plot::RateFigure figure;
    figure.name = "success_vs_" + name;
    std::replace(figure.name.begin(), figure.name.end(), '.', '_');
    figure.title = title + ": success against " + name + " (95 % Wilson intervals)";
    figure.xlabel = name;
    for (const ReportGroup& g : report.groups)
      if (g.parameter == name)
        figure.points.push_back({value_label(g.value), g.success.rate, g.success.low,
                                 g.success.high, static_cast<long long>(g.success.trials)});
    drawn.push_back(plot::plot_rates(figure, out, options.plot));
  }

  // the heat map over two grid axes
  std::vector<const SweepAxis*> axes;
  for (const std::string& wanted : options.heat_map) {
    const std::string name = parameter_name(wanted);
    const auto it = std::find_if(plan.file.axes.begin(), plan.file.axes.end(),
                                 [&](const SweepAxis& a) { return a.name == name; });
    if (it == plan.file.axes.end()) {
      std::vector<std::string> names;
      for (const SweepAxis& a : plan.file.axes) names.push_back(a.name);
      throw Error("heat map: " + unknown_name_message("axis", name, names));
    }
    axes.push_back(&*it);
  }
  if (!options.heat_map.empty() && axes.size() != 2)
    throw Error("heat map: two axes, got " + std::to_string(axes.size()));
  if (axes.empty())
    for (const SweepAxis& a : plan.file.axes)
      if (a.values.size() > 1 && axes.size() < 2) axes.push_back(&a);
  if (axes.size() == 2) {
    plot::HeatMapFigure figure;
    figure.name = "success_heat_map";
    figure.title = title + ": success rate";
    figure.xlabel = axes[0]->name;
    figure.ylabel = axes[1]->name;
    for (const Json& v : axes[0]->values) figure.columns.push_back(value_label(v));
    for (const Json& v : axes[1]->values) figure.rows.push_back(value_label(v));
    const int cx = table.column(axes[0]->name), cy = table.column(axes[1]->name);
    const int cs = table.column("success");
    for (const Json& y : axes[1]->values) {
      std::vector<double> row;
      for (const Json& x : axes[0]->values) {
        long long n = 0, ok = 0;
        for (const auto& r : table.rows)
          if (cell_is(r[static_cast<std::size_t>(cx)], x) &&
              cell_is(r[static_cast<std::size_t>(cy)], y)) {
            ++n;
            ok += r[static_cast<std::size_t>(cs)] == 1 ? 1 : 0;
          }
        row.push_back(n > 0 ? static_cast<double>(ok) / static_cast<double>(n)
                            : std::numeric_limits<double>::quiet_NaN());
      }
      figure.rates.push_back(std::move(row));
    }
    drawn.push_back(plot::plot_heat_map(figure, out, options.plot));
  }

  // every metric's distribution
  plot::HistogramFigure figure;
  figure.name = "metric_distributions";
  figure.title = title + ": metrics over " + std::to_string(table.rows.size()) + " trials";
  for (const MetricInfo& m : scenario.metrics()) {
    if (figure.histograms.size() == 12) break;
    const int c = table.column(m.name);
    plot::Histogram h{with_unit(m.name, m.unit), {}};
    for (const auto& r : table.rows)
      if (r[static_cast<std::size_t>(c)].is_number())
        h.values.push_back(r[static_cast<std::size_t>(c)].get<double>());
    figure.histograms.push_back(std::move(h));
  }
  drawn.push_back(plot::plot_histograms(figure, out, options.plot));
  return drawn;
}

}  // namespace mjarm
