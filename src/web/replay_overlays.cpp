#include "replay_overlays.hpp"

#include "base64.hpp"

namespace mjarm::web_detail {
namespace {

constexpr const char* kPoseAxes[] = {"x", "y", "z", "qw", "qx", "qy", "qz"};

// "ee." or "ref." pose columns at the frames, frame-major; empty when a column is missing
std::vector<float> poses(const std::map<std::string, std::vector<double>>& task,
                         const std::string& prefix, std::size_t frames) {
  std::vector<const std::vector<double>*> columns;
  for (const char* c : kPoseAxes) {
    const auto it = task.find(prefix + c);
    if (it == task.end()) return {};
    columns.push_back(&it->second);
  }
  std::vector<float> out;
  out.reserve(frames * 7);
  for (std::size_t f = 0; f < frames; ++f)
    for (const std::vector<double>* column : columns)
      out.push_back(static_cast<float>((*column)[f]));
  return out;
}

}  // namespace

std::vector<std::string> overlay_task_columns() {
  std::vector<std::string> columns;
  for (const char* prefix : {"ee.", "ref."})
    for (const char* c : kPoseAxes) columns.push_back(std::string(prefix) + c);
  return columns;
}

nlohmann::json replay_overlays(const ReplayFrames& frames,
                               const std::map<std::string, std::vector<double>>& task) {
  nlohmann::json out;
  const std::vector<float> tool = poses(task, "ee.", frames.time.size());
  const std::vector<float> target = poses(task, "ref.", frames.time.size());
  if (!tool.empty()) out["tool"] = base64_floats(tool);
  if (!target.empty()) out["target"] = base64_floats(target);
  out["contacts"] = {{"offsets", base64_uints(frames.contact_offsets)},
                     {"points", base64_floats(frames.contacts)}};
  return out;
}

}  // namespace mjarm::web_detail
