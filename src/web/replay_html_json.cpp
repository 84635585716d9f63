#include "mjarm/web/replay_html_json.hpp"

namespace mjarm {

nlohmann::ordered_json replay_html_json(const ReplayHtmlReport& report,
                                        const std::filesystem::path& recording) {
  nlohmann::ordered_json doc;
  doc["recording"] = recording.string();
  doc["path"] = report.path.string();
  doc["bytes"] = report.bytes;
  doc["frames"] = report.frames;
  doc["state_rows"] = report.state_rows;
  doc["rate"] = report.rate;
  doc["start_time"] = report.start_time;
  doc["end_time"] = report.end_time;
  doc["largest_gap"] = report.largest_gap;
  doc["bodies"] = report.bodies;
  doc["drawn_geoms"] = report.drawn_geoms;
  doc["meshes"] = report.meshes;
  doc["cameras"] = report.cameras;
  doc["plots"] = report.plots;
  doc["decimated"] = report.decimated;
  doc["decimation"] = report.decimation;
  doc["warnings"] = report.warnings;
  return doc;
}

}  // namespace mjarm
