#pragma once
/// @file
/// `VideoWriter`: MP4 video from `Image` frames, encoded by Debian's `ffmpeg` reading raw RGB24
/// frames from a pipe.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/render/image.hpp"

namespace mjarm {

/// How the video is encoded.
struct VideoOptions {
  /// The ffmpeg executable: a name looked up on PATH, or a path (with a '/').
  std::string ffmpeg = "ffmpeg";
  /// ffmpeg's video encoder: "libx264" (H.264, Debian's ffmpeg has it) or "mpeg4" (MPEG-4
  /// part 2, built into every ffmpeg).
  std::string codec = "libx264";
  /// Quality: the constant rate factor for libx264 (0 lossless … 51 worst, 18–23 looks good),
  /// the quantiser scale -q:v for other encoders (1 best … 31 worst; 20 is mapped to 4).
  int quality = 20;
  /// How long ffmpeg may take to accept one frame, and to finalize the file after the last one
  /// [s], finite and > 0. Past it, ffmpeg is killed and the writer reports an error. After
  /// Ctrl-C or SIGTERM (see mjarm/interrupt.hpp) ffmpeg gets at most 3 s more instead.
  double timeout_s = 60.0;
};

constexpr auto declared_fields(const VideoOptions*) {
  using S = VideoOptions;
  return declare<S>(
      "video", field("ffmpeg", &S::ffmpeg, "the ffmpeg executable: a name on PATH or a path"),
      field("codec", &S::codec, "ffmpeg's video encoder (libx264, mpeg4)"),
      field("quality", &S::quality, "", Range::finite(),
            "libx264's constant rate factor (0 … 51), else -q:v (1 … 31; 20 is mapped to 4)"),
      field("timeout_s", &S::timeout_s, "s", Range::positive(),
            "how long ffmpeg may take to accept a frame or to finalize the file"));
}

/// Writes frames of one size to an MP4 file (H.264 or MPEG-4, yuv420p, so width and height must
/// be even). Frames are timed by their index: frame k is shown at k / fps seconds.
///
/// A complete video or none. ffmpeg writes a hidden temporary file beside @p path (through
/// `FileWriter`, which makes it and proves the folder writable), and only `close()` after the
/// last frame finalizes it: after ffmpeg exits 0, the file must exist, be non-empty and be a
/// complete MP4 (its top-level boxes tile the file and include `moov`), else `close()` throws
/// naming the path (a full disk is caught this way); a file that passed the check is synced and
/// renamed over @p path. Everything else writes no video, removes the temporary file and leaves
/// a file already at @p path as it was: ffmpeg failing or being stopped, an incomplete file,
/// `abandon()`, a writer destroyed without `close()` (a run that stopped early, an exception
/// unwinding past it), and `close()` while an interrupt is pending (SIGINT/SIGTERM under an
/// `InterruptGuard`, mjarm/interrupt.hpp: the frames stop where the run was cut, so `close()`
/// throws "video 'PATH' was not written: interrupted after N frames (the file already at
/// 'PATH' is kept)"). `complete()` says which happened. This is the one way every command's
/// video is written (`RunVideo`: run, docking, pick-place, replay, bimanual, demo).
///
/// ffmpeg is started with an argv array (never through a shell) and runs in its own process
/// group, so a Ctrl-C aimed at the program does not cut it short; it gets SIGKILL if mjarm dies
/// (PR_SET_PDEATHSIG: it never outlives the program, and a video being written when mjarm is
/// killed is lost). PR_SET_PDEATHSIG follows the thread that created the writer: create it on a
/// thread that outlives it (ffmpeg is killed when that thread ends). Frames go through a
/// non-blocking pipe: an ffmpeg that stops reading is killed after `VideoOptions::timeout_s` (3 s
/// after an interrupt) and `write` throws. A dead ffmpeg never kills the program with SIGPIPE:
/// `write` throws instead, with ffmpeg's own message.
///
/// Pushing frames at video rate from a run loop: see `FrameSchedule`.
class VideoWriter {
 public:
  /// Starts ffmpeg writing the video for @p path (replaced once complete; MP4 whatever the
  /// extension). ffmpeg is looked up first: when it is missing, nothing is created.
  /// @param width  frame width [pixels], even and ≥ 2
  /// @param height frame height [pixels], even and ≥ 2
  /// @param fps    frames per second of the video, > 0
  /// @throws Error, before any frame, when a size is zero, negative or odd, @p fps is not a
  ///         positive finite number, @p path cannot be created for writing (the message names
  ///         the path and the reason), or ffmpeg cannot be found (the message names Debian's
  ///         package `ffmpeg`) or started.
  VideoWriter(const std::filesystem::path& path, int width, int height, double fps,
              VideoOptions options = {});
  /// Abandons the video if `close()` was not called (see `abandon`); never throws.
  ~VideoWriter();
  VideoWriter(VideoWriter&&) noexcept;
  VideoWriter& operator=(VideoWriter&&) noexcept;
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends one frame. Allocates nothing.
  /// @throws Error when the frame's size differs from the video's, after `close()`, when
  ///         ffmpeg has stopped (its exit status and message are in the error), or when it did
  ///         not take the frame within the timeout (it is then killed); the writer is then
  ///         closed.
  void write(const Image& frame);

  /// Ends the input, waits for ffmpeg to finalize the file, and checks the file. Idempotent.
  /// @throws Error with ffmpeg's message when it exits with a failure, does not exit within the
  ///         timeout (it is then killed), or leaves a file that is not a complete MP4; and when
  ///         an interrupt is pending (no video is written then).
  void close();

  /// Stops ffmpeg and removes what it wrote: no video is written, a file already at `path()`
  /// keeps its content. For a video that cannot be complete (its run failed). Idempotent.
  void abandon() noexcept;

  /// False after `close()` or `abandon()`, after a failed `write`, and for a moved-from writer.
  bool is_open() const noexcept;
  /// True once the finalized, checked video is at `path()` (after a successful `close()`).
  bool complete() const noexcept;
  /// Frames written so far.
  std::int64_t frames() const noexcept;
  /// Where the video goes.
  const std::filesystem::path& path() const noexcept;
  int width() const noexcept;   ///< [pixels]
  int height() const noexcept;  ///< [pixels]
  double fps() const noexcept;  ///< [frames/s]

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjarm
