#pragma once
/// @file
/// The video of a pick and place: one or several of the scene's cameras, tiled into one MP4 or
/// written one file each (`RunVideo`).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mjarm/tasks/run_video.hpp"
#include "mjarm/tasks/tick_observer.hpp"

namespace mjarm {

/// A video of a pick-and-place trial.
struct PickPlaceVideo {
  std::filesystem::path path;  ///< MP4 to write (overwritten); empty: no video
  /// Cameras of the scene ("front", "side", "top") or "follow" (the tool); empty: front.
  std::vector<std::string> cameras;
  /// With several cameras: one picture of options.width × options.height per camera, tiled
  /// into one file (true), or one file per camera, PATH's stem + "_" + camera (false).
  bool tiled = true;
  RunVideoOptions options;  ///< size of each camera's picture, frame rate, encoding, render
};

/// The video(s) of one trial while it runs: a `TickObserver` over one tiled `RunVideo` or one
/// per camera. Everything is checked when it is built (cameras, size, ffmpeg, the files).
class PickPlaceVideoRun final : public TickObserver {
 public:
  /// @param tool the site the "follow" camera keeps in view
  /// @param target drawn as a translucent green ball
  /// @throws Error for an unknown camera (naming the scene's), or as `RunVideo`.
  PickPlaceVideoRun(const Robot& robot, const mjData& start, const PickPlaceVideo& video,
                    const std::string& tool, const Eigen::Vector3d& target);
  ~PickPlaceVideoRun() override;

  void on_tick(const mjData& data) noexcept override;
  /// Finishes every file. @throws Error naming the first failure (each file is complete or not
  /// written, see `RunVideo::finish`).
  void finish(const mjData& last);
  /// The files being written.
  const std::vector<std::filesystem::path>& paths() const noexcept { return paths_; }
  /// The files written complete (after `finish`), in the order of `paths()`.
  std::vector<std::filesystem::path> written() const;
  /// Frames in each file.
  std::int64_t frames() const noexcept;

 private:
  std::vector<std::unique_ptr<RunVideo>> videos_;
  std::vector<std::filesystem::path> paths_;
};

/// The file of camera @p camera when each camera gets its own: PATH's stem + "_" + camera +
/// PATH's extension, in PATH's folder ("run.mp4", "top" → "run_top.mp4").
std::filesystem::path camera_video_path(const std::filesystem::path& path,
                                        const std::string& camera);

}  // namespace mjarm
