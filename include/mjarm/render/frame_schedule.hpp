#pragma once
/// @file
/// `FrameSchedule`: when a simulation loop owes the video a frame.

#include <cstdint>

namespace mjarm {

/// Frame times of a video in simulation time: frame k is due at t0 + k / fps. A run loop asks
/// after each step how many frames are due, renders once, and writes that many copies:
///
///     FrameSchedule schedule(30.0);
///     while (running) {
///       step(d);
///       if (const int n = schedule.frames_due(d.time); n > 0) {
///         renderer.render(d, camera, frame);
///         for (int k = 0; k < n; ++k) video.write(frame);
///       }
///     }
///
/// so the video plays at the speed of simulated time however physics and control periods relate
/// to the frame period (several frames are due at once when a step is longer than a frame).
/// No allocation, no exceptions after construction.
class FrameSchedule {
 public:
  /// @param fps        frames per second of the video, > 0 and finite
  /// @param start_time simulation time of frame 0 [s]
  /// @throws Error when @p fps is not a positive finite number or @p start_time is not finite.
  explicit FrameSchedule(double fps, double start_time = 0.0);

  /// Number of frames whose time is ≤ @p time [s] and that were not yet counted (0 when none);
  /// marks them as counted. A frame time within 1e-9 s after @p time counts as reached, so that
  /// steps of dt landing on k·dt with rounding error do not skip a frame.
  int frames_due(double time) noexcept;

  /// Simulation time of the next frame [s].
  double next_time() const noexcept;
  /// Frames counted so far.
  std::int64_t frames() const noexcept { return frames_; }
  /// [frames/s]
  double fps() const noexcept { return fps_; }

 private:
  double fps_;
  double start_;
  std::int64_t frames_ = 0;
};

}  // namespace mjarm
