#include "mjarm/tasks/pick_place/video.hpp"

#include <exception>

#include "mjarm/error.hpp"

namespace mjarm {

std::filesystem::path camera_video_path(const std::filesystem::path& path,
                                        const std::string& camera) {
  return path.parent_path() / (path.stem().string() + "_" + camera + path.extension().string());
}

namespace {

CameraSpec camera_of(const std::string& name, const std::string& tool) {
  if (name == "follow") return CameraSpec::follow(tool, 0.45, 150.0, -30.0);
  return CameraSpec::model_camera(name);
}

}  // namespace

PickPlaceVideoRun::PickPlaceVideoRun(const Robot& robot, const mjData& start,
                                     const PickPlaceVideo& video, const std::string& tool,
                                     const Eigen::Vector3d& target) {
  std::vector<std::string> names = video.cameras;
  if (names.empty()) names = {"front"};
  RunVideoOptions options = video.options;
  RenderMarker marker;
  marker.position = target;
  marker.radius = 0.008;
  options.render.markers.push_back(marker);
  if (video.tiled || names.size() == 1) {
    std::vector<CameraSpec> cameras;
    for (const std::string& name : names) cameras.push_back(camera_of(name, tool));
    videos_.push_back(std::make_unique<RunVideo>(robot, start, video.path, cameras, options));
    paths_.push_back(video.path);
    return;
  }
  for (const std::string& name : names) {
    const std::filesystem::path path = camera_video_path(video.path, name);
    videos_.push_back(
        std::make_unique<RunVideo>(robot, start, path, camera_of(name, tool), options));
    paths_.push_back(path);
  }
}

PickPlaceVideoRun::~PickPlaceVideoRun() = default;

void PickPlaceVideoRun::on_tick(const mjData& data) noexcept {
  for (const auto& video : videos_) video->on_tick(data);
}

void PickPlaceVideoRun::finish(const mjData& last) {
  std::string first;
  for (const auto& video : videos_) {
    try {
      video->finish(last);
    } catch (const Error& e) {
      if (first.empty()) first = e.what();
    }
  }
  if (!first.empty()) throw Error(first);
}

std::vector<std::filesystem::path> PickPlaceVideoRun::written() const {
  std::vector<std::filesystem::path> complete;
  for (const auto& video : videos_)
    if (video->complete()) complete.push_back(video->path());
  return complete;
}

std::int64_t PickPlaceVideoRun::frames() const noexcept {
  return videos_.empty() ? 0 : videos_.front()->frames();
}

}  // namespace mjarm
