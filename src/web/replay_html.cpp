#include "mjarm/web/replay_html.hpp"

#include <nlohmann/json.hpp>
#include <string>

#include "base64.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "page_html.hpp"
#include "replay_bundle.hpp"
#include "replay_cameras.hpp"
#include "replay_frames.hpp"
#include "replay_overlays.hpp"
#include "replay_plots.hpp"
#include "replay_scene.hpp"

namespace mjarm {
bool replay_html_available() { return web_detail::replay_bundle_missing().empty(); }

ReplayHtmlReport write_replay_html(const Robot& robot, const plot::Recording& recording,
                                   const std::filesystem::path& out,
                                   const ReplayHtmlOptions& options) {
  check_fields(options);
  const std::string missing = web_detail::replay_bundle_missing();
  if (!missing.empty()) throw Error("replay-html: " + missing);
  const mjModel& m = robot.model();
  const web_detail::ReplayFrames frames =
      web_detail::replay_frames(m, recording.state(), options.rate);
  const web_detail::ReplayScene scene = web_detail::replay_scene(m);
  const web_detail::ReplayPlots plots = web_detail::replay_plots(recording, frames.time);

  const std::string title =
      options.title.empty() ? recording.directory().filename().string() : options.title;
  const double duration = frames.time.back() - frames.time.front();
  const double kept_rate =
      duration > 0.0 ? static_cast<double>(frames.time.size() - 1) / duration : options.rate;
  nlohmann::json data = scene.json;
  data["title"] = title;
  data["model"] = recording.model();
  data["status"] = recording.status();
  data["rate"] = options.rate;
  const std::vector<float> time(frames.time.begin(), frames.time.end());
  data["frames"] = {{"time", web_detail::base64_floats(time)},
                    {"pos", web_detail::base64_floats(frames.pos)},
                    {"quat", web_detail::base64_floats(frames.quat)}};
  data["events"] = nlohmann::json::array();
  for (const plot::RecordedEvent& e : recording.events())
    data["events"].push_back({{"t", e.t}, {"kind", e.kind}, {"message", e.message}});
  data["overlays"] = web_detail::replay_overlays(m, recording, frames.time);
  data["camera_poses"] = web_detail::replay_camera_poses(m, recording.state(), frames.time);
  data["plot_time"] = plots.json["plot_time"];
  data["plots"] = plots.json["plots"];

  FileWriter writer(out, FileWriter::Mode::replace, "replay page");
  writer.write(web_detail::page_head(title + " — mjarm replay"));
  writer.write("<script type=\"application/json\" id=\"mjarm-replay-data\">");
  writer.write(web_detail::script_safe(data.dump()));
  writer.write("</script>\n<script>");
  writer.write(web_detail::replay_bundle());
  writer.write("</script>\n</body>\n</html>\n");
  writer.commit();

  ReplayHtmlReport report;
  report.path = out;
  report.bytes = writer.bytes();
  report.frames = static_cast<int>(frames.time.size());
  report.state_rows = static_cast<std::int64_t>(recording.state().rows());
  report.rate = kept_rate;
  report.start_time = frames.time.front();
  report.end_time = frames.time.back();
  report.bodies = m.nbody;
  report.drawn_geoms = scene.drawn_geoms;
  report.meshes = scene.meshes;
  report.cameras = scene.cameras;
  report.plots = plots.count;
  report.largest_gap = frames.largest_gap;
  return report;
}

}  // namespace mjarm
