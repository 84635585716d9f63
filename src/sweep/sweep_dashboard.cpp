#include "mjarm/sweep/sweep_dashboard.hpp"

#include <set>

#include "mjarm/file_writer.hpp"
#include "mjarm/sweep/sweep_report.hpp"
#include "mjarm/sweep/sweep_results.hpp"
#include "mjarm/web/page_html.hpp"
#include "sweep/sweep_dashboard_page.hpp"

namespace mjarm {

namespace {

using Json = nlohmann::ordered_json;

/// @p path (relative to the sweep folder) as seen from the dashboard's folder.
std::string link(const SweepFolder& folder, const std::filesystem::path& html_dir,
                 const std::string& path) {
  const std::filesystem::path target = std::filesystem::absolute(folder.dir / path);
  return std::filesystem::relative(target, html_dir).generic_string();
}

}  // namespace

std::string sweep_dashboard_html(const SweepFolder& folder, const std::filesystem::path& html) {
  const SweepReport report = sweep_report(folder);
  const ResultTable trials = read_trials(folder);
  const std::filesystem::path html_dir = std::filesystem::absolute(html).parent_path();
  Json parameters = Json::array();
  std::set<std::string> seen;
  for (const ReportGroup& g : report.groups)
    if (seen.insert(g.parameter).second) parameters.push_back(g.parameter);
  Json metrics = Json::array();
  for (const MetricSummary& m : report.metrics)
    metrics.push_back({{"name", m.name}, {"unit", m.unit}});
  // a recorded trial's links: its replay when one was written, its recording and video
  Json links = Json::object();
  const int trial = trials.column("trial"), recording = trials.column("recording");
  const int videos = trials.column("videos");
  for (const auto& row : trials.rows) {
    if (recording < 0 || row[recording].is_null()) continue;
    const std::string record = row[recording].get<std::string>();
    Json l{{"recording", link(folder, html_dir, record)}};
    const std::filesystem::path replay =
        std::filesystem::path(record).parent_path() / "replay.html";
    if (std::filesystem::exists(folder.dir / replay))
      l["replay"] = link(folder, html_dir, replay.string());
    if (videos >= 0 && row[videos].is_string()) {
      // the column holds the JSON array of the trial's videos: the first is linked
      const Json list = Json::parse(row[videos].get<std::string>(), nullptr, false);
      if (list.is_array() && !list.empty() && list[0].is_string())
        l["video"] = link(folder, html_dir, list[0].get<std::string>());
    }
    links[row[trial].dump()] = l;
  }
  const Json data{
      {"report", sweep_report_json(report)}, {"parameters", parameters}, {"metrics", metrics},
      {"columns", trials.columns},           {"rows", trials.rows},      {"links", links}};
  std::string page = sweep_dashboard_page();
  const std::string marker = "@DATA@";
  page.replace(page.find(marker), marker.size(), script_safe_json(data.dump()));
  return page;
}

SweepDashboard write_sweep_dashboard(const SweepFolder& folder, const std::filesystem::path& html) {
  const std::string page = sweep_dashboard_html(folder, html);
  FileWriter out(html, FileWriter::Mode::replace, "dashboard");
  out.write(page);
  out.commit();
  SweepDashboard d;
  d.path = html;
  d.bytes = page.size();
  const ResultTable trials = read_trials(folder);
  d.trials = static_cast<std::int64_t>(trials.rows.size());
  const int recording = trials.column("recording");
  for (const auto& row : trials.rows)
    if (recording >= 0 && !row[recording].is_null()) ++d.recorded;
  return d;
}

}  // namespace mjarm
