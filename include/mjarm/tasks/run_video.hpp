#pragma once
/// @file
/// `RunVideo`: an MP4 of a simulated run, rendered headless at a fixed frame rate on the
/// simulation clock while the run goes (a `TickObserver`).

#include <mujoco/mujoco.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/model/robot.hpp"
#include "mjarm/render/camera.hpp"
#include "mjarm/render/frame_schedule.hpp"
#include "mjarm/render/image.hpp"
#include "mjarm/render/offscreen_renderer.hpp"
#include "mjarm/render/tiled_renderer.hpp"
#include "mjarm/render/video_writer.hpp"
#include "mjarm/tasks/tick_observer.hpp"

namespace mjarm {

/// Size, rate and look of a run's video.
struct RunVideoOptions {
  int width = 640;        ///< [pixels], even and ≥ 2 (yuv420p)
  int height = 480;       ///< [pixels], even and ≥ 2
  double fps = 30.0;      ///< frames per simulated second, > 0
  VideoOptions encoding;  ///< ffmpeg executable, codec, quality
  RenderOptions render;   ///< shadows, groups, marker balls (a pick point)
};

/// Renders the states a run passes through into an MP4 at `fps` frames per simulated second:
/// frame k shows the state of the last control tick at or before t₀ + k/fps (t₀ = the start
/// state's time), so a run from t₀ to t_end gives ⌊(t_end − t₀)·fps⌋ + 1 frames and the video
/// plays at the speed of simulated time. Frames are rendered only when due (`FrameSchedule`),
/// not every physics step; a frame due several times over (a control period longer than the
/// frame period) is written that many times.
///
/// Rendering only reads the state (the renderer copies it), so a run with a video produces the
/// same figures bit for bit as one without. A complete video or none (see `VideoWriter`): only
/// `finish` after the run writes it; a failed frame, a run ended by an exception (the destructor)
/// or by an interrupt writes no video and leaves a file already at the path as it was.
class RunVideo final : public TickObserver {
 public:
  /// Creates the renderer, renders frame 0 from @p start (which checks the camera) and starts
  /// ffmpeg writing @p path — so every mistake shows before the run.
  /// @param robot  the simulated model (shared)
  /// @param start  the state the run starts from, kinematics computed (mj_forward)
  /// @param camera where the video is seen from (model, free or follow camera)
  /// @throws Error for a size that is zero, negative or odd, a frame rate that is not positive,
  ///         a camera, site or body the model does not have (the message lists those it has),
  ///         a path that cannot be written (naming it and why), ffmpeg missing (naming Debian's
  ///         package `ffmpeg`), or no headless OpenGL.
  RunVideo(const Robot& robot, const mjData& start, const std::filesystem::path& path,
           CameraSpec camera, const RunVideoOptions& options = {});

  /// Several cameras at once: each frame is a grid of pictures of options.width ×
  /// options.height, one per camera (`TiledRenderer`; @p columns 0 = one row up to three
  /// cameras, else ⌈√n⌉ columns). The video is columns·width × rows·height pixels.
  /// @throws Error as above, and for an empty camera list.
  RunVideo(const Robot& robot, const mjData& start, const std::filesystem::path& path,
           std::vector<CameraSpec> cameras, const RunVideoOptions& options = {}, int columns = 0);

  /// Writes the frames due at data.time. Never throws: the first failure is kept in `error()`,
  /// no more frames are rendered and no video is written (`complete()` is false; an old file at
  /// the path is left as it was); the run goes on.
  void on_tick(const mjData& data) noexcept override;

  /// Writes the frames due at @p last (the state the run ended in) and finalizes the file.
  /// Idempotent.
  /// @throws Error when a frame could not be written during the run, ffmpeg failed to finish
  ///         the file (its message), or an interrupt is pending (`VideoWriter::close`): no video
  ///         is written then.
  void finish(const mjData& last);

  /// Frames written so far.
  std::int64_t frames() const noexcept { return writer_.frames(); }
  /// True once a finalized, checked MP4 is at `path()` (see `VideoWriter::complete`).
  bool complete() const noexcept { return writer_.complete(); }
  const std::filesystem::path& path() const noexcept { return path_; }
  /// The (first) camera.
  const CameraSpec& camera() const noexcept { return renderer_.cameras().front(); }
  /// Every camera, in tile order.
  const std::vector<CameraSpec>& cameras() const noexcept { return renderer_.cameras(); }
  /// The first failure during the run (empty when none).
  const std::string& error() const noexcept { return error_; }
  int width() const noexcept { return renderer_.width(); }    ///< of the video [pixels]
  int height() const noexcept { return renderer_.height(); }  ///< of the video [pixels]
  double fps() const noexcept { return schedule_.fps(); }     ///< [frames/s]

 private:
  void write_due(const mjData& data);

  std::filesystem::path path_;
  TiledRenderer renderer_;
  Image frame_;
  FrameSchedule schedule_;
  VideoWriter writer_;
  std::string error_;
  bool finished_ = false;
};

}  // namespace mjarm
