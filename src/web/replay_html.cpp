#include "mjarm/web/replay_html.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base64.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/web/page_html.hpp"
#include "replay_bundle.hpp"
#include "replay_cameras.hpp"
#include "replay_frames.hpp"
#include "replay_overlays.hpp"
#include "replay_plots.hpp"
#include "replay_scene.hpp"
#include "replay_task.hpp"

namespace mjarm {

bool replay_html_available() { return web_detail::replay_bundle_missing().empty(); }

std::string replay_html_missing() { return web_detail::replay_bundle_missing(); }

namespace {

// task.csv's samples at the frames @p keep
std::map<std::string, std::vector<double>> select_rows(
    const std::map<std::string, std::vector<double>>& columns,
    const std::vector<std::size_t>& keep) {
  std::map<std::string, std::vector<double>> out;
  for (const auto& [name, values] : columns) {
    std::vector<double>& kept = out[name];
    kept.reserve(keep.size());
    for (std::size_t f : keep) kept.push_back(values[f]);
  }
  return out;
}

std::string megabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
  return text;
}

std::string grouped(std::int64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string ordinal(std::int64_t n) {
  const std::int64_t tens = n % 100, ones = n % 10;
  const char* suffix = (tens >= 11 && tens <= 13) ? "th"
                       : ones == 1                ? "st"
                       : ones == 2                ? "nd"
                       : ones == 3                ? "rd"
                                                  : "th";
  return std::to_string(n) + suffix;
}

}  // namespace

ReplayHtmlReport write_replay_html(const Robot& robot, const plot::Recording& recording,
                                   const std::filesystem::path& out,
                                   const ReplayHtmlOptions& options) {
  check_fields(options);
  const std::string missing = web_detail::replay_bundle_missing();
  if (!missing.empty()) throw Error("replay-html: " + missing);
  const mjModel& m = robot.model();
  const std::filesystem::path state_csv = recording.directory() / "state.csv";
  const std::filesystem::path task_csv = recording.directory() / "task.csv";
  // the first pass: the model against the columns, every row's time, the file whole and sound
  const web_detail::StateScan scan = web_detail::scan_state(m, state_csv);
  const web_detail::ReplayScene scene = web_detail::replay_scene(m);
  const std::string bundle = web_detail::replay_bundle();
  const std::string title =
      options.title.empty() ? recording.directory().filename().string() : options.title;
  const std::string head = html_page_head(title + " — mjarm replay") +
                           "<script type=\"application/json\" id=\"mjarm-replay-data\">";
  const std::string middle = "</script>\n<script>";
  const std::string tail = "</script>\n</body>\n</html>\n";

  nlohmann::json base = scene.json;
  base["title"] = title;
  base["model"] = recording.model();
  base["status"] = recording.status();
  base["events"] = nlohmann::json::array();
  for (const plot::RecordedEvent& e : recording.events())
    base["events"].push_back({{"t", e.t}, {"kind", e.kind}, {"message", e.message}});
  std::vector<std::string> warnings = robot.missing_meshes();
  base["warnings"] = warnings;

  // the size cap: what the page holds whatever the run (the script, the model, the events), and
  // what each frame adds without its contacts (as base64: 4 bytes per 3): the time (twice: the
  // frames' and the plots'), every body's pose, the plotted series, the tool and target poses,
  // the contacts' offset
  const std::vector<std::string> state_columns = web_detail::plot_state_columns(recording);
  std::vector<std::string> task_columns = web_detail::plot_task_columns();
  for (const std::string& c : web_detail::overlay_task_columns()) task_columns.push_back(c);
  const double cap = options.max_mb * 1e6;
  const double fixed = static_cast<double>(head.size() + middle.size() + tail.size() +
                                           bundle.size() + base.dump().size()) +
                       4096.0;  // the keys and the decimation note
  int moving_cameras = 0;
  for (int c = 0; c < m.ncam; ++c) moving_cameras += web_detail::camera_moves(m, c) ? 1 : 0;
  const double per_frame = 4.0 / 3.0 * 4.0 *
                           static_cast<double>(2 + 7 * m.nbody + 7 * moving_cameras +
                                               state_columns.size() + 2 + 14 + 1 + 1);
  if (fixed + 2.0 * per_frame > cap) {
    throw Error("replay-html: the page without its frames is already " + megabytes(fixed) +
                " (the page's script, the model's meshes and textures), over --max-mb " +
                number_text(options.max_mb) + ": raise it");
  }
  const double duration = scan.last - scan.first;
  const double max_frames = std::floor((cap - fixed) / per_frame);
  double rate = options.rate;
  if (duration > 0.0 && duration * rate + 2.0 > max_frames)
    rate = std::max(max_frames - 2.0, 1.0) / duration;

  // the second pass: the kept rows' frames, then task.csv at their times
  web_detail::ReplayFrames frames = web_detail::replay_frames(m, state_csv, rate, state_columns);
  if (!frames.stopped.empty()) warnings.push_back(frames.stopped);
  std::map<std::string, std::vector<double>> task =
      web_detail::sample_task(task_csv, task_columns, frames.time);

  // the contacts are not in the estimate: every k-th frame while the page is over the cap
  bool thinned = false;
  std::string data_text;
  ReplayHtmlReport report;
  while (true) {
    const double span = frames.time.back() - frames.time.front();
    report.rate = span > 0.0 ? static_cast<double>(frames.time.size() - 1) / span : options.rate;
    report.decimated = thinned || rate < options.rate;
    report.decimation.clear();
    if (report.decimated) {
      const auto n = static_cast<std::int64_t>(frames.time.size());
      report.decimation =
          "decimated to fit " + megabytes(cap) + " (--max-mb): " + grouped(n) + " frames of " +
          grouped(scan.rows) + " state rows (about every " +
          ordinal(std::max<std::int64_t>(1, scan.rows / std::max<std::int64_t>(n, 1))) + " row), " +
          number_text(std::round(report.rate * 1000.0) / 1000.0) + " per second instead of " +
          number_text(options.rate) + ": motion faster than a frame is smoothed";
    }
    nlohmann::json data = base;
    data["rate"] = report.decimated ? std::round(report.rate * 1000.0) / 1000.0 : options.rate;
    data["warnings"] = warnings;
    data["decimation"] = report.decimation;
    const std::vector<float> time(frames.time.begin(), frames.time.end());
    data["frames"] = {{"time", web_detail::base64_floats(time)},
                      {"pos", web_detail::base64_floats(frames.pos)},
                      {"quat", web_detail::base64_floats(frames.quat)}};
    data["overlays"] = web_detail::replay_overlays(frames, task);
    data["camera_poses"] = web_detail::replay_camera_poses(frames);
    const web_detail::ReplayPlots plots =
        web_detail::replay_plots(recording, frames.time, frames.series, task);
    data["plot_time"] = plots.json["plot_time"];
    data["plots"] = plots.json["plots"];
    report.plots = plots.count;
    data_text = script_safe_json(data.dump());
    const double total = static_cast<double>(head.size() + data_text.size() + middle.size() +
                                             bundle.size() + tail.size());
    if (total <= cap) break;
    if (frames.time.size() <= 2) {
      throw Error("replay-html: the page of the run's first and last frames alone is " +
                  megabytes(total) + ", over --max-mb " + number_text(options.max_mb) +
                  ": raise it");
    }
    const double frame_bytes = total - (fixed - 4096.0);
    const auto k = static_cast<std::size_t>(
        std::max(2.0, std::ceil(frame_bytes / std::max(cap - fixed, 1.0))));
    const std::vector<std::size_t> keep = web_detail::every_kth(frames.time.size(), k);
    frames = web_detail::select_frames(frames, keep);
    task = select_rows(task, keep);
    thinned = true;
  }

  FileWriter writer(out, FileWriter::Mode::replace, "replay page");
  writer.write(head);
  writer.write(data_text);
  writer.write(middle);
  writer.write(bundle);
  writer.write(tail);
  writer.commit();

  report.path = out;
  report.bytes = writer.bytes();
  report.frames = static_cast<int>(frames.time.size());
  report.state_rows = scan.rows;
  report.start_time = frames.time.front();
  report.end_time = frames.time.back();
  report.bodies = m.nbody;
  report.drawn_geoms = scene.drawn_geoms;
  report.meshes = scene.meshes;
  report.cameras = scene.cameras;
  report.largest_gap = frames.largest_gap;
  report.warnings = warnings;
  return report;
}

}  // namespace mjarm
