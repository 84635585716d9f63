#include "mjarm/tasks/run_video.hpp"

#include <cmath>
#include <exception>
#include <string>
#include <utility>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

// the cheap checks first, so that a bad size or rate fails before OpenGL and ffmpeg start
const RunVideoOptions& checked(const RunVideoOptions& options) {
  const std::string size = std::to_string(options.width) + "×" + std::to_string(options.height);
  if (options.width < 2 || options.height < 2)
    throw Error("video size must be at least 2×2 pixels, got " + size);
  if (options.width % 2 != 0 || options.height % 2 != 0)
    throw Error("video size must be even in both directions (yuv420p MP4), got " + size);
  if (!std::isfinite(options.fps) || !(options.fps > 0.0))
    throw Error("video frame rate must be a finite number > 0 frames/s, got " +
                number_text(options.fps));
  return options;
}

}  // namespace

RunVideo::RunVideo(const Robot& robot, const mjData& start, const std::filesystem::path& path,
                   CameraSpec camera, const RunVideoOptions& options)
    : RunVideo(robot, start, path, std::vector<CameraSpec>{std::move(camera)}, options, 1) {}

RunVideo::RunVideo(const Robot& robot, const mjData& start, const std::filesystem::path& path,
                   std::vector<CameraSpec> cameras, const RunVideoOptions& options, int columns)
    : path_(path),
      renderer_(robot, checked(options).width, options.height, std::move(cameras), columns,
                options.render),
      frame_(renderer_.render(start)),  // checks the cameras before ffmpeg starts
      schedule_(options.fps, start.time),
      writer_(path, renderer_.width(), renderer_.height(), options.fps, options.encoding) {
  // frame 0 is the start state
  for (int due = schedule_.frames_due(start.time); due > 0; --due) writer_.write(frame_);
}

void RunVideo::write_due(const mjData& data) {
  const int due = schedule_.frames_due(data.time);
  if (due == 0) return;
  renderer_.render(data, frame_);
  for (int k = 0; k < due; ++k) writer_.write(frame_);
}

void RunVideo::on_tick(const mjData& data) noexcept {
  if (finished_ || !error_.empty()) return;
  try {
    write_due(data);
  } catch (const std::exception& e) {
    error_ = e.what();
    writer_.abandon();  // a video with frames missing is no video
  }
}

void RunVideo::finish(const mjData& last) {
  if (finished_) return;
  finished_ = true;
  if (error_.empty()) {
    try {
      write_due(last);
    } catch (const std::exception& e) {
      error_ = e.what();
    }
  }
  if (!error_.empty()) {
    writer_.abandon();
    throw Error("video " + path_.string() + ": " + error_);
  }
  writer_.close();
}

}  // namespace mjarm
